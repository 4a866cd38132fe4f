#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "core/topology.h"
#include "core/shapes.h"

namespace shadowvol {
namespace {

TEST(Shapes, BumpyTorusIsAClosedOutwardManifoldOfTheAskedSize) {
  const Mesh torus = make_bumpy_torus(40, 20);
  EXPECT_EQ(torus.triangle_count(), 1600u);
  const TopologyReport r = build_topology(torus).report;
  EXPECT_TRUE(r.closed_manifold);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.degenerate_triangles, 0u);
  EXPECT_EQ(r.vertices - r.edges + r.triangles, 0u);  // Euler characteristic of a torus
  double volume = 0.0;  // divergence theorem: positive iff the normals point outwards
  for (std::size_t t = 0; t < torus.triangle_count(); ++t) {
    const glm::dvec3 a(torus.positions[torus.indices[3 * t]]);
    const glm::dvec3 b(torus.positions[torus.indices[3 * t + 1]]);
    const glm::dvec3 c(torus.positions[torus.indices[3 * t + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  EXPECT_GT(volume, 0.0);
  const std::size_t n = make_bumpy_torus_with(100000).triangle_count();
  EXPECT_NEAR(static_cast<double>(n), 100000.0, 1000.0);
}

double signed_volume(const Mesh& m) {  // divergence theorem: positive iff normals point out
  double volume = 0.0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::dvec3 a(m.positions[m.indices[3 * t]]);
    const glm::dvec3 b(m.positions[m.indices[3 * t + 1]]);
    const glm::dvec3 c(m.positions[m.indices[3 * t + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return volume;
}

TEST(Shapes, TubesAndSpheresAreClosedOutwardManifoldsOfTheRightVolume) {
  const Mesh tube = make_tube({0, 0, 0}, {0.3f, 2.0f, -0.4f}, 0.5f, 0.5f, 64);
  const Mesh sphere = make_sphere({1, 2, 3}, 0.7f, 32, 64);
  for (const Mesh* m : {&tube, &sphere}) {
    const TopologyReport r = build_topology(*m).report;
    EXPECT_TRUE(r.closed_manifold);
    EXPECT_EQ(r.components, 1u);
    EXPECT_EQ(r.degenerate_triangles, 0u);
  }
  const double pi = 3.14159265358979;
  const double length = std::sqrt(0.3 * 0.3 + 2.0 * 2.0 + 0.4 * 0.4);
  EXPECT_NEAR(signed_volume(tube), pi * 0.25 * length, 0.01 * pi * 0.25 * length);
  EXPECT_NEAR(signed_volume(sphere), 4.0 / 3.0 * pi * 0.343, 0.01 * 4.0 / 3.0 * pi * 0.343);
}

TEST(Shapes, KnightAndTreeAreMadeOfClosedPartsAndTheTreeSplitsIntoItsBranches) {
  const Mesh knight = make_knight();
  const std::vector<Mesh> knight_parts = connected_parts(knight);
  EXPECT_EQ(knight_parts.size(),
            12u);  // legs, shoulders, arms, torso, head, crest, sword, guard, shield
  for (const Mesh& part : knight_parts) {
    EXPECT_TRUE(build_topology(part).report.closed_manifold);
    EXPECT_GT(signed_volume(part), 0.0);
  }
  const Mesh tree = make_tree();
  EXPECT_EQ(make_tree().positions, tree.positions);  // the same seed, the same tree
  const std::vector<Mesh> branches = connected_parts(tree);
  EXPECT_EQ(branches.size(), 40u);  // 1 + 3 + 9 + 27
  std::size_t triangles = 0, open = 0;
  for (const Mesh& b : branches) {
    triangles += b.triangle_count();
    open += !build_topology(b).report.closed_manifold;  // the leafy tips
  }
  EXPECT_EQ(triangles, tree.triangle_count());
  EXPECT_EQ(open, 27u);
  EXPECT_FALSE(build_topology(tree).report.closed_manifold);
}

}  // namespace
}  // namespace shadowvol
