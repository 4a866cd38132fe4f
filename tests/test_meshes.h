// Small hand-built meshes for the tests, named for what they break (STYLE §6). All vertices
// are small integers, so that tests can reason about them in exact integer arithmetic.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/mesh.h"
#include "core/shapes.h"
#include "scene/scene.h"

namespace shadowvol::testing {

struct NamedMesh {
  std::string name;
  Mesh mesh;
};

// Every built-in scene by name, the cities at a size a test can afford (three blocks: city:48).
inline std::vector<std::string> builtin_scenes_at_test_size() {
  std::vector<std::string> names;
  for (const std::string_view name : builtin_scene_names())
    names.push_back(name.starts_with("city") ? std::string(name) + ":48" : std::string(name));
  return names;
}

// The scene k times larger: camera, near plane, point lights and objects alike.
inline Scene scaled(Scene scene, float k) {
  scene.camera.position *= k, scene.camera.target *= k, scene.camera.near *= k;
  for (SceneLight& light : scene.lights)
    if (light.position.w != 0.0f) light.position = glm::vec4(glm::vec3(light.position) * k, 1.0f);
  for (SceneObject& object : scene.objects)
    object.transform = glm::scale(glm::mat4(1.0f), glm::vec3(k)) * object.transform;
  return scene;
}

inline void add_triangle(Mesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), {a, b, c});
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
}

inline Mesh box(glm::vec3 lo, glm::vec3 hi, bool with_top = true) {
  return make_box(lo, hi, with_top);
}

inline Mesh merged(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (std::uint32_t i : b.indices) m.indices.push_back(base + i);
  return m;
}

inline Mesh tetrahedron(glm::vec3 o, float s) {
  Mesh m;
  m.positions = {o, o + glm::vec3(s, 0, 0), o + glm::vec3(0, s, 0), o + glm::vec3(0, 0, s)};
  m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return m;
}

// A closed box whose top is a grid of random integer heights: non-convex, nested silhouettes.
inline Mesh bumpy_box(int n, float cell, std::mt19937& rng) {
  Mesh m;
  std::uniform_int_distribution<int> height(8, 40);
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) m.positions.emplace_back(i * cell, j * cell, float(height(rng)));
  const auto bottom = static_cast<std::uint32_t>(m.positions.size());
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) m.positions.emplace_back(i * cell, j * cell, 0.0f);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});  // top, facing +z
      m.indices.insert(m.indices.end(),
                       {bottom + a, bottom + c, bottom + b, bottom + a, bottom + d, bottom + c});
    }
  // Walls: walk the border counter-clockwise seen from +z; each wall quad faces outwards.
  std::vector<std::pair<int, int>> ring;
  for (int i = 0; i < n; ++i) ring.emplace_back(i, 0);
  for (int j = 0; j < n; ++j) ring.emplace_back(n, j);
  for (int i = n; i > 0; --i) ring.emplace_back(i, n);
  for (int j = n; j > 0; --j) ring.emplace_back(0, j);
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const auto [i0, j0] = ring[k];
    const auto [i1, j1] = ring[(k + 1) % ring.size()];
    const std::uint32_t t0 = id(i0, j0), t1 = id(i1, j1);
    m.indices.insert(m.indices.end(), {bottom + t0, bottom + t1, t1, bottom + t0, t1, t0});
  }
  return m;
}

inline Mesh random_soup(int triangles, int range, std::mt19937& rng) {
  std::uniform_int_distribution<int> coord(-range, range);
  auto point = [&] { return glm::vec3(coord(rng), coord(rng), coord(rng)); };
  Mesh m;
  for (int t = 0; t < triangles; ++t) add_triangle(m, point(), point(), point());
  return m;
}

// The adversarial set of the volume law test and the topology tests.
inline std::vector<NamedMesh> adversarial_meshes(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<NamedMesh> out;
  const Mesh cube = box({-16, -16, -16}, {16, 16, 16});
  out.push_back({"cube", cube});
  out.push_back({"tetrahedron", tetrahedron({-10, -12, -8}, 30)});
  out.push_back(
      {"two_cubes", merged(box({-40, -8, -8}, {-20, 12, 12}), box({8, -4, 0}, {30, 20, 24}))});
  out.push_back({"bumpy_box", bumpy_box(5, 8, rng)});
  // Two closed tetrahedra meeting at one vertex: vertex-non-manifold, every edge still manifold.
  {
    Mesh bowtie = tetrahedron({0, 0, 0}, 20);
    Mesh other = tetrahedron({0, 0, 0}, -20);  // mirrored: reverse its winding to face outwards
    for (std::size_t i = 0; i < other.indices.size(); i += 3)
      std::swap(other.indices[i + 1], other.indices[i + 2]);
    out.push_back({"bowtie_nonmanifold", merged(bowtie, other)});
  }
  out.push_back({"open_box", box({-16, -16, -16}, {16, 16, 16}, false)});
  {
    Mesh fin = cube;  // a fin on the edge (-16,-16,16)-(16,-16,16): three faces on one edge
    const auto base = static_cast<std::uint32_t>(fin.positions.size());
    fin.positions.emplace_back(0, -40, 30);
    fin.indices.insert(fin.indices.end(), {4, 5, base});
    out.push_back({"fin_nonmanifold", fin});
  }
  {
    Mesh book;  // four pages on one spine
    for (glm::vec3 tip :
         {glm::vec3(20, 0, 0), glm::vec3(0, 20, 0), glm::vec3(-20, 3, 0), glm::vec3(5, -20, 0)})
      add_triangle(book, {0, 0, -15}, {0, 0, 15}, tip);
    out.push_back({"book_nonmanifold", book});
  }
  {
    Mesh flipped = cube;
    std::swap(flipped.indices[1], flipped.indices[2]);
    out.push_back({"flipped_face", flipped});
  }
  {
    Mesh coincident = cube;
    const std::vector<std::uint32_t> face(cube.indices.begin(), cube.indices.begin() + 6);
    coincident.indices.insert(coincident.indices.end(), face.begin(), face.end());
    coincident.indices.insert(coincident.indices.end(), {face[0], face[2], face[1]});
    out.push_back({"coincident_faces", coincident});
  }
  {
    Mesh sliver = cube;
    const auto base = static_cast<std::uint32_t>(sliver.positions.size());
    sliver.positions.emplace_back(0, -16, -16);                 // midpoint of the edge v0-v1
    sliver.indices.insert(sliver.indices.end(), {0, base, 1});  // collinear: zero area
    sliver.indices.insert(sliver.indices.end(), {2, 2, 3});     // collapsed
    out.push_back({"zero_area_sliver", sliver});
  }
  {
    Mesh single;
    add_triangle(single, {-20, -10, 0}, {20, -12, 2}, {0, 18, -3});
    out.push_back({"single_triangle", single});
  }
  out.push_back({"random_soup", random_soup(40, 48, rng)});
  out.push_back({"random_soup_dense", random_soup(120, 24, rng)});
  return out;
}

}  // namespace shadowvol::testing
