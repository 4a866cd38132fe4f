#include "accel/slices.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace shadowvol {

Slices make_slices(const glm::mat4& view_proj, const glm::vec4& light, int width, int height,
                   int count) {
  Slices s;
  const glm::dvec4 l = glm::dmat4(view_proj) * glm::dvec4(light);
  const glm::dvec2 away(-l.x, -l.y);
  // A light on the view's axis: shadows spread every way from the centre; any direction will do.
  if (glm::length(away) > 1e-12 * glm::length(glm::dvec4(l))) s.across = glm::normalize(away);
  const double extent = std::abs(s.across.x) + std::abs(s.across.y);  // of the image's corners
  s.count = count;
  s.first = -extent;
  s.width = 2.0 * extent / count;
  s.margin = 1.5 * (std::abs(s.across.x) * 2.0 / width + std::abs(s.across.y) * 2.0 / height);
  return s;
}

LayerRange Slices::of(double lo, double hi) const {
  const double a = std::floor((lo - margin - first) / width);
  const double b = std::floor((hi + margin - first) / width);
  if (b < 0.0 || a > count - 1) return {};
  return {static_cast<std::uint16_t>(std::max(a, 0.0)),
          static_cast<std::uint16_t>(std::min<double>(b, count - 1))};
}

raster::ScreenStrip Slices::strip(int first_strip, int last_strip) const {
  raster::ScreenStrip strip;
  strip.across = glm::vec2(across);
  if (first_strip > 0) strip.lo = static_cast<float>(first + first_strip * width);
  if (last_strip < count - 1) strip.hi = static_cast<float>(first + (last_strip + 1) * width);
  return strip;
}

}  // namespace shadowvol
