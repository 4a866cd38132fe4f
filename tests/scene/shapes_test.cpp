#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "core/topology.h"
#include "scene/shapes.h"

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

}  // namespace
}  // namespace shadowvol
