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

const SrgbTable& srgb_table() {
  static const SrgbTable table = [] {
    const auto code = [](float v) { return static_cast<int>(std::lround(to_srgb(v) * 255.0f)); };
    SrgbTable t{};
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
      t.bucket_code[b] =
          static_cast<std::uint8_t>(code(std::bit_cast<float>(b << SrgbTable::kDropBits)));
    return t;
  }();
  return table;
}

}  // namespace shadowvol::shading
