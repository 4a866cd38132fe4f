// The near-plane pre-fill of ZP+ (accel/near_plane.h): the count it leaves in every pixel is the
// one the whole volume leaves drawn without a depth test (negated: what lies beyond the near plane
// is what a point on it must count its way out through), pixel for pixel, for volumes the near
// plane cuts anywhere; and that count is the volume's at the pixel's near-plane point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include "accel/near_plane.h"
#include "core/projection.h"
#include "core/topology.h"
#include "core/volume.h"
#include "raster/raster.h"
#include "test_meshes.h"

namespace shadowvol {
namespace {

constexpr int kWidth = 160, kHeight = 90;
constexpr float kNear = 0.1f;

glm::mat4 projection() {
  return infinite_reversed_perspective(glm::radians(60.0f), float(kWidth) / kHeight, kNear);
}

// The eye at the origin looking down -z: every triangle of the volume (sides split as drawn,
// both caps) in clip space, each with its weight, and each part where asked.
struct ClipVolume {
  std::vector<glm::vec4> triangles;
  std::vector<std::int32_t> weights;
  std::vector<std::uint32_t> parts;
};
ClipVolume clip_volume(const Mesh& mesh, const glm::vec4& light, const glm::vec4& far_plane) {
  const Topology topo = build_topology(mesh);
  VolumeBuffer v;
  VolumeScratch scratch;
  build_volume(topo, light, {Generator::multiplicity, true, far_plane, true}, scratch, v);
  ClipVolume out;
  const glm::mat4 proj = projection();
  auto add = [&](const PrimitiveList& list, int corners) {
    for (std::size_t p = 0; p < list.size(); ++p)
      for (int t = 0; t < (corners == kQuadCorners ? 2 : 1); ++t) {
        for (int k = 0; k < 3; ++k)
          out.triangles.push_back(proj * list.vertices[p * corners + kQuadTriangles[3 * t + k]]);
        out.weights.push_back(list.weights[p]);
        out.parts.push_back(list.parts[p]);
      }
  };
  add(v.sides, kQuadCorners);
  add(v.light_caps, kTriangleCorners);
  add(v.dark_caps, kTriangleCorners);
  return out;
}

std::vector<std::int32_t> prefill_counts(const ClipVolume& v, bool by_part) {
  std::vector<glm::vec4> fan, apexes;
  std::vector<std::int32_t> weights;
  std::vector<std::uint32_t> parts;
  append_near_plane_prefill(
      v.triangles, v.weights,
      by_part ? std::span<const std::uint32_t>(v.parts) : std::span<const std::uint32_t>(), fan,
      weights, by_part ? &parts : nullptr, apexes);
  raster::Target target(kWidth, kHeight);
  raster::Counters counters;
  raster::draw_counts(target, fan, weights, raster::CountRule::prefill, counters);
  return target.count;
}

std::vector<std::int32_t> whole_volume_counts(const ClipVolume& v) {
  std::vector<std::int32_t> negated;
  for (const std::int32_t w : v.weights) negated.push_back(-w);
  raster::Target target(kWidth, kHeight);
  raster::Counters counters;
  raster::draw_counts(target, v.triangles, negated, raster::CountRule::prefill, counters);
  return target.count;
}

int nonzero(const std::vector<std::int32_t>& counts) {
  int n = 0;
  for (const std::int32_t c : counts) n += c != 0;
  return n;
}

TEST(NearPlanePrefill, CountsWhatTheWholeVolumeCountsOnEveryPixel) {
  std::mt19937 rng(39);
  std::uniform_real_distribution<float> depth(-2.0f, -0.02f), unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> fraction(0.1f, 1.0f);
  int cut = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // Casters about the line of sight, from beyond the near plane to across it, of about their
    // distance's size, so that their volumes meet the near plane's rectangle.
    const float z = depth(rng);
    const glm::vec3 at(0.4f * z * unit(rng) - 0.1f, 0.4f * z * unit(rng) - 0.1f, z);
    auto size = [&] { return -z * fraction(rng); };
    Mesh mesh;
    switch (trial % 4) {
      case 0:
        mesh = testing::box(at, at + glm::vec3(size(), size(), size()));
        break;
      case 1:
        mesh = testing::tetrahedron(at, size());
        break;
      case 2: {  // non-convex, nested silhouettes
        std::mt19937 grid(trial);
        mesh = testing::bumpy_box(4, 0.1f * size(), grid);
        for (glm::vec3& p : mesh.positions) p = at + glm::vec3(p.x, p.y, p.z * 0.005f * size());
        break;
      }
      default: {  // open: a box without its top, and a lone triangle
        const float s = size();
        mesh = testing::box(at, at + glm::vec3(s), false);
        testing::add_triangle(mesh, at + glm::vec3(s, 0, 0), at + glm::vec3(1.5f * s, 0, 0),
                              at + glm::vec3(s, 0.5f * s, 0.3f * s));
      }
    }
    // Lights beyond the casters, shining back at the eye; beside them; in the near plane's own
    // plane; and directional ones.
    glm::vec4 light;
    switch (trial % 5) {
      case 0:
        light = {unit(rng), unit(rng), -4.0f - 4.0f * fraction(rng), 1};
        break;
      case 1:
        light = {3.0f * unit(rng), 3.0f * unit(rng), depth(rng), 1};
        break;
      case 2:
        light = {0.3f * unit(rng), 0.3f * unit(rng), -kNear, 1};
        break;
      case 3:
        light = {0.3f * unit(rng), 0.3f * unit(rng), -1.0f, 0};
        break;
      default:
        light = {unit(rng), unit(rng), unit(rng), 0};
    }
    // Extruded to infinity, and ended on a plane behind the eye.
    const glm::vec4 far_plane = trial % 3 == 2 ? glm::vec4(0, 0, -1, -1) : kPlaneAtInfinity;
    const ClipVolume v = clip_volume(mesh, light, far_plane);
    const std::vector<std::int32_t> expected = whole_volume_counts(v);
    cut += nonzero(expected) > 0;
    for (const bool by_part : {false, true}) {
      const std::vector<std::int32_t> counts = prefill_counts(v, by_part);
      int differ = 0;
      for (std::size_t p = 0; p < counts.size(); ++p) differ += counts[p] != expected[p];
      EXPECT_EQ(differ, 0) << "trial " << trial << (by_part ? ", by part" : "");
    }
  }
  EXPECT_GT(cut, 60);  // volumes the near plane does cut, not only ones it misses
}

// Slab test of the segment a -> b against the box [lo, hi].
bool segment_meets_box(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& lo,
                       const glm::dvec3& hi) {
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k];
    const double u = (lo[k] - a[k]) / d, v = (hi[k] - a[k]) / d;
    t0 = std::max(t0, std::min(u, v));
    t1 = std::min(t1, std::max(u, v));
  }
  return t0 < t1;
}

