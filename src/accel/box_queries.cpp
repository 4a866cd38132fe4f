#include "accel/box_queries.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "accel/near_plane.h"

namespace shadowvol {
namespace {

glm::vec3 corner(const glm::vec3& lo, const glm::vec3& hi, int i) {
  return {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
}

// The box's faces as quads of corner indices (bit 0: x, bit 1: y, bit 2: z), and its edges.
constexpr int kFaces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                              {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
constexpr int kEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                               {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

void add_quad(const glm::vec4& a, const glm::vec4& b, const glm::vec4& c, const glm::vec4& d,
              std::vector<glm::vec4>& out) {
  out.insert(out.end(), {a, b, c, a, c, d});
}

// The grown box's corners, w = 1.
std::array<glm::vec4, 8> grown_corners(const glm::vec3& lo, const glm::vec3& hi) {
  const glm::vec3 m(query_margin(lo, hi));
  std::array<glm::vec4, 8> c;
  for (int i = 0; i < 8; ++i) c[i] = glm::vec4(corner(lo - m, hi + m, i), 1.0f);
  return c;
}

}  // namespace

float query_margin(const glm::vec3& lo, const glm::vec3& hi) {
  float farthest = 0.0f;
  for (int i = 0; i < 8; ++i) farthest = std::max(farthest, glm::length(corner(lo, hi, i)));
  return 1e-4f * (farthest + glm::length(hi - lo));
}

void box_query_triangles(const glm::vec3& lo, const glm::vec3& hi, std::vector<glm::vec4>& out) {
  const std::array<glm::vec4, 8> c = grown_corners(lo, hi);
  for (const auto& f : kFaces) add_quad(c[f[0]], c[f[1]], c[f[2]], c[f[3]], out);
}

void shadow_query_triangles(const glm::vec3& lo, const glm::vec3& hi, const glm::vec4& light,
                            std::vector<glm::vec4>& out) {
  const std::array<glm::vec4, 8> c = grown_corners(lo, hi);
  const bool point = light.w != 0.0f;
  const glm::vec3 l = point ? glm::vec3(light) / light.w : glm::vec3(light);
  // A face faces the light where the light lies on its outer side or in its plane (kFaces: -z,
  // +z, -y, +y, -x, +x).
  bool facing[6];
  for (int f = 0; f < 6; ++f) {
    const int axis = 2 - f / 2;
    const float side = f % 2 ? 1.0f : -1.0f;
    const float plane = (f % 2 ? c[7] : c[0])[axis];
    facing[f] = side * (point ? l[axis] - plane : l[axis]) >= 0.0f;
  }
  auto face_of = [](int axis, bool high) { return 2 * (2 - axis) + (high ? 1 : 0); };
  for (int f = 0; f < 6; ++f)
    if (facing[f])
      add_quad(c[kFaces[f][0]], c[kFaces[f][1]], c[kFaces[f][2]], c[kFaces[f][3]], out);
  auto at_infinity = [&](const glm::vec4& p) {
    return glm::vec4(point ? glm::vec3(p) - l : -l, 0.0f);
  };
  // The silhouette: edges between a face toward the light and one away from it.
  for (const auto& e : kEdges) {
    const int axis = e[0] ^ e[1];  // the bit the edge runs along: 1 x, 2 y, 4 z
    const int along = axis == 1 ? 0 : axis == 2 ? 1 : 2;
    int faces[2], n = 0;
    for (int k = 0; k < 3; ++k)
      if (k != along) faces[n++] = face_of(k, (e[0] >> k) & 1);
    if (facing[faces[0]] == facing[faces[1]]) continue;
    add_quad(c[e[0]], c[e[1]], at_infinity(c[e[1]]), at_infinity(c[e[0]]), out);
  }
}

bool box_outside_frustum(const glm::vec3& lo, const glm::vec3& hi, const glm::mat4& view_proj) {
  std::array<glm::vec4, 8> clip;
  for (int i = 0; i < 8; ++i) clip[i] = view_proj * glm::vec4(corner(lo, hi, i), 1.0f);
  // The planes x >= -w, x <= w, y >= -w, y <= w, z <= w (in front of the near plane), as dot
  // products that are >= 0 inside.
  const glm::vec4 planes[] = {
      {1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1}, {0, -1, 0, 1}, {0, 0, -1, 1}};
  for (const glm::vec4& plane : planes)
    if (std::all_of(clip.begin(), clip.end(),
                    [&](const glm::vec4& p) { return glm::dot(plane, p) < 0.0f; }))
      return true;
  return false;
}

bool box_meets_near(const glm::vec3& lo, const glm::vec3& hi,
                    const std::array<glm::vec3, 4>& near_rect) {
  glm::vec3 rect_lo(INFINITY), rect_hi(-INFINITY);
  for (const glm::vec3& p : near_rect)
    rect_lo = glm::min(rect_lo, p), rect_hi = glm::max(rect_hi, p);
  const glm::vec3 m(query_margin(lo, hi));
  return glm::all(glm::lessThanEqual(lo - m, rect_hi)) &&
         glm::all(glm::lessThanEqual(rect_lo, hi + m));
}

bool shadow_meets_near(const glm::vec3& lo, const glm::vec3& hi, const glm::vec4& light,
                       const std::array<glm::vec3, 4>& near_rect) {
  const glm::vec3 m(query_margin(lo, hi));
  if (light.w != 0.0f) {
    const glm::vec3 l = glm::vec3(light) / light.w;
    if (glm::all(glm::lessThanEqual(lo - m, l)) && glm::all(glm::lessThanEqual(l, hi + m)))
      return true;
  }
  return box_meets_near(lo, hi, near_rect) ||
         may_shadow_near_plane((lo + hi) * 0.5f, glm::length(hi - lo) * 0.5f + 2.0f * m.x,
                               near_rect, light);
}

}  // namespace shadowvol
