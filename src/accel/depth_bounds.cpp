#include "accel/depth_bounds.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/clip_polygon.h"
#include "core/shapes.h"
#include "core/topology.h"
#include "core/volume.h"

namespace shadowvol {
namespace {

// Whether the segment from p towards the light (to it, for a point light; along it without end,
// for a directional one) meets the box [lo, hi]: the slab test, in double.
bool sees_box_towards_light(const glm::vec3& p, const glm::vec4& light, const glm::vec3& lo,
                            const glm::vec3& hi) {
  const bool point = light.w != 0.0f;
  const glm::dvec3 from(p);
  const glm::dvec3 d = point ? glm::dvec3(light) / double(light.w) - from : glm::dvec3(light);
  double t0 = 0.0, t1 = point ? 1.0 : INFINITY;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (from[k] < lo[k] || from[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - from[k]) / d[k], b = (hi[k] - from[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

}  // namespace

glm::vec4 bounded_far_plane(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& reach_lo,
                            const glm::vec3& reach_hi, const glm::vec4& light) {
  const glm::dvec3 centre = (glm::dvec3(lo) + glm::dvec3(hi)) * 0.5;
  const bool point = light.w != 0.0f;
  const glm::dvec3 l = glm::dvec3(light) / (point ? double(light.w) : 1.0);
  glm::dvec3 n = point ? centre - l : -l;
  if (!(glm::length(n) > 0.0)) return kPlaneAtInfinity;
  n = glm::normalize(n);
  auto corner = [](const glm::vec3& a, const glm::vec3& b, int i) {
    return glm::dvec3(i & 1 ? b.x : a.x, i & 2 ? b.y : a.y, i & 4 ? b.z : a.z);
  };
  constexpr double kMinCosine = 0.1;
  for (int i = 0; i < 8 && point; ++i) {
    const glm::dvec3 r = corner(lo, hi, i) - l;
    if (!(glm::dot(n, r) >= kMinCosine * glm::length(r)) || glm::length(r) == 0.0)
      return kPlaneAtInfinity;
  }
  double farthest = -INFINITY;
  for (int i = 0; i < 8; ++i)
    farthest = std::max(farthest, glm::dot(n, corner(reach_lo, reach_hi, i)));
  const double margin = 1e-2 * glm::length(glm::dvec3(reach_hi) - glm::dvec3(reach_lo)) + 1e-3;
  return glm::vec4(glm::vec3(n), float(-(farthest + margin)));
}

raster::DepthBounds box_volume_depth_bounds(const glm::vec3& lo, const glm::vec3& hi,
                                            const glm::vec4& light, const glm::vec4& far_plane,
                                            const glm::mat4& view_proj,
                                            const std::array<glm::vec3, 4>& near_rect) {
  const raster::DepthBounds all{0.0f, 1.0f};
  if (light.w != 0.0f && sees_box_towards_light(glm::vec3(light) / light.w, light, lo, hi))
    return all;  // a point light in or on the box: its volume is everything around it
  const Mesh box = make_box(lo, hi);
  const Topology topology = build_topology(box);
  VolumeScratch scratch;
  VolumeBuffer volume;
  build_volume(topology, light, {Generator::standard, true, far_plane}, scratch, volume);
  raster::DepthBounds b{1.0f, 0.0f};
  auto add_triangle = [&](const glm::vec4& a, const glm::vec4& c, const glm::vec4& d) {
    std::array<glm::vec4, 9> v{view_proj * a, view_proj * c, view_proj * d};
    int n = 3;
    // The frustum: before the near plane (z <= w), within x and y (|x|, |y| <= w).
    const auto planes = {glm::vec4(0, 0, -1, 1), glm::vec4(-1, 0, 0, 1), glm::vec4(1, 0, 0, 1),
                         glm::vec4(0, -1, 0, 1), glm::vec4(0, 1, 0, 1)};
    for (const glm::vec4& plane : planes) {
      clip_polygon(v, n, [&plane](const glm::vec4& x) { return glm::dot(plane, x); });
      if (n < 3) return;
    }
    for (int i = 0; i < n; ++i) {
      const float depth = v[i].w > 0.0f ? std::clamp(v[i].z / v[i].w, 0.0f, 1.0f) : 0.0f;
      b.zmin = std::min(b.zmin, depth);
      b.zmax = std::max(b.zmax, depth);
    }
  };
  auto add = [&](const PrimitiveList& list, int corners) {
    for (std::size_t p = 0; p < list.size(); ++p) {
      const glm::vec4* v = &list.vertices[p * static_cast<std::size_t>(corners)];
      for (int t = 0; t < (corners == kQuadCorners ? 2 : 1); ++t)
        add_triangle(v[kQuadTriangles[3 * t]], v[kQuadTriangles[3 * t + 1]],
                     v[kQuadTriangles[3 * t + 2]]);
    }
  };
  add(volume.sides, kQuadCorners);
  add(volume.light_caps, kTriangleCorners);
  add(volume.dark_caps, kTriangleCorners);
  for (const glm::vec3& c : near_rect)
    if (glm::dot(glm::vec3(far_plane), c) + far_plane.w <= 0.0f &&
        sees_box_towards_light(c, light, lo, hi))
      b = {std::min(b.zmin, 1.0f), 1.0f};
  if (b.zmin > b.zmax) return b;  // out of view
  constexpr float kSlack = 1e-5f;
  return {std::max(0.0f, b.zmin - kSlack), std::min(1.0f, b.zmax + kSlack)};
}

}  // namespace shadowvol