// A box between the eye and a light beyond it: a pixel's count is 2 (the box's surfaces crossed)
// exactly where the segment from its near-plane point to the light crosses the box, and 0 where it
// does not (away from the shadow's outline).
TEST(NearPlanePrefill, IsTheCountOfTheNearPlanePoint) {
  const glm::vec3 lo(-0.3f, -0.2f, -1.2f), hi(0.2f, 0.25f, -0.9f);
  const glm::vec4 light(0.1f, 0.3f, -6.0f, 1.0f);
  const std::vector<std::int32_t> counts =
      prefill_counts(clip_volume(testing::box(lo, hi), light, kPlaneAtInfinity), false);
  const glm::mat4 inv = glm::inverse(projection());
  int inside = 0, checked = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::vec4 ndc((x + 0.5f) / kWidth * 2 - 1, 1 - (y + 0.5f) / kHeight * 2, 1, 1);
      const glm::vec4 e = inv * ndc;
      const glm::dvec3 n = glm::dvec3(e) / double(e.w), l(light);
      // Within a margin of about a pixel's width of the box, the outline: not checked.
      const double margin = 0.004;
      const bool surely_in =
          segment_meets_box(n, l, glm::dvec3(lo) + margin, glm::dvec3(hi) - margin);
      const bool surely_out =
          !segment_meets_box(n, l, glm::dvec3(lo) - margin, glm::dvec3(hi) + margin);
      if (!surely_in && !surely_out) continue;  // on the outline
      ++checked;
      inside += surely_in;
      EXPECT_EQ(counts[std::size_t(y) * kWidth + x], surely_in ? 2 : 0) << x << ", " << y;
    }
  EXPECT_GT(inside, 500);
  EXPECT_GT(checked, kWidth * kHeight * 9 / 10);
}

}  // namespace
}  // namespace shadowvol
