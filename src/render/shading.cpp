#include "render/shading.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace shadowvol::shading {

glm::vec3 background(int y, int h) {
  const float fade = 1.0f - float(y) / float(h);
  return kBackgroundBottom + (kBackgroundTop - kBackgroundBottom) * fade;
}

float to_srgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t to_srgb8(float linear) {
  // Floats in [0, 1) fall into buckets by their top bits (2^15 neighbouring floats each), each
  // narrower than the gap between two codes' first values, so that a bucket's code is the code
  // of its least float, or one more from where the next code begins (steps[code]).
  constexpr int kDropBits = 15;
  constexpr std::uint32_t kOne = 0x3f800000u;  // the bits of 1.0f
  struct Table {
    std::array<std::uint8_t, (kOne >> kDropBits)> bucket_code;
    std::array<float, 256> steps;  // steps[k]: the least float whose code is more than k
  };
  static const Table table = [] {
    const auto code = [](float v) { return static_cast<int>(std::lround(to_srgb(v) * 255.0f)); };
    Table t{};
    for (int k = 0; k < 255; ++k) {
      float lo = 0.0f, hi = 1.0f;  // code(lo) <= k < code(hi)
      for (;;) {
        const float mid = lo + (hi - lo) * 0.5f;
        if (mid <= lo || mid >= hi) break;  // lo and hi are neighbouring floats
        (code(mid) > k ? hi : lo) = mid;
      }
      t.steps[static_cast<std::size_t>(k)] = hi;
    }
    t.steps[255] = INFINITY;
    for (std::uint32_t b = 0; b < t.bucket_code.size(); ++b)
      t.bucket_code[b] = static_cast<std::uint8_t>(code(std::bit_cast<float>(b << kDropBits)));
    return t;
  }();
  if (!(linear > 0.0f)) return 0;  // NaN too, as to_srgb's clamp makes it
  if (!(linear < 1.0f)) return 255;
  const std::uint8_t c = table.bucket_code[std::bit_cast<std::uint32_t>(linear) >> kDropBits];
  return static_cast<std::uint8_t>(c + (linear >= table.steps[c]));
}

}  // namespace shadowvol::shading
