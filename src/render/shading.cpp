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

glm::vec3 sample_texture(const Texture& texture, glm::vec2 uv) {
  const int w = texture.width, h = texture.height;
  if (w <= 0 || h <= 0 || texture.rgba.size() != std::size_t(w) * std::size_t(h) * 4 ||
      !std::isfinite(uv.x) || !std::isfinite(uv.y))
    return glm::vec3(1.0f);
  static const std::array<float, 256> linear = [] {
    std::array<float, 256> t{};
    for (int k = 0; k < 256; ++k) {
      const float c = float(k) / 255.0f;
      t[std::size_t(k)] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    }
    return t;
  }();
  // Texel centres at (i + 0.5) / w; repeat: the coordinate's fraction.
  const float x = (uv.x - std::floor(uv.x)) * float(w) - 0.5f;
  const float y = (1.0f - (uv.y - std::floor(uv.y))) * float(h) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const auto wrap = [](float i, int n) { return int(((long long)(i) % n + n) % n); };
  const int x0 = wrap(fx, w), x1 = wrap(fx + 1.0f, w), y0 = wrap(fy, h), y1 = wrap(fy + 1.0f, h);
  const auto texel = [&](int xi, int yi) {
    const std::uint8_t* p = &texture.rgba[(std::size_t(yi) * std::size_t(w) + std::size_t(xi)) * 4];
    return glm::vec3(linear[p[0]], linear[p[1]], linear[p[2]]);
  };
  return (texel(x0, y0) * (1.0f - tx) + texel(x1, y0) * tx) * (1.0f - ty) +
         (texel(x0, y1) * (1.0f - tx) + texel(x1, y1) * tx) * ty;
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
