// Hand-drawn edge tables and reports: answers worked out on paper (STYLE §6).
#include <gtest/gtest.h>

#include <algorithm>

#include "core/topology.h"
#include "test_meshes.h"

namespace shadowvol {
namespace {

using testing::add_triangle;

// The faces of edge (a, b) as {face, runs b -> a} pairs, in face order, whichever list holds it.
std::vector<std::pair<std::uint32_t, bool>> faces_of(const Topology& t, std::uint32_t a,
                                                     std::uint32_t b) {
  std::vector<std::pair<std::uint32_t, bool>> out;
  for (std::size_t e = 0; e < t.regular_edge_count(); ++e) {
    const IndexPair v = t.edge_vertices[e];
    if (std::minmax(v[0], v[1]) != std::minmax(a, b)) continue;
    const bool first_runs_a_to_b = v[0] == a;
    out.emplace_back(t.edge_faces[e][0], !first_runs_a_to_b);
    if (t.edge_faces[e][1] != t.face_count())
      out.emplace_back(t.edge_faces[e][1], first_runs_a_to_b);
  }
  for (std::size_t e = 0; e < t.irregular_edge_count(); ++e) {
    const IndexPair v = t.irregular_vertices[e];
    if (std::minmax(v[0], v[1]) != std::minmax(a, b)) continue;
    for (std::uint32_t k = t.irregular_offsets[e]; k < t.irregular_offsets[e + 1]; ++k)
      out.emplace_back(face_of(t.irregular_faces[k]),
                       is_reversed(t.irregular_faces[k]) == (v[0] == a));
  }
  std::sort(out.begin(), out.end());
  return out;
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
  EXPECT_EQ(t.irregular_edge_count(), 0u);
  for (std::size_t e = 0; e < t.regular_edge_count(); ++e) {
    ASSERT_NE(t.edge_faces[e][1], t.face_count());  // no boundary
    // The first face runs the edge in its stored direction.
    const std::uint32_t* v = &t.face_vertices[3 * t.edge_faces[e][0]];
    bool found = false;
    for (int k = 0; k < 3; ++k)
      found |= v[k] == t.edge_vertices[e][0] && v[(k + 1) % 3] == t.edge_vertices[e][1];
    EXPECT_TRUE(found) << "edge " << e;
  }
  // Face 0 is (0, 2, 3) on the z = 0 side: normal (0, 0, -1), scaled by 2^-1 into [0.5, 1).
  EXPECT_EQ(t.face_planes[0], glm::vec4(0, 0, -0.5f, 0));
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
  // Edge 0-1 belongs to face 0 only, along its direction; its second face is the extra slot.
  EXPECT_EQ(faces_of(t, 0, 1), (std::vector<std::pair<std::uint32_t, bool>>{{0u, false}}));
  EXPECT_EQ(t.irregular_edge_count(), 0u);
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
  EXPECT_EQ(t.irregular_edge_count(), 1u);  // the spine; the other six are regular
}

TEST(Topology, TwoFacesRunningOneEdgeTheSameWayAreInconsistent) {
  Mesh m;
  add_triangle(m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  add_triangle(m, {0, 0, 0}, {1, 0, 0}, {0, -1, 0});  // flipped: runs 0 -> 1 again
  const Topology t = build_topology(m);
  EXPECT_EQ(t.report.inconsistent_edges, 1u);
  EXPECT_EQ(t.irregular_edge_count(), 1u);
  EXPECT_EQ(faces_of(t, 0, 1),
            (std::vector<std::pair<std::uint32_t, bool>>{{0u, false}, {1u, false}}));
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

// Parts wound outwards: closed, and enclosing a positive volume. A box turned inside out (as a
// hollow shell's cavity is) and an open box are not; the other parts of their mesh still are.
TEST(Topology, ClosedMeshesWoundOutwardsAreTold) {
  const Mesh a = testing::box({0, 0, 0}, {1, 1, 1}), b = testing::box({3, 0, 0}, {4, 1, 1});
  Mesh inside_out = b;
  for (std::size_t f = 0; f < inside_out.triangle_count(); ++f)
    std::swap(inside_out.indices[3 * f + 1], inside_out.indices[3 * f + 2]);
  const auto outwards = [](const Mesh& m) {
    const Topology t = build_topology(m);
    return std::make_pair(t.report.parts_wound_outwards, t.part_wound_outwards);
  };
  using Parts = std::vector<std::uint8_t>;
  EXPECT_EQ(outwards(a), std::make_pair(std::size_t{1}, Parts{1}));
  EXPECT_EQ(outwards(testing::merged(a, b)), std::make_pair(std::size_t{2}, Parts{1, 1}));
  EXPECT_EQ(outwards(inside_out), std::make_pair(std::size_t{0}, Parts{0}));
  EXPECT_EQ(outwards(testing::merged(a, inside_out)), std::make_pair(std::size_t{1}, Parts{1, 0}));
  const Mesh open = testing::box({0, 0, 0}, {1, 1, 1}, false);
  EXPECT_EQ(outwards(testing::merged(open, b)), std::make_pair(std::size_t{1}, Parts{0, 1}));
  EXPECT_EQ(outwards(testing::tetrahedron({0, 0, 0}, 2)), std::make_pair(std::size_t{1}, Parts{1}));
}

// Parts are the faces joined through shared vertices, numbered in order of their first face;
// two shells touching at one vertex are one part, and a vertex no face uses has none.
TEST(Topology, PartsAreNumberedInFaceOrder) {
  Mesh m;
  add_triangle(m, {5, 0, 0}, {6, 0, 0}, {5, 1, 0});  // part 0
  add_triangle(m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});  // part 1
  add_triangle(m, {6, 0, 0}, {7, 0, 0}, {6, 1, 0});  // touches the first at (6, 0, 0): part 0
  m.positions.emplace_back(9, 9, 9);                 // used by no face
  const Topology t = build_topology(m);
  ASSERT_EQ(t.part_count(), 2u);
  ASSERT_EQ(t.vertex_part.size(), t.positions.size());
  for (std::size_t f = 0; f < t.face_count(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(t.vertex_part[t.face_vertices[3 * f + k]], f == 1 ? 1u : 0u) << f;
  EXPECT_EQ(t.vertex_part[t.vertex_remap[9]], Topology::kNoPart);
}

TEST(Topology, FrameBytesCountsTheFlatArraysOfTheSidePass) {
  const Topology cube = build_topology(testing::box({0, 0, 0}, {1, 1, 1}));
  // 12 planes of 16 B, 18 regular edges of two 4-byte faces, one irregular offset.
  EXPECT_EQ(cube.frame_bytes(), 12u * 16u + 18u * 8u + 1u * 4u);
  // A fan of three faces: 19 regular edges, 1 irregular (vertex pair, 2 offsets, 3 references).
  const Topology fin = build_topology(testing::adversarial_meshes(1)[6].mesh);
  ASSERT_EQ(testing::adversarial_meshes(1)[6].name, "fin_nonmanifold");
  EXPECT_EQ(fin.frame_bytes(), 13u * 16u + 19u * 8u + 8u + 2u * 4u + 3u * 4u);
}

TEST(Topology, FacePlanesScaleByAPowerOfTwo) {
  Mesh m;
  add_triangle(m, {0, 0, 3}, {12, 0, 3}, {0, 12, 3});  // n = (0, 0, 144) -> 144 / 256
  const Topology t = build_topology(m);
  EXPECT_EQ(t.face_planes[0], glm::vec4(0, 0, 0.5625f, -1.6875f));
}

}  // namespace
}  // namespace shadowvol
