#include "scene/shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace shadowvol {

Mesh make_bumpy_torus(int rings, int segments, float major_radius, float minor_radius, int bumps) {
  Mesh m;
  m.positions.reserve(static_cast<std::size_t>(rings) * segments);
  const float two_pi = 2.0f * std::numbers::pi_v<float>;
  for (int i = 0; i < rings; ++i) {
    const float u = two_pi * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j < segments; ++j) {
      const float v = two_pi * static_cast<float>(j) / static_cast<float>(segments);
      const float r = minor_radius * (1.0f + 0.25f * std::sin(bumps * u) * std::cos(bumps * v));
      const float d = major_radius + r * std::cos(v);
      m.positions.emplace_back(d * std::cos(u), d * std::sin(u), r * std::sin(v));
    }
  }
  auto id = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % rings) * segments + (j % segments));
  };
  m.indices.reserve(static_cast<std::size_t>(rings) * segments * 6);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});  // outward: u x v points out
    }
  return m;
}

Mesh make_bumpy_torus_with(std::size_t triangles) {
  const double quads = static_cast<double>(triangles) / 2.0;
  const int segments = std::max(3, static_cast<int>(std::lround(std::sqrt(quads / 2.0))));
  const int rings = std::max(3, static_cast<int>(std::lround(quads / segments)));
  return make_bumpy_torus(rings, segments);
}

Mesh make_box(glm::vec3 lo, glm::vec3 hi, bool with_top) {
  Mesh m;
  for (int i = 0; i < 8; ++i)  // bit 0: x, bit 1: y, bit 2: z
    m.positions.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  // Each face's corners counter-clockwise seen from outside: -z, +z, -y, +y, -x, +x.
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (int q = 0; q < 6; ++q) {
    if (!with_top && q == 1) continue;
    const std::uint32_t* v = quads[q];
    m.indices.insert(m.indices.end(), {v[0], v[1], v[2], v[0], v[2], v[3]});
  }
  return m;
}

Mesh make_ground(float half_size) {
  Mesh m;
  const float h = half_size;
  m.positions = {{-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}};
  m.indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from +y
  return m;
}

}  // namespace shadowvol
