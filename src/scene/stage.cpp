#include "scene/stage.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cmath>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

#include "core/shapes.h"
#include "scene/mesh_io.h"

namespace shadowvol {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// A deterministic stream of numbers in [0, 1) (splitmix64), the same on every platform.
struct Draws {
  std::uint64_t state;
  float next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return static_cast<float>((z ^ (z >> 31)) >> 40) * 0x1.0p-24f;
  }
  float between(float lo, float hi) { return lo + (hi - lo) * next(); }
};

// A tube along the polyline `path` of radius r, `sides` around, without end caps (open).
Mesh open_pipe(const std::vector<glm::vec3>& path, float r, int sides) {
  Mesh m;
  const auto n = static_cast<std::uint32_t>(sides);
  for (std::size_t k = 0; k < path.size(); ++k) {
    const glm::vec3 along =
        glm::normalize(path[std::min(k + 1, path.size() - 1)] - path[k == 0 ? 0 : k - 1]);
    const glm::vec3 helper = std::abs(along.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 u = glm::normalize(glm::cross(helper, along)), v = glm::cross(along, u);
    for (int i = 0; i < sides; ++i) {
      const float t = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(sides);
      m.positions.push_back(path[k] + r * (std::cos(t) * u + std::sin(t) * v));
    }
  }
  for (std::uint32_t k = 0; k + 1 < path.size(); ++k)
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t a0 = k * n + i, a1 = k * n + (i + 1) % n, b0 = a0 + n, b1 = a1 + n;
      m.indices.insert(m.indices.end(), {a0, a1, b1, a0, b1, b0});
    }
  return m;
}

// The upper half of a sphere, open at its rim.
Mesh open_dome(glm::vec3 centre, float radius, int rings, int segments) {
  Mesh m;
  const auto n = static_cast<std::uint32_t>(segments);
  for (int k = 0; k <= rings; ++k) {
    const float theta = 0.5f * kPi * static_cast<float>(k) / static_cast<float>(rings);
    for (int j = 0; j < segments; ++j) {
      const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(segments);
      m.positions.push_back(centre + radius * glm::vec3(std::cos(theta) * std::cos(phi),
                                                        std::sin(theta),
                                                        std::cos(theta) * std::sin(phi)));
    }
  }
  for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(rings); ++k)
    for (std::uint32_t j = 0; j < n; ++j) {
      const std::uint32_t a = k * n + j, b = k * n + (j + 1) % n, c = b + n, d = a + n;
      m.indices.insert(m.indices.end(), {a, d, c, a, c, b});
    }
  return m;
}

// A grid of nx x nz quads over [lo, hi] in x and z at height y, facing +y.
Mesh grid(glm::vec2 lo, glm::vec2 hi, float y, int nx, int nz) {
  Mesh m;
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= nx; ++i)
      m.positions.emplace_back(lo.x + (hi.x - lo.x) * static_cast<float>(i) / nx, y,
                               lo.y + (hi.y - lo.y) * static_cast<float>(k) / nz);
  const auto row = static_cast<std::uint32_t>(nx + 1);
  for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(nz); ++k)
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(nx); ++i) {
      const std::uint32_t a = k * row + i, b = a + 1, c = a + row + 1, d = a + row;
      m.indices.insert(m.indices.end(), {a, d, c, a, c, b});
    }
  return m;
}

}  // namespace

Scene stage_scene(std::string name, Mesh mesh) {
  assert(!mesh.positions.empty());
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 c = (lo + hi) * 0.5f;
  const float r = std::max(0.5f * glm::length(hi - lo), 1e-6f);
  Scene s;
  s.name = name;
  s.objects.push_back(
      make_object(std::move(name), std::move(mesh), glm::mat4(1.0f), {0.8f, 0.55f, 0.35f}));
  s.objects.back().animation.move = glm::vec3(kStageStepPerFrame * r, 0.0f, 0.0f);
  glm::mat4 ground(1.0f);
  ground[3] = glm::vec4(c.x, lo.y - 0.001f * r, c.z, 1.0f);
  s.objects.push_back(make_object("ground", make_ground(4.0f * r), ground, {0.75f, 0.75f, 0.72f}));
  s.lights.push_back(
      {glm::vec4(c + r * glm::vec3(1.5f, 3.0f, 1.0f), 1.0f), {1, 0.97f, 0.9f}, 1.0f});
  s.camera = {c + r * glm::vec3(0.0f, 1.2f, 3.0f), c, {0, 1, 0}, 50.0f, 0.05f * r};
  return s;
}

Mesh stage_sphere(int n) {
  assert(n >= 3 && n <= 4096);
  return make_sphere({0.0f, 1.2f, 0.0f}, 1.0f, n + 1, n);
}

