#include "accel/light_reach.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace shadowvol {
namespace {

// Along one axis of the image: the slopes a / c (a across, c the distance ahead) of the rays
// through the eye that meet the circle of centre (a0, c0) and radius r, for a circle wholly
// ahead (c0 - r > 0): the roots of (a0 - t c0)^2 = r^2 (1 + t^2), the two tangent lines.
void tangent_slopes(double a0, double c0, double r, double& lo, double& hi) {
  const double k = c0 * c0 - r * r;  // > 0
  const double root = r * std::sqrt(a0 * a0 + k);
  lo = (a0 * c0 - root) / k;
  hi = (a0 * c0 + root) / k;
}

}  // namespace

LightReach light_reach(const glm::vec4& light, float range, const glm::mat4& view,
                       const glm::mat4& proj, float near, int width, int height) {
  LightReach reach;
  reach.limited = light.w != 0.0f && std::isfinite(range);
  reach.scissor = {0, 0, width, height};
  if (!reach.limited) return reach;
  const glm::dvec3 c =
      glm::dvec3(glm::dmat4(view) * glm::dvec4(glm::dvec3(light) / double(light.w), 1.0));
  const double r = range;
  const double ahead = -c.z;  // the centre's distance ahead of the eye
  // Depths: near / distance, from the nearest point of the sphere ahead to the farthest.
  const double nearest = ahead - r, farthest = ahead + r;
  if (farthest <= near) {  // wholly behind the near plane: nothing to see
    reach.scissor = {};
    reach.depth = {1.0f, 0.0f};
    return reach;
  }
  constexpr double kHair = 1e-5;
  reach.depth.zmin = static_cast<float>(std::max(0.0, near / farthest * (1.0 - kHair)));
  reach.depth.zmax =
      nearest > near ? static_cast<float>(std::min(1.0, near / nearest * (1.0 + kHair))) : 1.0f;
  // NDC per axis: x = sx * a / c (sx = proj[0][0]), y = sy * b / c.
  const double sx = proj[0][0], sy = proj[1][1];
  double ndc[2][2];  // [axis][lo, hi]
  if (nearest > near) {
    tangent_slopes(c.x, ahead, r, ndc[0][0], ndc[0][1]);
    tangent_slopes(c.y, ahead, r, ndc[1][0], ndc[1][1]);
  } else {
    // The cube's corners ahead of the near plane, and where its edges along z cross it: the
    // hull of the cube's part in front of the near plane, projected.
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    const double front = std::max(nearest, double(near));
    for (const double d : {front, farthest})
      for (const double a : {c.x - r, c.x + r})
        for (const double b : {c.y - r, c.y + r}) {
          lo[0] = std::min(lo[0], a / d), hi[0] = std::max(hi[0], a / d);
          lo[1] = std::min(lo[1], b / d), hi[1] = std::max(hi[1], b / d);
        }
    for (int axis = 0; axis < 2; ++axis) ndc[axis][0] = lo[axis], ndc[axis][1] = hi[axis];
  }
  for (int k = 0; k < 2; ++k) ndc[0][k] *= sx, ndc[1][k] *= sy;
  // Pixel i's centre i + 0.5 at window x = (ndc + 1) w / 2: the centres within the range, and a
  // pixel more on each side for the rounding of the rasterizer's and this arithmetic.
  const auto first = [](double window) { return std::ceil(window - 0.5) - 1.0; };
  const auto last = [](double window) { return std::floor(window - 0.5) + 1.0; };
  const double x0 = first((ndc[0][0] + 1.0) * 0.5 * width),
               x1 = last((ndc[0][1] + 1.0) * 0.5 * width);
  const double y0 = first((1.0 - ndc[1][1]) * 0.5 * height),
               y1 = last((1.0 - ndc[1][0]) * 0.5 * height);
  const auto clamp = [](double v, int hi) {
    return static_cast<int>(std::clamp(v, 0.0, double(hi)));
  };
  reach.scissor = {clamp(x0, width), clamp(y0, height), clamp(x1 + 1.0, width),
                   clamp(y1 + 1.0, height)};
  if (reach.scissor.empty()) reach.scissor = {};
  return reach;
}

void mark_beyond_reach(std::span<std::uint8_t> mask, std::span<const float> depth,
                       const glm::mat4& inv_view_proj, const glm::vec4& light, float range,
                       const LightReach& reach, int width, int height) {
  if (!reach.limited) return;
  const glm::vec3 centre = glm::vec3(light) / light.w;
  const float range2 = range * range;
  const raster::PixelRect& r = reach.scissor;
  tbb::parallel_for(0, height, [&](int y) {
    std::uint8_t* row = mask.data() + static_cast<std::size_t>(y) * width;
    const float* z = depth.data() + static_cast<std::size_t>(y) * width;
    if (r.empty() || y < r.y0 || y >= r.y1) {  // outside the scissor: beyond the range
      std::fill(row, row + width, std::uint8_t{1});
      return;
    }
    std::fill(row, row + r.x0, std::uint8_t{1});
    std::fill(row + r.x1, row + width, std::uint8_t{1});
    // The pixel's point, homogeneous: base + step x + along_z depth (ndc x linear in x).
    const float ndc_y = 1.0f - (float(y) + 0.5f) / float(height) * 2.0f;
    const glm::vec4 base = inv_view_proj[0] * (1.0f / float(width) - 1.0f) +
                           inv_view_proj[1] * ndc_y + inv_view_proj[3];
    const glm::vec4 step = inv_view_proj[0] * (2.0f / float(width));
    const glm::vec4 along_z = inv_view_proj[2];
    for (int x = r.x0; x < r.x1; ++x) {
      const glm::vec4 q = base + step * float(x) + along_z * z[x];
      const glm::vec3 d = glm::vec3(q) / q.w - centre;
      // No surface (depth 0, a point at infinity) is beyond every range.
      if (!(glm::dot(d, d) < range2)) row[x] = 1;
    }
  });
}

bool box_meets_sphere(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& centre,
                      float range) {
  if (lo.x > hi.x) return false;
  const glm::dvec3 nearest = glm::clamp(glm::dvec3(centre), glm::dvec3(lo), glm::dvec3(hi));
  const glm::dvec3 d = nearest - glm::dvec3(centre);
  return glm::dot(d, d) <= double(range) * double(range);
}

}  // namespace shadowvol
