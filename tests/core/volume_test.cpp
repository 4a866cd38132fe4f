// Hand-worked volumes: a single triangle and a cube under a light straight above.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/topology.h"
#include "core/volume.h"
#include "test_meshes.h"

namespace shadowvol {
namespace {

VolumeBuffer build(const Mesh& mesh, glm::vec4 light, Generator g, bool caps = true) {
  const Topology topo = build_topology(mesh);
  VolumeBuffer out;
  VolumeScratch scratch;
  build_volume(topo, light, {g, caps}, scratch, out);
  return out;
}

std::vector<int> sorted_weights(const PrimitiveList& list) {
  std::vector<int> w(list.weights.begin(), list.weights.end());
  std::sort(w.begin(), w.end());
  return w;
}

TEST(Volume, SingleTriangleUnderAPointLight) {
  Mesh tri;
  testing::add_triangle(tri, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});  // normal +z
  const VolumeBuffer v = build(tri, {0, 0, 10, 1}, Generator::multiplicity);
  // Each edge of an open triangle is stored in the direction the triangle runs it: weight +1.
  EXPECT_EQ(sorted_weights(v.sides), (std::vector<int>{1, 1, 1}));
  ASSERT_EQ(v.light_caps.size(), 1u);
  EXPECT_EQ(v.light_caps.weights[0], 1);
  EXPECT_EQ(v.light_caps.vertices[1], glm::vec4(1, 0, 0, 1));  // own order, unchanged
  ASSERT_EQ(v.dark_caps.size(), 1u);
  EXPECT_EQ(v.dark_caps.weights[0], -1);
  EXPECT_EQ(v.dark_caps.vertices[1], glm::vec4(1, 0, -10, 0));  // vertex minus light, w = 0
  // First quad is edge 0 -> 1: (u, u_inf, v_inf, v).
  const glm::vec4 expected[4] = {{0, 0, 0, 1}, {0, 0, -10, 0}, {1, 0, -10, 0}, {1, 0, 0, 1}};
  for (int k = 0; k < 4; ++k) EXPECT_EQ(v.sides.vertices[k], expected[k]) << k;
}

TEST(Volume, TriangleFacingAwayGetsNegatedWeightsNotReversedVertices) {
  Mesh tri;
  testing::add_triangle(tri, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const VolumeBuffer v = build(tri, {0, 0, -10, 1}, Generator::multiplicity);
  EXPECT_EQ(sorted_weights(v.sides), (std::vector<int>{-1, -1, -1}));
  EXPECT_EQ(v.light_caps.weights[0], -1);
  EXPECT_EQ(v.light_caps.vertices[0], glm::vec4(0, 0, 0, 1));
  EXPECT_EQ(v.dark_caps.weights[0], 1);
}

TEST(Volume, EdgeOnTriangleCastsNothing) {
  Mesh tri;
  testing::add_triangle(tri, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  EXPECT_EQ(build(tri, {5, 5, 0, 1}, Generator::multiplicity).primitive_count(), 0u);
  EXPECT_EQ(build(tri, {1, 0, 0, 0}, Generator::robust).primitive_count(), 0u);
}

TEST(Volume, FacingIsRightWhereFloatRoundingCannotTell) {
  // A face a million units out and a light 1/16 above or below its plane: the float dot product
  // cancels to within its own rounding, so the pass must decide these faces in double.
  Mesh tri;
  testing::add_triangle(tri, {0, 0, 1e6f}, {1, 0, 1e6f}, {0, 1, 1e6f});  // normal +z
  const Topology topo = build_topology(tri);
  std::vector<std::int8_t> weights(weight_buffer_size(topo), 0);
  compute_face_weights(topo, {0, 0, 1e6f + 0.0625f, 1}, Generator::multiplicity, {0, 1}, weights);
  EXPECT_EQ(weights[0], 1);
  compute_face_weights(topo, {0, 0, 1e6f - 0.0625f, 1}, Generator::multiplicity, {0, 1}, weights);
  EXPECT_EQ(weights[0], -1);
  compute_face_weights(topo, {5, 7, 1e6f, 1}, Generator::multiplicity, {0, 1}, weights);
  EXPECT_EQ(weights[0], 0);  // in the plane
  compute_face_weights(topo, {0, 0, 1e6f - 0.0625f, 1}, Generator::standard, {0, 1}, weights);
  EXPECT_EQ(weights[0], 0);  // standard: back faces weigh 0
}

TEST(Volume, DirectionalLightsHaveNoDarkCaps) {
  Mesh tri;
  testing::add_triangle(tri, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const VolumeBuffer v = build(tri, {0.2f, 0.1f, 1, 0}, Generator::multiplicity);
  EXPECT_EQ(v.sides.size(), 3u);
  EXPECT_EQ(v.light_caps.size(), 1u);
  EXPECT_EQ(v.dark_caps.size(), 0u);
  EXPECT_EQ(v.sides.vertices[1], glm::vec4(-0.2f, -0.1f, -1, 0));  // extrusion along -direction
}

TEST(Volume, CubeUnderALightAboveEachGenerator) {
  const Mesh cube = testing::box({-1, -1, -1}, {1, 1, 1});
  const glm::vec4 light(0, 0, 100, 1);  // only the two top triangles face it
  // An edge runs the direction of its lower-numbered face, which may face the light or not: a
  // silhouette quad's weight is +-1 (standard, robust) or +-2 (multiplicity), by that choice.
  auto magnitudes = [](const PrimitiveList& list) {
    std::vector<int> w;
    for (int x : list.weights) w.push_back(std::abs(x));
    std::sort(w.begin(), w.end());
    return w;
  };
  const VolumeBuffer standard = build(cube, light, Generator::standard);
  EXPECT_EQ(magnitudes(standard.sides), (std::vector<int>{1, 1, 1, 1}));
  EXPECT_EQ(standard.light_caps.size(), 2u);  // front faces
  EXPECT_EQ(standard.dark_caps.size(), 10u);  // back faces at infinity
  const VolumeBuffer multiplicity = build(cube, light, Generator::multiplicity);
  EXPECT_EQ(magnitudes(multiplicity.sides), (std::vector<int>{2, 2, 2, 2}));
  EXPECT_EQ(multiplicity.light_caps.size(), 12u);
  EXPECT_EQ(multiplicity.dark_caps.size(), 12u);
  const VolumeBuffer robust = build(cube, light, Generator::robust);
  EXPECT_EQ(robust.sides.size(), 8u);  // each silhouette edge once per face (GPU Gems 3 §11.3.1)
  EXPECT_EQ(magnitudes(robust.sides), (std::vector<int>(8, 1)));
  // The two quads of one edge cancel in z-pass count only if they had the same sign; they close
  // two different parts, so they carry opposite facings and the same sign along the edge.
  for (std::size_t q = 0; q < robust.sides.size(); q += 2)
    EXPECT_EQ(robust.sides.weights[q], robust.sides.weights[q + 1]);
  // auto picks standard for the closed cube; z-pass needs no caps.
  const VolumeBuffer automatic = build(cube, light, Generator::automatic, false);
  EXPECT_EQ(automatic.sides.weights, standard.sides.weights);
  EXPECT_EQ(automatic.light_caps.size() + automatic.dark_caps.size(), 0u);
}

TEST(Volume, BufferIsReusedWithoutReallocating) {
  const Topology topo = build_topology(testing::box({-1, -1, -1}, {1, 1, 1}));
  VolumeBuffer out;
  VolumeScratch scratch;
  build_volume(topo, {3, 2, 5, 1}, {}, scratch, out);
  const VolumeBuffer first = out;
  const glm::vec4* storage = out.sides.vertices.data();
  build_volume(topo, {3, 2, 5, 1}, {}, scratch, out);
  EXPECT_EQ(out.sides.vertices.data(), storage);
  EXPECT_EQ(out.sides.vertices, first.sides.vertices);
  EXPECT_EQ(out.dark_caps.weights, first.dark_caps.weights);
}

// A primitive as sortable values: its part, weight and vertices.
using Primitive = std::vector<float>;
std::vector<Primitive> primitives_of(const PrimitiveList& list, int corners,
                                     std::uint32_t only_part, bool has_parts) {
  std::vector<Primitive> out;
  for (std::size_t p = 0; p < list.size(); ++p) {
    if (has_parts && list.parts[p] != only_part) continue;
    Primitive v{static_cast<float>(list.weights[p])};
    for (int k = 0; k < corners; ++k)
      for (int c = 0; c < 4; ++c) v.push_back(list.vertices[p * corners + k][c]);
    out.push_back(v);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// VolumeOptions::parts: the primitives a mesh's volume tags with part p are exactly the volume
// that part alone casts (in another order), on every test mesh, for every generator that takes
// it, and with or without caps; without the option, nothing is recorded.
TEST(Volume, EachPartsPrimitivesAreThatPartsOwnVolume) {
  // Above every mesh; the far plane y = -100 below all of them (core/volume.h's precondition).
  const glm::vec4 light(7.0f, 400.0f, 23.0f, 1.0f), far(0.0f, -1.0f, 0.0f, -100.0f);
  for (const testing::NamedMesh& named : testing::adversarial_meshes(11)) {
    const Topology topo = build_topology(named.mesh);
    for (const Generator g : {Generator::automatic, Generator::robust, Generator::multiplicity}) {
      const Generator resolved = resolve_generator(g, topo.report);
      VolumeBuffer whole, plain, own;
      VolumeScratch scratch;
      build_volume(topo, light, {resolved, true, kPlaneAtInfinity, true}, scratch, whole);
      build_volume(topo, light, {resolved, true, kPlaneAtInfinity, false}, scratch, plain);
      EXPECT_TRUE(plain.sides.parts.empty() && plain.light_caps.parts.empty());
      ASSERT_EQ(whole.sides.parts.size(), whole.sides.size());
      for (std::uint32_t part = 0; part < topo.part_count(); ++part) {
        SCOPED_TRACE(named.name + ", part " + std::to_string(part) + ", " +
                     std::string(to_string(g)));
        Mesh alone;  // the part's faces, over the welded positions
        alone.positions = topo.positions;
        for (std::size_t f = 0; f < topo.face_count(); ++f)
          if (topo.vertex_part[topo.face_vertices[3 * f]] == part)
            alone.indices.insert(alone.indices.end(), &topo.face_vertices[3 * f],
                                 &topo.face_vertices[3 * f + 3]);
        for (const glm::vec4 far_plane : {kPlaneAtInfinity, far}) {
          build_volume(topo, light, {resolved, true, far_plane, true}, scratch, whole);
          build_volume(build_topology(alone), light, {resolved, true, far_plane}, scratch, own);
          EXPECT_EQ(primitives_of(whole.sides, kQuadCorners, part, true),
                    primitives_of(own.sides, kQuadCorners, 0, false));
          EXPECT_EQ(primitives_of(whole.light_caps, kTriangleCorners, part, true),
                    primitives_of(own.light_caps, kTriangleCorners, 0, false));
          EXPECT_EQ(primitives_of(whole.dark_caps, kTriangleCorners, part, true),
                    primitives_of(own.dark_caps, kTriangleCorners, 0, false));
        }
      }
    }
  }
}

TEST(Lights, CheckRefusesWhatIsNotALight) {
  EXPECT_TRUE(check_light({1, 2, 3, 1}).ok());
  EXPECT_TRUE(check_light({0, 0, 1, 0}).ok());
  EXPECT_FALSE(check_light({0, 0, 0, 0}).ok());
  EXPECT_FALSE(check_light({1, 2, 3, 2}).ok());
  EXPECT_FALSE(check_light({std::nanf(""), 0, 1, 1}).ok());
  EXPECT_FALSE(check_light({std::numeric_limits<float>::infinity(), 0, 1, 0}).ok());
}

TEST(Generators, ParseResolveAndCheck) {
  EXPECT_EQ(*parse_generator("robust"), Generator::robust);
  EXPECT_EQ(*parse_generator("auto"), Generator::automatic);
  auto bad = parse_generator("fast");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message,
            "unknown generator 'fast': expected standard, robust, multiplicity or auto");

  const Topology closed = build_topology(testing::box({0, 0, 0}, {1, 1, 1}));
  const Topology open = build_topology(testing::box({0, 0, 0}, {1, 1, 1}, false));
  EXPECT_EQ(resolve_generator(Generator::automatic, closed.report), Generator::standard);
  EXPECT_EQ(resolve_generator(Generator::automatic, open.report), Generator::multiplicity);
  EXPECT_EQ(resolve_generator(Generator::robust, closed.report), Generator::robust);
  EXPECT_TRUE(check_generator(Generator::standard, closed.report, "box").ok());
  auto refused = check_generator(Generator::standard, open.report, "open_box.obj");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message.rfind("open_box.obj: the standard generator needs a closed "
                                          "2-manifold, but this mesh has 4 boundary",
                                          0),
            0u);
  EXPECT_TRUE(check_generator(Generator::multiplicity, open.report, "open").ok());
}

// CC shadow volumes §3.3: a square of two triangles under a light straight above, its triangles
// in two leaves. Kept alike, the shared diagonal cancels: 4 quads, as for one leaf. Kept apart,
// the diagonal casts where only one side's interval holds it.
TEST(Volume, ClampedLeavesDrawASharedEdgeOnlyWhereTheirIntervalsDiffer) {
  Mesh square;
  square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  square.indices = {0, 1, 2, 0, 2, 3};  // facing +z, the light
  const Topology topo = build_topology(square);
  const std::vector<std::uint32_t> leaves{0, 1};
  std::vector<std::uint32_t> vertex_offsets, vertex_leaves;
  build_vertex_leaves(topo, leaves, vertex_offsets, vertex_leaves);
  EXPECT_EQ(vertex_offsets, (std::vector<std::uint32_t>{0, 2, 3, 5, 6}));  // 0 and 2: both
  VolumeClamp clamp;
  clamp.depth = {0, 0, -1, 0};  // depth = -z: growing downwards, away from the light
  clamp.face_leaf = leaves;
  clamp.vertex_leaf_offsets = vertex_offsets;
  clamp.vertex_leaves = vertex_leaves;
  auto build_clamped = [&] {
    VolumeBuffer out;
    VolumeScratch scratch;
    build_volume(topo, {0.5f, 0.5f, 10, 1}, {Generator::multiplicity, true}, scratch, out, &clamp);
    return out;
  };
  clamp.intervals = {{-INFINITY, 1}, {3, 4}, {-INFINITY, 1}, {3, 4}};
  clamp.offsets = {0, 2, 4};
  VolumeBuffer alike = build_clamped();
  EXPECT_EQ(alike.sides.size(), 8u);  // 4 boundary edges x 2 segments, no diagonal
  EXPECT_EQ(alike.light_caps.size(), 2u);
  EXPECT_EQ(alike.dark_caps.size(), 6u);  // per face: the far cap at 1, both caps of [3, 4]
  // The second segment of an edge starts on the plane z = -3 and ends on z = -4.
  for (std::size_t q = 0; q < alike.sides.size(); ++q) {
    const glm::vec4* v = &alike.sides.vertices[4 * q];
    const float start = v[0].z / v[0].w, end = v[1].z / v[1].w;
    EXPECT_TRUE((start == 0 && end == -1) || (start == -3 && end == -4)) << q;
  }
  clamp.intervals = {{-INFINITY, 1}, {-INFINITY, 4}};  // leaf 1 reaches on to 4
  clamp.offsets = {0, 1, 2};
  VolumeBuffer apart = build_clamped();
  // Leaf 0's two boundary edges from the square to 1; leaf 1's two to 4, each cut at 1 on the ray
  // of its vertex that leaf 0 shares (a quad and a triangle: no T-junction where leaf 0's pieces
  // end); the diagonal once, from 1 to 4, leaf 1's term alone.
  ASSERT_EQ(apart.sides.size(), 7u);
  int diagonal = 0, triangles = 0;
  for (std::size_t q = 0; q < apart.sides.size(); ++q) {
    const glm::vec4* v = &apart.sides.vertices[4 * q];
    EXPECT_EQ(std::abs(apart.sides.weights[q]), 1);
    triangles += v[0] == v[1] || v[2] == v[3];
    for (int k = 0; k < 4; ++k) {  // every corner on a plane some leaf ends at, or the square
      const float z = v[k].z / v[k].w;
      EXPECT_TRUE(z == 0.0f || z == -1.0f || z == -4.0f) << q << " " << k << " " << z;
    }
    if (v[0].w == 1.0f || v[3].w == 1.0f) continue;  // starts at the caster: a boundary edge
    ++diagonal;
    EXPECT_FLOAT_EQ(v[0].z / v[0].w, -1.0f);
    EXPECT_FLOAT_EQ(v[1].z / v[1].w, -4.0f);
  }
  EXPECT_EQ(diagonal, 1);
  EXPECT_EQ(triangles, 2);
  // Leaf 0 culled: leaf 1's triangle alone, its three edges and caps.
  clamp.intervals = {{-INFINITY, 4}};
  clamp.offsets = {0, 0, 1};
  VolumeBuffer one = build_clamped();
  EXPECT_EQ(one.sides.size(), 3u);
  EXPECT_EQ(one.light_caps.size(), 1u);
  EXPECT_EQ(one.dark_caps.size(), 1u);
}

}  // namespace
}  // namespace shadowvol