Mesh make_cad_assembly() {
  Draws d{42};
  Mesh m;
  // The cast base: a box with its top a grid (panels' edges cross it: T-junctions).
  append_mesh(m, make_box({-30.0f, -2.0f, -20.0f}, {30.0f, 0.0f, 20.0f}, false));
  append_mesh(m, grid({-30.0f, -20.0f}, {30.0f, 20.0f}, 0.0f, 96, 64));
  // Brackets: two boxes sharing part of a face (coincident faces), around the base's edge.
  for (int i = 0; i < 60; ++i) {
    const float x = -28.0f + 56.0f * static_cast<float>(i % 30) / 29.0f;
    const float z = i < 30 ? -18.5f : 18.5f;
    append_mesh(m, make_box({x - 0.6f, 0.0f, z - 0.6f}, {x + 0.6f, 0.4f, z + 0.6f}));
    append_mesh(m, make_box({x - 0.2f, 0.4f, z - 0.6f}, {x + 0.2f, 2.2f, z + 0.6f}));
  }
  // Panels standing on the base, their feet across the grid's lines, and open pipes between.
  for (int i = 0; i < 16; ++i) {
    const float x = d.between(-24.0f, 24.0f), z = d.between(-14.0f, 14.0f);
    const float w = d.between(2.0f, 5.0f), h = d.between(3.0f, 8.0f);
    append_mesh(m, make_box({x - w, 0.0f, z - 0.07f}, {x + w, h, z + 0.07f}));
  }
  for (int i = 0; i < 26; ++i) {
    std::vector<glm::vec3> path;
    const glm::vec3 from(d.between(-26.0f, 26.0f), 0.0f, d.between(-16.0f, 16.0f));
    const float reach = d.between(6.0f, 16.0f), turn = d.between(0.0f, 2.0f * kPi);
    const float rise = d.between(3.0f, 9.0f);
    for (int k = 0; k <= 36; ++k) {  // up, over an arc, and down again
      const float t = static_cast<float>(k) / 36.0f;
      path.push_back(from + glm::vec3(reach * t * std::cos(turn), rise * std::sin(kPi * t),
                                      reach * t * std::sin(turn)));
    }
    append_mesh(m, open_pipe(path, d.between(0.25f, 0.6f), 32));
  }
  // Heat sinks: plates of thin fins.
  for (int s = 0; s < 4; ++s) {
    const float x0 = -20.0f + 12.0f * static_cast<float>(s), z0 = -6.0f;
    append_mesh(m, make_box({x0, 0.0f, z0}, {x0 + 6.0f, 0.5f, z0 + 6.0f}));
    for (int f = 0; f < 30; ++f) {
      const float x = x0 + 0.1f + 0.2f * static_cast<float>(f);
      append_mesh(m, make_box({x, 0.5f, z0 + 0.2f}, {x + 0.06f, 3.0f, z0 + 5.8f}));
    }
  }
  // Open domes (covers), each a separate part.
  for (int i = 0; i < 12; ++i)
    append_mesh(m, open_dome({d.between(-25.0f, 25.0f), 0.0f, d.between(-15.0f, 15.0f)},
                             d.between(1.0f, 2.5f), 24, 48));
  // Bolts: hex heads on shafts, in rows along the base and on the brackets.
  for (int i = 0; i < 480; ++i) {
    const float x = -29.0f + 58.0f * static_cast<float>(i % 60) / 59.0f;
    const float z = -19.2f + 38.4f * static_cast<float>(i / 60) / 7.0f;
    append_mesh(m, make_tube({x, -0.8f, z}, {x, 0.35f, z}, 0.16f, 0.16f, 20));
    append_mesh(m, make_tube({x, 0.35f, z}, {x, 0.6f, z}, 0.3f, 0.3f, 6));
  }
  return m;
}

Expected<Scene> load_stage(const std::string& name) {
  if (name == "cad") return stage_scene("cad", make_cad_assembly());
  if (name.starts_with("sphere:")) {
    int n = 0;
    const char* end = name.data() + name.size();
    const auto [at, error] = std::from_chars(name.data() + 7, end, n);
    if (error != std::errc{} || at != end || n < 3 || n > 4096)
      return make_error("--stage " + name + ": sphere:N takes N from 3 to 4096 (2 N^2 triangles)");
    return stage_scene(name, stage_sphere(n));
  }
  auto loaded = load_mesh(name);
  if (!loaded) return loaded.error();
  return stage_scene(std::filesystem::path(name).filename().string(), std::move(loaded->mesh));
}

}  // namespace shadowvol
