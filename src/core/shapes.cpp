#include "core/shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <tuple>
#include <utility>

#include <glm/geometric.hpp>

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

Mesh make_tube(glm::vec3 a, glm::vec3 b, float ra, float rb, int sides) {
  const glm::vec3 w = glm::normalize(b - a);
  const glm::vec3 helper = std::abs(w.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 u = glm::normalize(glm::cross(helper, w)), v = glm::cross(w, u);  // u x v = w
  Mesh m;
  m.positions = {a, b};
  for (const auto& [centre, radius] : {std::pair{a, ra}, std::pair{b, rb}})
    for (int i = 0; i < sides; ++i) {
      const float t = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / sides;
      m.positions.push_back(centre + radius * (std::cos(t) * u + std::sin(t) * v));
    }
  const auto ring = [&](int end, int i) {
    return static_cast<std::uint32_t>(2 + end * sides + i % sides);
  };
  for (int i = 0; i < sides; ++i) {
    const std::uint32_t a0 = ring(0, i), a1 = ring(0, i + 1), b0 = ring(1, i), b1 = ring(1, i + 1);
    m.indices.insert(m.indices.end(), {a0, a1, b1, a0, b1, b0});  // sides, outward
    m.indices.insert(m.indices.end(), {0, a1, a0, 1, b0, b1});    // end caps, facing -w and +w
  }
  return m;
}

Mesh make_sphere(glm::vec3 centre, float radius, int rings, int segments) {
  Mesh m;
  m.positions = {centre + glm::vec3(0, radius, 0), centre - glm::vec3(0, radius, 0)};
  for (int k = 1; k < rings; ++k) {
    const float theta = std::numbers::pi_v<float> * static_cast<float>(k) / rings;
    for (int j = 0; j < segments; ++j) {
      const float phi = 2.0f * std::numbers::pi_v<float> * static_cast<float>(j) / segments;
      m.positions.push_back(centre + radius * glm::vec3(std::sin(theta) * std::cos(phi),
                                                        std::cos(theta),
                                                        std::sin(theta) * std::sin(phi)));
    }
  }
  // Row 0 is the north pole and row `rings` the south pole; rows between are rings of vertices.
  const auto at = [&](int k, int j) -> std::uint32_t {
    if (k == 0) return 0;
    if (k == rings) return 1;
    return static_cast<std::uint32_t>(2 + (k - 1) * segments + j % segments);
  };
  for (int k = 0; k < rings; ++k)
    for (int j = 0; j < segments; ++j) {
      const std::uint32_t a = at(k, j), b = at(k, j + 1), c = at(k + 1, j + 1), d = at(k + 1, j);
      if (k > 0) m.indices.insert(m.indices.end(), {a, b, c});  // outward: d/dphi x d/dtheta
      if (k + 1 < rings) m.indices.insert(m.indices.end(), {a, c, d});
    }
  return m;
}

void append_mesh(Mesh& mesh, const Mesh& part) {
  const auto offset = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
  for (const std::uint32_t i : part.indices) mesh.indices.push_back(offset + i);
}

std::vector<Mesh> connected_parts(const Mesh& mesh, bool join_equal_positions) {
  std::vector<std::uint32_t> parent(mesh.positions.size());
  for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  const auto root = [&](std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  if (join_equal_positions) {  // sorted by position, equal neighbours join
    std::vector<std::uint32_t> order(parent);
    const auto key = [&](std::uint32_t i) {
      const glm::vec3& p = mesh.positions[i];
      return std::tuple(p.x, p.y, p.z);
    };
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
    for (std::size_t k = 1; k < order.size(); ++k)
      if (key(order[k]) == key(order[k - 1])) parent[root(order[k])] = root(order[k - 1]);
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 1; k < 3; ++k) parent[root(mesh.indices[3 * t + k])] = root(mesh.indices[3 * t]);
  std::vector<Mesh> parts;
  std::vector<std::int64_t> part_of_root(parent.size(), -1);
  std::vector<std::int64_t> new_index(parent.size(), -1);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    std::int64_t& part = part_of_root[root(mesh.indices[3 * t])];
    if (part < 0) {
      part = static_cast<std::int64_t>(parts.size());
      parts.emplace_back();
    }
    Mesh& out = parts[static_cast<std::size_t>(part)];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = mesh.indices[3 * t + k];
      if (new_index[i] < 0) {
        new_index[i] = static_cast<std::int64_t>(out.positions.size());
        out.positions.push_back(mesh.positions[i]);
      }
      out.indices.push_back(static_cast<std::uint32_t>(new_index[i]));
    }
  }
  return parts;
}

