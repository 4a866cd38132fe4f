#include "accel/near_plane.h"

#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "raster/raster.h"

namespace shadowvol {

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

void append_near_plane_prefill(std::span<const glm::vec4> triangles,
                               std::span<const std::int32_t> weights,
                               std::span<const std::uint32_t> parts, std::vector<glm::vec4>& out,
                               std::vector<std::int32_t>& out_weights,
                               std::vector<std::uint32_t>* out_parts,
                               std::vector<glm::vec4>& apexes) {
  assert(triangles.size() == 3 * weights.size());
  assert(parts.empty() || (parts.size() == weights.size() && out_parts != nullptr));
  // Drawn with z between 0 and w, or w and 0 behind the eye, so that the near plane, the first
  // plane the clipper cuts by, leaves the fan whole; x, y and w, all the other planes and the
  // snapping read, stay the clipper's own.
  auto drawn = [](glm::vec4 v) {
    v.z = v.w >= 0.0f ? 0.5f * v.w : 1.5f * v.w;
    return v;
  };
  constexpr glm::vec4 kUnset(0.0f);
  apexes.clear();
  const std::size_t first = out_weights.size();
  for (std::size_t t = 0; t < weights.size(); ++t) {
    glm::vec4 leaves, returns;
    if (!raster::near_plane_cut(&triangles[3 * t], leaves, returns)) continue;
    const std::uint32_t part = parts.empty() ? 0 : parts[t];
    if (apexes.size() <= part) apexes.resize(part + 1, kUnset);
    for (const glm::vec4& v : {leaves, returns})  // in view, so that the fan stays small
      if (apexes[part] == kUnset && v.w > 0.0f && std::abs(v.x) <= v.w && std::abs(v.y) <= v.w)
        apexes[part] = v;
    out.insert(out.end(), {kUnset, drawn(leaves), drawn(returns)});
    out_weights.push_back(-weights[t]);
    if (out_parts != nullptr) out_parts->push_back(part);
  }
  for (std::size_t f = first; f < out_weights.size(); ++f) {
    const std::uint32_t part = parts.empty() ? 0 : (*out_parts)[f];
    // Where no cut point is in view, the near plane's centre.
    out[3 * f] = drawn(apexes[part] == kUnset ? glm::vec4(0.0f, 0.0f, 1.0f, 1.0f) : apexes[part]);
  }
}

}  // namespace shadowvol
