#include "accel/near_plane.h"

#include <array>
#include <cassert>
#include <cstddef>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "core/clip_polygon.h"

namespace shadowvol {
namespace {

// A cap cut by at most two planes: 3 + 2 vertices.
constexpr int kMaxPolygon = 5;

// The near plane z = w of clip space, in eye-relative space: N . X = z_clip - w_clip, positive
// on the eye's side.
glm::dvec4 near_plane(const glm::mat4& view_proj) {
  return glm::transpose(glm::dmat4(view_proj)) * glm::dvec4(0.0, 0.0, 1.0, -1.0);
}

glm::dvec4 affine(const glm::vec4& point) {
  const glm::dvec4 p(point);
  return p.w != 0.0 ? p / p.w : p;
}

}  // namespace

std::array<glm::vec3, 4> near_rectangle(const glm::mat4& inv_view_proj) {
  std::array<glm::vec3, 4> rect;
  for (int i = 0; i < 4; ++i) {
    const glm::vec4 c = inv_view_proj * glm::vec4(i == 1 || i == 2 ? 1 : -1, i >= 2 ? 1 : -1, 1, 1);
    rect[i] = glm::vec3(c) / c.w;
  }
  return rect;
}

bool may_shadow_near_plane(const glm::vec3& centre, float radius,
                           const std::array<glm::vec3, 4>& rect, const glm::vec4& light) {
  const glm::vec3 inside = (rect[0] + rect[1] + rect[2] + rect[3]) * 0.25f;
  const bool point = light.w != 0.0f;
  const glm::vec3 l = glm::vec3(light) / (point ? light.w : 1.0f);
  auto outside = [&](glm::vec3 n, glm::vec3 on, glm::vec3 reference) {
    const float len = glm::length(n);
    if (len < 1e-12f) return false;  // degenerate plane: no verdict
    n /= len;
    if (glm::dot(n, reference - on) > 0.0f) n = -n;  // outward: away from the reference point
    return glm::dot(n, centre - on) > radius;
  };
  // The rectangle's plane bounds the hull on the side away from the light.
  const glm::vec3 rect_normal = glm::cross(rect[1] - rect[0], rect[3] - rect[0]);
  const glm::vec3 towards = point ? l - inside : l;
  if (glm::dot(rect_normal, towards) == 0.0f) return true;  // light in the near plane
  if (outside(rect_normal, rect[0], rect[0] + towards)) return false;
  for (int i = 0; i < 4; ++i) {
    const glm::vec3 a = rect[i], b = rect[(i + 1) % 4];
    const glm::vec3 n = glm::cross(b - a, point ? l - a : l);
    if (outside(n, a, inside + towards * 1e-3f)) return false;
  }
  return true;
}

bool near_plane_prefill_possible(const glm::vec4& light, const glm::mat4& view_proj) {
  return glm::dot(near_plane(view_proj), affine(light)) != 0.0;
}

void append_near_plane_prefill(const PrimitiveList& light_caps, const glm::mat4& model, int mirror,
                               const glm::vec4& light, const glm::mat4& view_proj,
                               std::vector<glm::vec4>& triangles,
                               std::vector<std::int32_t>& weights,
                               std::vector<std::uint32_t>* parts) {
  assert(parts == nullptr || light_caps.parts.size() == light_caps.size());
  const glm::dmat4 to_clip(view_proj);
  const glm::dvec4 near = near_plane(view_proj);
  const glm::dvec4 l = affine(light);
  const double light_side = glm::dot(near, l);
  assert(light_side != 0.0);  // near_plane_prefill_possible
  const double s = light_side > 0.0 ? 1.0 : -1.0;
  const bool point = l.w != 0.0;
  const glm::dmat4 to_world(model);
  for (std::size_t c = 0; c < light_caps.size(); ++c) {
    std::array<glm::dvec4, kMaxPolygon> poly;
    int n = 0;
    for (int k = 0; k < kTriangleCorners; ++k)
      poly[n++] = to_world * glm::dvec4(light_caps.vertices[c * kTriangleCorners + k]);
    // Only the part on the light's side of the near plane, and not beyond a point light, can
    // meet a segment from the light to the near plane.
    clip_polygon(poly, n, [&](const glm::dvec4& v) { return s * glm::dot(near, v); });
    if (point && n >= 3)  // homogeneous: a clamped volume's caps have w other than 1
      clip_polygon(poly, n,
                   [&](const glm::dvec4& v) { return s * (light_side * v.w - glm::dot(near, v)); });
    if (n < 3) continue;
    // Where the line from the light through v meets the near plane: (N.v) l - (N.l) v, a linear
    // map of v. Its w has the sign of -s; negated by s, every vertex lands in front of the eye.
    glm::vec4 projected[kMaxPolygon];
    for (int i = 0; i < n; ++i) {
      const glm::dvec4 on_near = -s * (glm::dot(near, poly[i]) * l - light_side * poly[i]);
      glm::dvec4 clip_space = to_clip * on_near;
      clip_space.z = 0.5 * clip_space.w;  // counts, not depth: keep it inside the depth range
      projected[i] = glm::vec4(clip_space);
    }
    // Seen from the eye, the projection turns the way the cap turns seen from the light exactly
    // when both lie on the same side of the near plane (s = 1).
    const std::int32_t weight = light_caps.weights[c] * mirror * static_cast<std::int32_t>(s);
    for (int i = 1; i + 1 < n; ++i) {
      triangles.insert(triangles.end(), {projected[0], projected[i], projected[i + 1]});
      weights.push_back(weight);
      if (parts != nullptr) parts->push_back(light_caps.parts[c]);
    }
  }
}

}  // namespace shadowvol