Mesh make_knight() {
  Mesh m;
  for (const float side : {-1.0f, 1.0f}) {
    append_mesh(m, make_tube({0.15f * side, 0.0f, 0.02f}, {0.13f * side, 0.92f, 0.0f}, 0.09f, 0.12f,
                             12));                                           // leg
    append_mesh(m, make_sphere({0.33f * side, 1.47f, 0.0f}, 0.14f, 8, 12));  // shoulder
  }
  append_mesh(m, make_tube({0.0f, 0.85f, 0.0f}, {0.0f, 1.52f, 0.0f}, 0.27f, 0.31f, 16));    // torso
  append_mesh(m, make_tube({0.38f, 1.42f, 0.0f}, {0.46f, 0.98f, 0.2f}, 0.08f, 0.07f, 10));  // arm
  append_mesh(m, make_tube({-0.38f, 1.42f, 0.0f}, {-0.5f, 1.05f, 0.12f}, 0.08f, 0.07f, 10));
  append_mesh(m, make_sphere({0.0f, 1.74f, 0.0f}, 0.17f, 10, 14));          // head
  append_mesh(m, make_box({-0.03f, 1.8f, -0.18f}, {0.03f, 1.98f, 0.14f}));  // crest
  append_mesh(m,
              make_tube({0.46f, 0.95f, 0.22f}, {0.5f, 1.95f, 0.75f}, 0.035f, 0.02f, 6));   // sword
  append_mesh(m, make_tube({0.3f, 1.04f, 0.3f}, {0.62f, 0.88f, 0.16f}, 0.03f, 0.03f, 6));  // guard
  append_mesh(m,
              make_tube({-0.52f, 1.08f, 0.16f}, {-0.58f, 1.1f, 0.24f}, 0.34f, 0.3f, 20));  // shield
  return m;
}

Mesh make_truss(float half_span, float height, float depth, int panels, float radius, int sides) {
  Mesh m;
  auto member = [&](glm::vec3 a, glm::vec3 b) {
    append_mesh(m, make_tube(a, b, radius, radius, sides));
  };
  const float step = 2.0f * half_span / static_cast<float>(panels);
  auto bottom = [&](int i) { return glm::vec3(-half_span + step * float(i), 0.0f, 0.0f); };
  auto top = [&](int i, float side) {  // over the middle of panel i
    return glm::vec3(-half_span + step * (float(i) + 0.5f), height, side * 0.5f * depth);
  };
  for (int i = 0; i < panels; ++i) member(bottom(i), bottom(i + 1));  // chords panel by panel
  for (const float side : {-1.0f, 1.0f}) {
    for (int i = 0; i + 1 < panels; ++i) member(top(i, side), top(i + 1, side));
    for (int i = 0; i < panels; ++i) {
      member(bottom(i), top(i, side));
      member(top(i, side), bottom(i + 1));
    }
  }
  for (int i = 0; i < panels; ++i) member(top(i, -1.0f), top(i, 1.0f));
  return m;
}

