// Hand-drawn edge tables and reports: answers worked out on paper (STYLE §6).
#include <gtest/gtest.h>

#include <map>

#include "core/topology.h"
#include "test_meshes.h"

namespace shadowvol {
namespace {

using testing::add_triangle;

// The faces of edge (a, b) as {face, reversed} pairs, looked up by welded vertex indices.
std::vector<std::pair<std::uint32_t, bool>> faces_of(const Topology& t, std::uint32_t a,
                                                     std::uint32_t b) {
  for (std::size_t e = 0; e < t.edge_count(); ++e)
    if (t.edge_vertices[2 * e] == std::min(a, b) && t.edge_vertices[2 * e + 1] == std::max(a, b)) {
      std::vector<std::pair<std::uint32_t, bool>> out;
      for (std::uint32_t i = t.edge_face_offsets[e]; i < t.edge_face_offsets[e + 1]; ++i)
        out.emplace_back(face_of(t.edge_faces[i]), is_reversed(t.edge_faces[i]));
      return out;
    }
  return {};
}

TEST(Topology, CubeIsAClosedManifold) {
  const Topology t = build_topology(testing::box({0, 0, 0}, {1, 1, 1}));
  const TopologyReport& r = t.report;
  EXPECT_EQ(r.vertices, 8u);
  EXPECT_EQ(r.triangles, 12u);
  EXPECT_EQ(r.edges, 18u);  // 12 box edges + 6 face diagonals; Euler: 8 - 18 + 12 = 2
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_EQ(r.nonmanifold_edges, 0u);
  EXPECT_EQ(r.inconsistent_edges, 0u);
  EXPECT_EQ(r.degenerate_triangles, 0u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_TRUE(r.closed_manifold);
  // Every edge: two faces, one along and one against its canonical direction.
  for (std::size_t e = 0; e < t.edge_count(); ++e) {
    ASSERT_EQ(t.edge_face_offsets[e + 1] - t.edge_face_offsets[e], 2u);
    EXPECT_NE(is_reversed(t.edge_faces[t.edge_face_offsets[e]]),
              is_reversed(t.edge_faces[t.edge_face_offsets[e] + 1]));
  }
}

TEST(Topology, QuadOfTwoTrianglesHasFourBoundaryEdgesAndOneShared) {
  Mesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  const Topology t = build_topology(quad);
  EXPECT_EQ(t.report.edges, 5u);
  EXPECT_EQ(t.report.boundary_edges, 4u);
  EXPECT_FALSE(t.report.closed_manifold);
  // Diagonal 0-2: face 0 runs 2 -> 0 (against 0 -> 2), face 1 runs 0 -> 2 (along).
  const auto diagonal = faces_of(t, 0, 2);
  ASSERT_EQ(diagonal.size(), 2u);
  EXPECT_EQ(diagonal[0], std::make_pair(0u, true));
  EXPECT_EQ(diagonal[1], std::make_pair(1u, false));
  // Edge 0-1 belongs to face 0 only, along its direction.
  EXPECT_EQ(faces_of(t, 0, 1), (std::vector<std::pair<std::uint32_t, bool>>{{0u, false}}));
}

TEST(Topology, ThreeFacesOnOneEdgeAreNonManifold) {
  Mesh m;
  add_triangle(m, {0, 0, 0}, {0, 0, 1}, {1, 0, 0});
  add_triangle(m, {0, 0, 1}, {0, 0, 0}, {0, 1, 0});
  add_triangle(m, {0, 0, 0}, {0, 0, 1}, {-1, -1, 0});
  const Topology t = build_topology(m);  // 9 input vertices weld to 5
  EXPECT_EQ(t.report.vertices, 5u);
  EXPECT_EQ(t.report.edges, 7u);
  EXPECT_EQ(t.report.nonmanifold_edges, 1u);
  EXPECT_EQ(t.report.boundary_edges, 6u);
  EXPECT_EQ(t.report.components, 1u);
  const auto spine = faces_of(t, 0, 1);  // welded 0 = (0,0,0), 1 = (0,0,1)
  ASSERT_EQ(spine.size(), 3u);
  EXPECT_FALSE(spine[0].second);
  EXPECT_TRUE(spine[1].second);
  EXPECT_FALSE(spine[2].second);
}

TEST(Topology, TwoFacesRunningOneEdgeTheSameWayAreInconsistent) {
  Mesh m;
  add_triangle(m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  add_triangle(m, {0, 0, 0}, {1, 0, 0}, {0, -1, 0});  // flipped: runs 0 -> 1 again
  const Topology t = build_topology(m);
  EXPECT_EQ(t.report.inconsistent_edges, 1u);
  EXPECT_EQ(t.report.nonmanifold_edges, 0u);
  EXPECT_FALSE(t.report.closed_manifold);
}

TEST(Topology, DegenerateTrianglesAreCountedAndCollapsedOnesAddNoEdges) {
  Mesh m;
  add_triangle(m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  add_triangle(m, {0, 0, 0}, {1, 0, 0}, {2, 0, 0});  // collinear: zero area, three edges
  add_triangle(m, {5, 5, 5}, {5, 5, 5}, {6, 5, 5});  // collapsed: no edges
  const Topology t = build_topology(m);
  EXPECT_EQ(t.report.degenerate_triangles, 2u);
  EXPECT_EQ(t.report.edges, 5u);  // 3 + 2 new (1-2, 0-2 on the x axis)
  EXPECT_EQ(t.report.components, 2u);
  EXPECT_EQ(t.face_count(), 3u);  // face indices still match the input
}

TEST(Topology, WeldsExactlyByDefaultAndWithinEpsilonOnRequest) {
  Mesh m;
  add_triangle(m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  add_triangle(m, {1.0001f, 0, 0}, {-0.0f, 0, 0}, {1, 1, 0});  // -0 == +0; 1.0001 != 1
  EXPECT_EQ(build_topology(m).report.vertices, 5u);
  const Topology welded = build_topology(m, WeldOptions{0.001f});
  EXPECT_EQ(welded.report.vertices, 4u);
  EXPECT_EQ(welded.report.edges, 5u);
  EXPECT_EQ(welded.vertex_remap[3], 1u);
  EXPECT_EQ(welded.vertex_remap[4], 0u);
}

TEST(Topology, ComponentsCountSeparateShells) {
  const Topology t = build_topology(
      testing::merged(testing::box({0, 0, 0}, {1, 1, 1}), testing::box({3, 0, 0}, {4, 1, 1})));
  EXPECT_EQ(t.report.components, 2u);
  EXPECT_TRUE(t.report.closed_manifold);
}

TEST(Topology, FrameBytesCountsTheFlatArrays) {
  const Topology t = build_topology(testing::box({0, 0, 0}, {1, 1, 1}));
  // 8 positions * 12 B + 36 face indices * 4 B + 18 edges * (2 + 1) * 4 B + 1 offset * 4 B
  // + 36 face references * 4 B.
  EXPECT_EQ(t.frame_bytes(), 96u + 144u + 216u + 4u + 144u);
}

}  // namespace
}  // namespace shadowvol
