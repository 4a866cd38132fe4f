// The law of shadow volumes, as a property test in exact arithmetic.
//
// For every adversarial mesh, random point and directional lights, and every generator:
//   z-pass form: for random points P, the signed number of volume primitives crossed by the
//     segment from a reference point O (outside every shadow) to P
//   z-fail form: minus the signed number crossed by the ray from P away from O, to infinity,
//     where it ends on the dark caps
// both equal the number of caster surfaces crossed by the segment from P to the light (all
// surfaces for multiplicity and robust, the light-facing ones for standard; Kim et al. §1.2).
//
// "Signed": a primitive of weight w crossed from its front side counts +w, from behind -w.
// Rays through edges, vertices or planes: every predicate is exact (integer coordinates,
// __int128 determinants), so such a sample is detected, never misjudged, and is replaced by a
// new random sample. The test asserts that these replacements stay rare.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <sstream>

#include "core/topology.h"
#include "core/volume.h"
#include "exact_predicates.h"
#include "test_meshes.h"

namespace shadowvol {
namespace {

using testing::Crossing;
using testing::HPoint;

struct Counts {
  long long value = 0;
  bool ambiguous = false;
};

// Caster surfaces crossed by the segment from P to the light (the light itself excluded: a face
// whose plane contains the light cannot be crossed before the light is reached).
// `counts(f)`: whether face f counts at all (a clamped volume's leaf holds P's depth).
template <class Counted = bool (*)(std::size_t)>
Counts caster_count(
    const Topology& topo, const HPoint& p, const HPoint& light, bool front_only,
    Counted&& counts = [](std::size_t) { return true; }) {
  Counts n;
  for (std::size_t f = 0; f < topo.face_count(); ++f) {
    if (!counts(f)) continue;
    const HPoint x0 = testing::exact(glm::vec4(topo.positions[topo.face_vertices[3 * f]], 1));
    const HPoint x1 = testing::exact(glm::vec4(topo.positions[topo.face_vertices[3 * f + 1]], 1));
    const HPoint x2 = testing::exact(glm::vec4(topo.positions[topo.face_vertices[3 * f + 2]], 1));
    if (testing::degenerate(x0, x1, x2)) continue;
    const int facing = testing::side(x0, x1, x2, light);
    if (facing == 0) continue;
    if (front_only && facing < 0) continue;
    const Crossing c = testing::segment_crosses(p, light, x0, x1, x2);
    if (c == Crossing::ambiguous) n.ambiguous = true;
    if (c == Crossing::crossed) ++n.value;
  }
  return n;
}

// O: a far point whose own segment to the light crosses no caster, i.e. outside every shadow;
// false where none is found (a light inside a closed solid).
bool far_lit_point(const Topology& topo, const HPoint& light, std::mt19937& rng, HPoint& o) {
  std::uniform_int_distribution<int> far(-3000, 3000);
  for (int attempt = 0; attempt < 200; ++attempt) {
    o = {far(rng), far(rng), far(rng), 1};
    const Counts c = caster_count(topo, o, light, false);
    if (!c.ambiguous && c.value == 0) return true;
  }
  return false;
}

// Signed crossings of every primitive of `list` (kCorners vertices each; quads split as the
// renderer splits them) by the segment a -> b, each counted with the side `a` is on.
void add_crossings(const PrimitiveList& list, int corners, const HPoint& a, const HPoint& b,
                   Counts& n) {
  for (std::size_t i = 0; i < list.size(); ++i) {
    const glm::vec4* v = &list.vertices[corners * i];
    const int triangles = corners == kQuadCorners ? 2 : 1;
    for (int t = 0; t < triangles; ++t) {
      const int* k = &kQuadTriangles[3 * t];
      const HPoint x0 = testing::exact(v[k[0]]), x1 = testing::exact(v[k[1]]),
                   x2 = testing::exact(v[k[2]]);
      const Crossing c = testing::segment_crosses(a, b, x0, x1, x2);
      if (c == Crossing::ambiguous) n.ambiguous = true;
      if (c == Crossing::crossed) n.value += list.weights[i] * testing::side(x0, x1, x2, a);
    }
  }
}

// z-pass: crossings on the way from O to P (which reach dark caps on a finite far plane only).
Counts zpass_count(const VolumeBuffer& volume, const HPoint& o, const HPoint& p) {
  Counts n;
  add_crossings(volume.sides, kQuadCorners, o, p, n);
  add_crossings(volume.light_caps, kTriangleCorners, o, p, n);
  add_crossings(volume.dark_caps, kTriangleCorners, o, p, n);
  return n;
}

// The point at infinity in the direction from finite point `from` to finite point `to`.
HPoint direction(const HPoint& from, const HPoint& to) {
  return {to[0] * from[3] - from[0] * to[3], to[1] * from[3] - from[1] * to[3],
          to[2] * from[3] - from[2] * to[3], 0};
}

// z-fail: minus the crossings on the way from P to `end`, a point at infinity. Any direction
// will do: the ray ends at infinity, beyond every finite far plane; at infinity, where dark caps
// extruded to infinity lie, it meets one iff its direction is inside it, and beyond infinity
// (the depth-clamped far plane) nothing is shadowed.
Counts zfail_count(const VolumeBuffer& volume, const HPoint& p, const HPoint& end) {
  Counts n;
  add_crossings(volume.sides, kQuadCorners, p, end, n);
  add_crossings(volume.light_caps, kTriangleCorners, p, end, n);
  const PrimitiveList& dark = volume.dark_caps;
  for (std::size_t i = 0; i < dark.size(); ++i) {
    if (dark.vertices[3 * i].w != 0.0f) {  // a finite cap: crossed or not, like any other
      PrimitiveList one;
      const PrimitiveSpan at = one.grow(1, kTriangleCorners);
      std::copy_n(&dark.vertices[3 * i], 3, at.vertices);
      at.weights[0] = dark.weights[i];
      add_crossings(one, kTriangleCorners, p, end, n);
      continue;
    }
    const HPoint x0 = testing::exact(dark.vertices[3 * i]),
                 x1 = testing::exact(dark.vertices[3 * i + 1]),
                 x2 = testing::exact(dark.vertices[3 * i + 2]);
    const Crossing c = testing::direction_inside(end, x0, x1, x2);
    if (c == Crossing::ambiguous) n.ambiguous = true;
    if (c == Crossing::crossed) n.value += dark.weights[i] * testing::side(x0, x1, x2, p);
  }
  n.value = -n.value;
  return n;
}

struct LawStats {
  int checked = 0;
  int in_shadow = 0;  // samples with at least one caster surface towards the light
  long long deepest = 0;
  int resampled = 0;
  int skipped_lights = 0;
  int beyond_far_plane = 0;  // samples redrawn because they lay past a finite far plane
  std::vector<std::string> failures;
};

// A far plane with integer coefficients that ends every extrusion of this mesh `margin` beyond
// its farthest vertex, seen from the light; the plane at infinity if none can (a light among the
// vertices, seen from it in directions more than 90 degrees apart).
glm::vec4 far_plane_beyond(const Topology& topo, const glm::vec4& light, float margin) {
  // Towards the meshes (about the origin), in small integers so that the extruded vertices stay
  // integers a float holds exactly.
  const glm::vec3 l(light);
  const glm::vec3 n = glm::round(-l / std::max({std::abs(l.x), std::abs(l.y), std::abs(l.z)}) *
                                 (light.w == 0.0f ? 16.0f : 4.0f));
  if (light.w != 0.0f)
    for (const glm::vec3& p : topo.positions)
      if (glm::dot(n, p - glm::vec3(light)) <= 0.0f) return kPlaneAtInfinity;
  float farthest = -1e30f;
  for (const glm::vec3& p : topo.positions) farthest = std::max(farthest, glm::dot(n, p));
  return glm::vec4(n, -std::ceil(farthest + margin * glm::length(n)));
}

// A point (homogeneous, w > 0) on the kept side of the far plane.
bool before_plane(const HPoint& p, const glm::vec4& plane) {
  return plane.x * double(p[0]) + plane.y * double(p[1]) + plane.z * double(p[2]) +
             plane.w * double(p[3]) <
         0.0;
}

void check_law(const testing::NamedMesh& named, const glm::vec4& light, Generator generator,
               std::mt19937& rng, LawStats& stats, bool finite_far = false) {
  const Topology topo = build_topology(named.mesh);
  VolumeBuffer volume;
  VolumeScratch scratch;
  VolumeOptions options{generator, true};
  if (finite_far) options.far_plane = far_plane_beyond(topo, light, 40.0f);
  if (finite_far && options.far_plane == kPlaneAtInfinity) {
    ++stats.skipped_lights;
    return;
  }
  build_volume(topo, light, options, scratch, volume);
  const std::vector<std::int8_t>& weights = scratch.weights;
  const Generator used = resolve_generator(generator, topo.report);
  const bool front_only = used == Generator::standard;
  const HPoint l = testing::exact(light);

  HPoint o{};
  if (!far_lit_point(topo, l, rng, o)) {  // e.g. a light inside a closed solid: nothing is lit
    ++stats.skipped_lights;
    return;
  }

  // Half the samples anywhere around the casters, half behind a random caster point as seen
  // from the light, so that shadows and overlaps are well sampled. Samples lie on a grid of
  // sevenths (w = 7), off the integer planes of the meshes' faces, so few rays meet an edge.
  constexpr int kGrid = 7;
  std::uniform_int_distribution<int> near(-120 * kGrid, 120 * kGrid);
  // Only faces that face the light (robust: or turn away from it), never edge-on ones (which
  // standard weighs 1): a point behind an edge-on face lies in its plane, a genuinely
  // ambiguous sample.
  std::vector<std::int8_t> facing(weights.size());
  compute_face_weights(topo, light, Generator::robust, {0, topo.face_count()}, facing);
  std::vector<std::size_t> lit_faces;
  for (std::size_t f = 0; f < topo.face_count(); ++f)
    if (weights[f] != 0 && facing[f] != 0) lit_faces.push_back(f);
  std::uniform_int_distribution<std::size_t> pick_face(
      0, std::max<std::size_t>(lit_faces.size(), 1) - 1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  auto behind_caster = [&]() -> HPoint {
    const std::size_t f = lit_faces[pick_face(rng)];
    float a = unit(rng), b = unit(rng);
    if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
    const glm::vec3 q = topo.positions[topo.face_vertices[3 * f]] * (1.0f - a - b) +
                        topo.positions[topo.face_vertices[3 * f + 1]] * a +
                        topo.positions[topo.face_vertices[3 * f + 2]] * b;
    const glm::vec3 away = light.w == 0.0f ? -glm::vec3(light) * 4.0f : q - glm::vec3(light);
    const glm::vec3 p = glm::round((q + away * unit(rng) * 0.8f) * float(kGrid));
    return {std::int64_t(p.x), std::int64_t(p.y), std::int64_t(p.z), kGrid};
  };
  for (int sample = 0; sample < 60; ++sample) {
    HPoint p{};
    Counts expected, zpass, zfail;
    int tries = 0, beyond = 0;
    do {
      if (tries++ > 0) ++stats.resampled;
      p = sample % 2 && !lit_faces.empty() ? behind_caster()
                                           : HPoint{near(rng), near(rng), near(rng), kGrid};
      if (!before_plane(p, options.far_plane)) {  // the law holds on the kept side only
        ++stats.beyond_far_plane;
        if (++beyond < 1000) --tries;
        expected.ambiguous = true;
        continue;
      }
      expected = caster_count(topo, p, l, front_only);
      zpass = zpass_count(volume, o, p);
      // The ray away from O, or for point lights every other time the ray away from the light,
      // which ends on the dark caps whenever P is in shadow.
      const bool away_from_light = l[3] != 0 && sample % 4 >= 2;
      zfail = zfail_count(volume, p, away_from_light ? direction(l, p) : direction(o, p));
    } while ((expected.ambiguous || zpass.ambiguous || zfail.ambiguous) && tries < 50);
    ASSERT_LT(tries, 50) << "no unambiguous sample for " << named.name;
    ++stats.checked;
    stats.in_shadow += expected.value > 0;
    stats.deepest = std::max(stats.deepest, expected.value);
    if (zpass.value != expected.value || zfail.value != expected.value) {
      std::ostringstream msg;
      msg << named.name << " generator=" << to_string(generator) << " light=(" << light.x << ","
          << light.y << "," << light.z << "," << light.w << ") P=(" << p[0] << "," << p[1] << ","
          << p[2] << ")/" << p[3] << ": surfaces=" << expected.value << " zpass=" << zpass.value
          << " zfail=" << zfail.value;
      stats.failures.push_back(msg.str());
    }
  }
}

glm::vec4 random_light(std::mt19937& rng, bool directional) {
  if (directional) {
    std::uniform_int_distribution<int> d(-16, 16);
    glm::vec4 l(0.0f);
    while (l.x == 0 && l.y == 0 && l.z == 0) l = glm::vec4(d(rng), d(rng), d(rng), 0);
    return l;
  }
  std::uniform_int_distribution<int> p(-160, 160);
  return glm::vec4(p(rng), p(rng), p(rng), 1);
}

}  // namespace

void PrintTo(Generator g, std::ostream* os) { *os << to_string(g); }

namespace {

class VolumeLaw : public ::testing::TestWithParam<Generator> {};

TEST_P(VolumeLaw, CountEqualsCasterSurfacesBetweenPointAndLight) {
  const Generator generator = GetParam();
  std::mt19937 rng(1234u + static_cast<unsigned>(generator));
  LawStats stats;
  int meshes = 0;
  for (const testing::NamedMesh& named : testing::adversarial_meshes(42)) {
    const Topology topo = build_topology(named.mesh);
    if (generator == Generator::standard && !topo.report.closed_manifold) continue;
    ++meshes;
    for (int i = 0; i < 6; ++i)
      check_law(named, random_light(rng, i % 3 == 2), generator, rng, stats);
    for (int i = 0; i < 4; ++i)  // the same volumes ended on a finite far plane
      check_law(named, random_light(rng, i % 2 == 1), generator, rng, stats, true);
    // Lights on the planes of the axis-aligned faces: facing 0 on those faces.
    check_law(named, glm::vec4(16, 40, 16, 1), generator, rng, stats);
    check_law(named, glm::vec4(0, 0, 1, 0), generator, rng, stats);
  }
  for (std::size_t i = 0; i < std::min<std::size_t>(stats.failures.size(), 10); ++i)
    ADD_FAILURE() << stats.failures[i];
  EXPECT_TRUE(stats.failures.empty())
      << stats.failures.size() << " of " << stats.checked << " samples broke the law";
  // The test must have tested: most lights usable, most samples unambiguous at first draw.
  EXPECT_GE(meshes, generator == Generator::standard ? 4 : 14);
  EXPECT_GE(stats.checked, meshes * 12 * 60 * 3 / 4);
  EXPECT_LT(stats.resampled, stats.checked / 20);
  EXPECT_GT(stats.in_shadow, stats.checked / 4);  // shadows were there to be counted
  EXPECT_GE(stats.deepest, generator == Generator::standard ? 2 : 4);
  std::cout << "[ law ] " << to_string(generator) << ": " << stats.checked << " samples on "
            << meshes << " meshes, " << stats.in_shadow << " in shadow (up to " << stats.deepest
            << " surfaces deep), " << stats.resampled << " redrawn (ray through an edge), "
            << stats.skipped_lights << " lights with no lit far point or no far plane, "
            << stats.beyond_far_plane << " drawn past a far plane\n";
}

// --- clamped volumes (core/volume.h VolumeClamp; CC shadow volumes §3.2.1, §3.3) ---------------

// Whether depth(P) = dot(depth, P) / w lies in an interval of `intervals`; ambiguous on a bound.
bool in_intervals(std::span<const DepthInterval> intervals, const glm::vec4& depth, const HPoint& p,
                  bool& ambiguous) {
  const std::int64_t scaled = std::int64_t(depth.x) * p[0] + std::int64_t(depth.y) * p[1] +
                              std::int64_t(depth.z) * p[2] + std::int64_t(depth.w) * p[3];
  bool inside = false;
  for (const DepthInterval& i : intervals) {
    for (float bound : {i.begin, i.end})
      if (std::isfinite(bound) && scaled == std::int64_t(bound) * p[3]) ambiguous = true;
    const bool after = i.begin == -INFINITY || scaled > std::int64_t(i.begin) * p[3];
    const bool before = i.end == INFINITY || scaled < std::int64_t(i.end) * p[3];
    inside = inside || (after && before);
  }
  return inside;
}

// Three leaves (faces by index, mod 3) of the mesh, clamped along integer depth planes that face
// away from the light: leaf 0 kept near itself, over a gap, and from further on to the far plane;
// leaf 1 over one long interval from itself; leaf 2 culled (no intervals) or kept whole. False
// where no such depth exists (a point light among the vertices).
struct TestLeaves {
  std::vector<std::uint32_t> face_leaf, vertex_offsets, vertex_leaves;
};

bool make_test_clamp(const Topology& topo, const glm::vec4& light, bool cull_leaf2,
                     TestLeaves& leaves, VolumeClamp& clamp) {
  std::vector<std::uint32_t>& face_leaf = leaves.face_leaf;
  const glm::vec3 l(light);
  const glm::vec3 n = glm::round(-l / std::max({std::abs(l.x), std::abs(l.y), std::abs(l.z)}) *
                                 (light.w == 0.0f ? 16.0f : 4.0f));
  std::array<float, 3> deepest{-1e30f, -1e30f, -1e30f};
  face_leaf.resize(topo.face_count());
  for (std::size_t f = 0; f < topo.face_count(); ++f) {
    face_leaf[f] = static_cast<std::uint32_t>(f % 3);
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& p = topo.positions[topo.face_vertices[3 * f + k]];
      if (light.w != 0.0f && glm::dot(n, p - l) <= 0.0f) return false;
      deepest[f % 3] = std::max(deepest[f % 3], glm::dot(n, p));
    }
  }
  for (float& d : deepest)  // a leaf without faces (a mesh of one or two): bounds like leaf 0's
    if (d == -1e30f) d = std::max({deepest[0], deepest[1], deepest[2]});
  const float unit = glm::length(n);
  auto at = [&](int leaf, float steps) { return std::ceil(deepest[leaf] + steps * unit); };
  clamp.depth = glm::vec4(n, 0.0f);
  clamp.face_leaf = face_leaf;
  build_vertex_leaves(topo, face_leaf, leaves.vertex_offsets, leaves.vertex_leaves);
  clamp.vertex_leaf_offsets = leaves.vertex_offsets;
  clamp.vertex_leaves = leaves.vertex_leaves;
  clamp.intervals = {
      {-INFINITY, at(0, 4)}, {at(0, 25), at(0, 50)}, {at(0, 80), INFINITY}, {-INFINITY, at(1, 60)}};
  clamp.offsets = {0, 3, 4, 4};
  if (!cull_leaf2) {
    clamp.intervals.push_back({-INFINITY, INFINITY});
    clamp.offsets.back() = 5;
  }
  return true;
}

struct ClampedLawStats {
  int checked = 0, in_shadow = 0, clamped_away = 0, lights = 0;
  std::vector<std::string> failures;
};

void check_clamped_law(const testing::NamedMesh& named, const glm::vec4& light, Generator generator,
                       bool cull_leaf2, std::mt19937& rng, ClampedLawStats& stats) {
  const Topology topo = build_topology(named.mesh);
  TestLeaves leaves;
  VolumeClamp clamp;
  if (!make_test_clamp(topo, light, cull_leaf2, leaves, clamp)) return;
  const std::vector<std::uint32_t>& face_leaf = leaves.face_leaf;
  VolumeBuffer volume;
  VolumeScratch scratch;
  build_volume(topo, light, {generator, true}, scratch, volume, &clamp);
  const bool front_only = resolve_generator(generator, topo.report) == Generator::standard;
  const HPoint l = testing::exact(light);
  HPoint o{};
  if (!far_lit_point(topo, l, rng, o)) return;
  ++stats.lights;
  constexpr int kGrid = 7;
  std::uniform_int_distribution<std::size_t> pick_face(0, topo.face_count() - 1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int sample = 0; sample < 80; ++sample) {
    HPoint p{};
    Counts expected, all, zpass, zfail;
    int tries = 0;
    do {
      // Behind a random face point, as far again as the light is (or 6 units of a directional
      // light's direction): across the gaps and intervals.
      const std::size_t f = pick_face(rng);
      float a = unit(rng), b = unit(rng);
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      const glm::vec3 q = topo.positions[topo.face_vertices[3 * f]] * (1.0f - a - b) +
                          topo.positions[topo.face_vertices[3 * f + 1]] * a +
                          topo.positions[topo.face_vertices[3 * f + 2]] * b;
      const glm::vec3 away = light.w == 0.0f ? -glm::vec3(light) * 6.0f : q - glm::vec3(light);
      const glm::vec3 pp = glm::round((q + away * unit(rng) * 1.5f) * float(kGrid));
      p = {std::int64_t(pp.x), std::int64_t(pp.y), std::int64_t(pp.z), kGrid};
      bool ambiguous = false;
      std::array<bool, 3> held{};
      for (std::uint32_t k = 0; k < 3; ++k)
        held[k] = in_intervals(clamp.of_leaf(k), clamp.depth, p, ambiguous);
      expected = caster_count(topo, p, l, front_only,
                              [&](std::size_t face) { return held[face_leaf[face]]; });
      all = caster_count(topo, p, l, front_only);
      expected.ambiguous = expected.ambiguous || ambiguous;
      zpass = zpass_count(volume, o, p);
      zfail = zfail_count(volume, p, direction(o, p));
    } while ((expected.ambiguous || zpass.ambiguous || zfail.ambiguous) && ++tries < 50);
    ASSERT_LT(tries, 50) << "no unambiguous sample for " << named.name;
    ++stats.checked;
    stats.in_shadow += expected.value != 0;
    stats.clamped_away += all.value != expected.value;
    if (zpass.value != expected.value || zfail.value != expected.value) {
      std::ostringstream msg;
      msg << named.name << " generator=" << to_string(generator) << " light=(" << light.x << ","
          << light.y << "," << light.z << "," << light.w << ") P=(" << p[0] << "," << p[1] << ","
          << p[2] << ")/" << p[3] << ": surfaces held=" << expected.value
          << " zpass=" << zpass.value << " zfail=" << zfail.value;
      stats.failures.push_back(msg.str());
    }
  }
}

class ClampedVolumeLaw : public ::testing::TestWithParam<Generator> {};

// A clamped volume counts, at every point, the caster surfaces towards the light whose leaf holds
// the point's depth; the pieces of edges shared by two leaves included.
TEST_P(ClampedVolumeLaw, CountEqualsHeldCasterSurfaces) {
  const Generator generator = GetParam();
  std::mt19937 rng(77u + static_cast<unsigned>(generator));
  ClampedLawStats stats;
  for (const testing::NamedMesh& named : testing::adversarial_meshes(42)) {
    if (generator == Generator::standard && !build_topology(named.mesh).report.closed_manifold)
      continue;
    for (int i = 0; i < 6; ++i)
      check_clamped_law(named, random_light(rng, i % 3 == 2), generator, i % 2 == 0, rng, stats);
  }
  for (std::size_t i = 0; i < std::min<std::size_t>(stats.failures.size(), 10); ++i)
    ADD_FAILURE() << stats.failures[i];
  EXPECT_TRUE(stats.failures.empty())
      << stats.failures.size() << " of " << stats.checked << " samples broke the law";
  EXPECT_GE(stats.lights, generator == Generator::standard ? 12 : 40);
  EXPECT_GT(stats.in_shadow, stats.checked / 5);      // some held shadows to count
  EXPECT_GT(stats.clamped_away, stats.checked / 10);  // and some clamped away
  std::cout << "[ law ] clamped " << to_string(generator) << ": " << stats.checked << " samples, "
            << stats.in_shadow << " in a held shadow, " << stats.clamped_away << " clamped away\n";
}

INSTANTIATE_TEST_SUITE_P(AllGenerators, ClampedVolumeLaw,
                         ::testing::Values(Generator::multiplicity, Generator::robust,
                                           Generator::standard),
                         [](const auto& info) { return std::string(to_string(info.param)); });

INSTANTIATE_TEST_SUITE_P(AllGenerators, VolumeLaw,
                         ::testing::Values(Generator::multiplicity, Generator::robust,
                                           Generator::standard, Generator::automatic),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace shadowvol
