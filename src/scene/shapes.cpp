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

}  // namespace shadowvol