Mesh make_robot() {
  Mesh m;
  for (const float side : {-1.0f, 1.0f}) {
    append_mesh(m,
                make_box({0.08f * side - 0.1f, 0.0f, -0.12f}, {0.08f * side + 0.1f, 0.1f, 0.16f}));
    append_mesh(m, make_tube({0.14f * side, 0.08f, 0.0f}, {0.16f * side, 0.85f, 0.0f}, 0.08f, 0.1f,
                             12));  // leg
    append_mesh(m, make_tube({0.42f * side, 1.5f, 0.0f}, {0.5f * side, 0.95f, 0.1f}, 0.07f, 0.06f,
                             10));                                          // arm
    append_mesh(m, make_sphere({0.5f * side, 0.9f, 0.12f}, 0.09f, 8, 12));  // hand
  }
  append_mesh(m, make_box({-0.36f, 0.82f, -0.22f}, {0.36f, 1.6f, 0.22f}));  // torso
  append_mesh(m, make_box({-0.24f, 1.05f, 0.2f}, {0.24f, 1.45f, 0.27f}));   // chest plate
  append_mesh(m, make_tube({0.0f, 1.58f, 0.0f}, {0.0f, 1.7f, 0.0f}, 0.09f, 0.09f, 10));   // neck
  append_mesh(m, make_sphere({0.0f, 1.85f, 0.0f}, 0.2f, 12, 18));                         // head
  append_mesh(m, make_tube({0.0f, 2.0f, 0.0f}, {0.05f, 2.22f, 0.0f}, 0.02f, 0.015f, 6));  // antenna
  append_mesh(m, make_sphere({0.05f, 2.24f, 0.0f}, 0.04f, 6, 8));
  return m;
}

namespace {

// Uniform in [lo, hi) from mt19937's fully specified sequence, so the tree is the same on every
// standard library (std::uniform_real_distribution's algorithm is left to each).
float uniform(std::mt19937& rng, float lo, float hi) {
  return lo + (hi - lo) * static_cast<float>(rng() >> 8) / static_cast<float>(1u << 24);
}

void grow(Mesh& tree, std::mt19937& rng, glm::vec3 base, glm::vec3 direction, float length,
          float radius, int level) {
  const glm::vec3 tip = base + direction * length;
  const float tip_radius = radius * 0.65f;
  Mesh branch = make_tube(base, tip, radius, tip_radius, level == 0 ? 12 : 8);
  if (level == 3) {  // leaves: open quads fanned from the tip's centre vertex (vertex 1)
    for (int leaf = 0; leaf < 5; ++leaf) {
      const float yaw = uniform(rng, 0.0f, 6.2832f), pitch = uniform(rng, -0.6f, 0.9f);
      const glm::vec3 out(std::cos(yaw) * std::cos(pitch), std::sin(pitch),
                          std::sin(yaw) * std::cos(pitch));
      const glm::vec3 across = glm::normalize(glm::cross(out, glm::vec3(0.3f, 1.0f, 0.2f))) * 0.18f;
      const auto first = static_cast<std::uint32_t>(branch.positions.size());
      branch.positions.insert(
          branch.positions.end(),
          {tip + out * 0.25f + across, tip + out * 0.55f, tip + out * 0.25f - across});
      branch.indices.insert(branch.indices.end(), {1, first, first + 1, 1, first + 1, first + 2});
    }
  }
  append_mesh(tree, branch);
  if (level == 3) return;
  for (int child = 0; child < 3; ++child) {
    const float yaw = 2.0944f * static_cast<float>(child) + uniform(rng, -0.5f, 0.5f);
    const float spread = uniform(rng, 0.45f, 0.8f);
    const glm::vec3 side =
        glm::normalize(glm::cross(direction, glm::vec3(std::cos(yaw), 0.1f, std::sin(yaw))));
    const glm::vec3 d = glm::normalize(direction * std::cos(spread) + side * std::sin(spread) +
                                       glm::vec3(0.0f, 0.15f, 0.0f));
    // Children start a little inside the parent's tip, so the tree looks joined; each stays a
    // closed part of its own.
    grow(tree, rng, tip - direction * (0.15f * length), d, length * uniform(rng, 0.62f, 0.75f),
         tip_radius * 0.9f, level + 1);
  }
}

}  // namespace

Mesh make_tree(std::uint32_t seed) {
  std::mt19937 rng(seed);
  Mesh tree;
  grow(tree, rng, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 1.6f, 0.16f, 0);
  return tree;
}

}  // namespace shadowvol
