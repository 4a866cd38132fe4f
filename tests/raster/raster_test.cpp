// The rasterizer's promises: watertight (no pixel of a closed fan or mesh drawn twice or
// missed), both facings, near-plane clipping with vertices at infinity (w = 0) matching a
// ray-cast, and the hi-z skipping only tiles that hold no work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include "core/projection.h"
#include "raster/raster.h"

namespace shadowvol::raster {
namespace {

// A triangle list in clip space straight from NDC x, y (depth z = 0.5, w = 1).
void add_ndc(std::vector<glm::vec4>& out, glm::vec2 a, glm::vec2 b, glm::vec2 c) {
  out.insert(out.end(), {glm::vec4(a, 0.5f, 1), glm::vec4(b, 0.5f, 1), glm::vec4(c, 0.5f, 1)});
}

// Counts each triangle once, +1 front, -1 back, on an empty depth buffer (every fragment passes).
std::vector<std::int32_t> coverage(int w, int h, const std::vector<glm::vec4>& tris) {
  Target target(w, h);
  Counters counters;
  draw_counts(target, tris, std::vector<std::int32_t>(tris.size() / 3, 1), CountRule::zpass,
              counters);
  return target.count;
}

glm::vec2 ndc_of_pixel(int px, int py, int w, int h) {
  return {(px + 0.5) / w * 2.0 - 1.0, 1.0 - (py + 0.5) / h * 2.0};
}

TEST(Raster, FanAroundAPointCoversItsPolygonExactlyOnce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-0.3f, 0.3f);
  const int w = 97, h = 61;
  for (int trial = 0; trial < 20; ++trial) {
    const glm::vec2 centre(jitter(rng), jitter(rng));
    const int n = 5 + trial * 3;
    std::vector<glm::vec2> ring;
    for (int i = 0; i < n; ++i) {
      const float a = 6.2831853f * (i + 0.5f * (jitter(rng) + 0.3f)) / n;
      ring.push_back(centre + glm::vec2(std::cos(a), std::sin(a)) * 0.9f);
    }
    std::vector<glm::vec4> tris;
    for (int i = 0; i < n; ++i) add_ndc(tris, centre, ring[i], ring[(i + 1) % n]);  // CCW
    const std::vector<std::int32_t> count = coverage(w, h, tris);
    int covered = 0;
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px) {
        const std::int32_t c = count[py * w + px];
        ASSERT_TRUE(c == 0 || c == 1) << "pixel " << px << "," << py << " counted " << c;
        // Inside the outer polygon? (Pixels within a hair of its boundary are the fill rule's.)
        const glm::vec2 p = ndc_of_pixel(px, py, w, h);
        float nearest = 1e9f;
        bool inside = true;
        for (int i = 0; i < n; ++i) {
          const glm::vec2 e = ring[(i + 1) % n] - ring[i], d = p - ring[i];
          const float side = (e.x * d.y - e.y * d.x) / glm::length(e);
          inside &= side > 0.0f;
          nearest = std::min(nearest, std::abs(side));
        }
        if (nearest > 1e-4f) {
          EXPECT_EQ(c, inside ? 1 : 0) << "pixel " << px << "," << py;
        }
        covered += c;
      }
    EXPECT_GT(covered, w * h / 4);
  }
}

class JitteredGrid : public ::testing::TestWithParam<bool> {};

// Vertices on a grid that overhangs the viewport, jittered inside their cells (the border ones
// stay on the overhang, so that the mesh covers the whole viewport). With snapping, every
// vertex sits on a pixel centre, so that many edges run exactly through pixel centres and the
// top-left rule decides them.
TEST_P(JitteredGrid, CoversEveryPixelOnce) {
  const bool on_pixel_centres = GetParam();
  std::mt19937 rng(11);
  const int w = 64, h = 48, n = 9;
  std::uniform_real_distribution<float> jitter(-0.45f, 0.45f);
  auto snap = [&](float ndc, int size) {
    if (!on_pixel_centres) return ndc;
    const float pixel = std::round((ndc + 1.0f) * 0.5f * size - 0.5f);
    return (pixel + 0.5f) / size * 2.0f - 1.0f;
  };
  std::vector<glm::vec2> grid;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      grid.emplace_back(snap(-1.2f + 2.4f * (i + (border ? 0.0f : jitter(rng))) / n, w),
                        snap(-1.2f + 2.4f * (j + (border ? 0.0f : jitter(rng))) / n, h));
    }
  std::vector<glm::vec4> tris;
  auto at = [&](int i, int j) { return grid[j * (n + 1) + i]; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      add_ndc(tris, at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add_ndc(tris, at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  for (std::int32_t c : coverage(w, h, tris)) ASSERT_EQ(c, 1);
}

INSTANTIATE_TEST_SUITE_P(Vertices, JitteredGrid, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "on_pixel_centres" : "free"; });

TEST(Raster, BackFacesSubtractAndTheSharedEdgeIsDrawnOnce) {
  std::vector<glm::vec4> tris;
  add_ndc(tris, {-0.8f, -0.8f}, {0.8f, -0.8f}, {0.0f, 0.8f});  // CCW: front
  add_ndc(tris, {-0.8f, -0.8f}, {0.0f, 0.8f}, {0.8f, -0.8f});  // CW: back
  for (std::int32_t c : coverage(40, 40, tris)) ASSERT_EQ(c, 0);
  // Two triangles sharing a vertical edge through pixel centres (x = 0 at 40 px: between
  // columns 19 and 20, so move it onto the centre of column 20: x_ndc = 0.025).
  std::vector<glm::vec4> pair;
  add_ndc(pair, {-0.5f, -0.5f}, {0.025f, -0.5f}, {0.025f, 0.5f});
  add_ndc(pair, {0.025f, -0.5f}, {0.6f, -0.5f}, {0.025f, 0.5f});
  const std::vector<std::int32_t> count = coverage(40, 40, pair);
  int on_edge = 0;
  for (int py = 0; py < 40; ++py) {
    ASSERT_LE(count[py * 40 + 20], 1);
    on_edge += count[py * 40 + 20];
  }
  EXPECT_GT(on_edge, 10);
}

// CountRule::cover counts the surfaces in front of the stored depth whichever way they face, and
// CountRule::behind those behind it: a front face and a back face on the counted side of a
// surface at depth 0.25 both add (z-pass or z-fail would cancel them), and a face on the other
// side adds nothing.
TEST(Raster, CoverAndBehindCountEveryFaceOnTheirSideWhicheverWayItFaces) {
  constexpr int w = 40, h = 40;
  struct Case {
    CountRule rule;
    float counted_depth, other_depth;  // reversed depth: 0.5 is in front of 0.25, 0.1 behind
  };
  for (const Case& c : {Case{CountRule::cover, 0.5f, 0.1f}, Case{CountRule::behind, 0.1f, 0.5f}}) {
    Target target(w, h);
    target.clear_depth(0.25f);
    target.update_tile_depth();
    std::vector<glm::vec4> tris;
    add_ndc(tris, {-0.8f, -0.8f}, {0.8f, -0.8f}, {0.0f, 0.8f});  // CCW: front
    add_ndc(tris, {-0.8f, -0.8f}, {0.0f, 0.8f}, {0.8f, -0.8f});  // CW: back
    for (glm::vec4& v : tris) v.z = c.counted_depth;
    for (const glm::vec2 a : {glm::vec2(-0.8f, -0.8f), glm::vec2(0.8f, -0.8f), glm::vec2(0, 0.8f)})
      tris.emplace_back(a, c.other_depth, 1.0f);
    Counters counters;
    draw_counts(target, tris, std::vector<std::int32_t>(tris.size() / 3, 1), c.rule, counters);
    EXPECT_EQ(target.count[static_cast<std::size_t>(h / 2) * w + w / 2], 2);
    EXPECT_EQ(target.count[0], 0);  // outside the triangles
    for (std::int32_t count : target.count) ASSERT_TRUE(count == 0 || count == 2);
  }
}

// An eye-space quad crossing the near plane, and a shadow-volume-like triangle with two vertices
// at infinity, against a ray-cast per pixel: the same pixels, but for those within a pixel of
// an edge of the projected shape.
TEST(Raster, ClipsAtTheNearPlaneAndDrawsVerticesAtInfinity) {
  const int w = 80, h = 60;
  const float near = 0.1f;
  const glm::mat4 proj = infinite_reversed_perspective(glm::radians(70.0f), float(w) / h, near);
  struct Case {
    glm::vec4 eye[3];  // eye space, homogeneous
    bool crosses_near;
  };
  const Case cases[] = {
      // A floor triangle running from behind the camera to far ahead (crosses the near plane).
      {{{-3, -1, 2, 1}, {3, -1, 2, 1}, {0, -1, -30, 1}}, true},
      // A side-quad triangle: one finite vertex, two directions (w = 0) going away and down-left.
      {{{0.5f, 0.2f, -2, 1}, {-0.2f, -0.3f, -1, 0}, {0.4f, -0.5f, -1, 0}}, false},
  };
  for (const Case& c : cases) {
    std::vector<glm::vec4> tri;
    for (const glm::vec4& e : c.eye) tri.push_back(proj * e);
    Target target(w, h);
    Counters counters;
    draw_counts(target, tri, std::vector<std::int32_t>{1}, CountRule::zpass, counters);
    // Ray-cast: the pixel's ray from the eye, against the triangle as the set of positive
    // combinations of its homogeneous vertices (exactly what the rasterizer draws), beyond near.
    const glm::mat4 inv = glm::inverse(proj);
    int mismatches = 0, covered = 0;
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px) {
        const glm::vec2 ndc = ndc_of_pixel(px, py, w, h);
        glm::vec4 far_point = inv * glm::vec4(ndc, 1.0f, 1.0f);  // a point on the ray
        const glm::dvec3 d = glm::normalize(glm::dvec3(far_point));
        // Solve l0 E0 + l1 E1 + l2 E2 = (t d, 1) up to scale: 4 equations, 4 unknowns (l, t).
        glm::dmat4 m(glm::dvec4(c.eye[0]), glm::dvec4(c.eye[1]), glm::dvec4(c.eye[2]),
                     -glm::dvec4(d, 0.0));
        const glm::dvec4 sol = glm::inverse(m) * glm::dvec4(0, 0, 0, 1);
        const bool hit = sol.x > 0 && sol.y > 0 && sol.z > 0 && sol.w * d.z < -near;
        const bool drawn = target.count[py * w + px] != 0;
        covered += drawn;
        if (hit != drawn) {
          // Allowed only within a pixel of the shape's edge: a neighbour disagrees with itself.
          bool boundary = false;
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int x = px + dx, y = py + dy;
              if (x >= 0 && y >= 0 && x < w && y < h)
                boundary |= (target.count[y * w + x] != 0) != drawn;
            }
          mismatches += !boundary;
        }
      }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(covered, 50);
    EXPECT_EQ(counters.triangles_clipped, c.crosses_near ? 1u : 0u);
  }
}

// A jittered floor grid running from behind the camera to far ahead: the near plane cuts many
// shared edges, and the cut must leave neither gaps nor overlaps.
TEST(Raster, NearPlaneCutsKeepAMeshWatertight) {
  const int w = 96, h = 64, n = 24;
  const glm::mat4 proj = infinite_reversed_perspective(glm::radians(75.0f), float(w) / h, 0.05f);
  const glm::mat4 view = glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(1, 0, 0));  // look down
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> jitter(-0.4f, 0.4f);
  std::vector<glm::vec4> grid;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      const float x = -60.0f + 120.0f * (i + (border ? 0.0f : jitter(rng))) / n;
      const float z = 3.0f - 63.0f * (j + (border ? 0.0f : jitter(rng))) / n;
      grid.push_back(proj * view * glm::vec4(x, -1.0f, z, 1.0f));
    }
  std::vector<glm::vec4> tris;
  auto at = [&](int i, int j) { return grid[j * (n + 1) + i]; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {  // counter-clockwise seen from above (+y)
      tris.insert(tris.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      tris.insert(tris.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  Target target(w, h);
  Counters counters;
  draw_counts(target, tris, std::vector<std::int32_t>(tris.size() / 3, 1), CountRule::zpass,
              counters);
  EXPECT_GT(counters.triangles_clipped, 4u);
  // Every pixel whose ray meets the floor well inside the grid is covered exactly once.
  const glm::mat4 inv = glm::inverse(proj * view);
  int checked = 0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const std::int32_t c = target.count[py * w + px];
      ASSERT_LE(std::abs(c), 1) << px << "," << py;
      const glm::vec2 ndc = ndc_of_pixel(px, py, w, h);
      const glm::vec4 a = inv * glm::vec4(ndc, 1.0f, 1.0f), b = inv * glm::vec4(ndc, 0.5f, 1.0f);
      const glm::vec3 from = glm::vec3(a) / a.w, to = glm::vec3(b) / b.w;
      const glm::vec3 d = to - from;
      if (d.y >= 0.0f) continue;
      const glm::vec3 hit = from + d * ((-1.0f - from.y) / d.y);
      if (std::abs(hit.x) < 50.0f && hit.z < 1.0f && hit.z > -50.0f) {
        ++checked;
        EXPECT_EQ(c, 1) << "pixel " << px << "," << py;
      }
    }
  EXPECT_GT(checked, w * h / 4);
}

TEST(Raster, DepthOfAPointAtInfinityIsZeroAndTheHiZSkipsOnlyIdleTiles) {
  const int w = 64, h = 64;
  const glm::mat4 proj = infinite_reversed_perspective(glm::radians(60.0f), 1.0f, 0.1f);
  Target target(w, h);
  Counters counters;
  // A wall at eye depth 5 over the whole view: depth everywhere near / distance = 0.1 / 5.
  std::vector<glm::vec4> wall = {proj * glm::vec4(-50, -50, -5, 1),
                                 proj * glm::vec4(50, -50, -5, 1), proj * glm::vec4(0, 50, -5, 1)};
  draw_depth(target, wall, 7, counters);
  EXPECT_EQ(target.id[32 * w + 32], 7u);
  target.update_tile_depth();
  EXPECT_FLOAT_EQ(target.depth[32 * w + 32], 0.1f / 5.0f);
  // A triangle far behind the wall: z-pass cannot change any pixel, so the hi-z's coarser level
  // leaves it out of its block row before any tile.
  std::vector<glm::vec4> behind = {proj * glm::vec4(-1, -1, -50, 1),
                                   proj * glm::vec4(1, -1, -50, 1), proj * glm::vec4(0, 1, -50, 1)};
  Counters zpass;
  draw_counts(target, behind, std::vector<std::int32_t>{1}, CountRule::zpass, zpass);
  EXPECT_EQ(zpass.block_rows_skipped, 1u);
  EXPECT_EQ(zpass.tiles_touched, 0u);
  EXPECT_EQ(zpass.pixels_processed, 0u);
  EXPECT_EQ(zpass.count_updates, 0u);
  // The same triangle under z-fail counts in every pixel it covers (it is behind the wall).
  Counters zfail;
  draw_counts(target, behind, std::vector<std::int32_t>{1}, CountRule::zfail, zfail);
  EXPECT_EQ(zfail.block_rows_skipped, 0u);
  EXPECT_EQ(zfail.tiles_skipped, 0u);
  EXPECT_EQ(zfail.count_updates, zfail.pixels_processed);
  EXPECT_GT(zfail.count_updates, 0u);
  // Depth bounds that exclude the wall's depth leave every pixel alone, tile by tile.
  Counters bounded;
  const std::vector<std::int32_t> before = target.count;
  draw_counts(target, behind, std::vector<std::int32_t>{1}, CountRule::zfail, bounded,
              DepthBounds{0.5f, 1.0f});
  EXPECT_EQ(bounded.count_updates, 0u);
  EXPECT_EQ(bounded.block_rows_skipped, 1u);
  EXPECT_EQ(bounded.tiles_skipped, bounded.tiles_touched);
  EXPECT_EQ(target.count, before);
  // A triangle at infinity (all w = 0) lies at depth 0, the cleared depth: never nearer.
  std::vector<glm::vec4> at_infinity = {proj * glm::vec4(-1, -1, -5, 0),
                                        proj * glm::vec4(1, -1, -5, 0),
                                        proj * glm::vec4(0, 1, -5, 0)};
  Target empty(w, h);
  Counters inf;
  draw_depth(empty, at_infinity, 0, inf);
  EXPECT_EQ(empty.id[32 * w + 32], Target::kNoId);
  EXPECT_EQ(inf.pixels_passed, 0u);  // depth 0 is not greater than the cleared 0
  EXPECT_GT(inf.pixels_processed, 0u);
}

// The hi-z's coarser level leaves out only what the tiles would have rejected: long slivers to
// infinity (shadow-volume sides) over a receding ground and boxes on it count exactly as they do
// where every tile is tested (a split plane that picks the same rule for every tile: no block
// level), and most of their block rows are left out.
TEST(Raster, BlocksLeaveOutOnlyWhatTheTilesWouldReject) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const int w = 301, h = 197;  // blocks and tiles cut at the edges
  const glm::mat4 proj = infinite_reversed_perspective(glm::radians(60.0f), float(w) / h, 0.1f);
  Target target(w, h);
  Counters ignored;
  std::vector<glm::vec4> surface = {proj * glm::vec4(-400, -2, 0, 1),
                                    proj * glm::vec4(400, -2, 0, 1),
                                    proj * glm::vec4(0, -2, -800, 1)};
  for (int i = 0; i < 30; ++i) {
    const glm::vec3 c(6.0f * unit(rng), -1.5f + unit(rng), -12.0f + 6.0f * unit(rng));
    for (int k = 0; k < 3; ++k)
      surface.push_back(proj * glm::vec4(c + 0.8f * glm::vec3(unit(rng), unit(rng), unit(rng)), 1));
  }
  draw_depth(target, surface, 0, ignored);
  target.update_tile_depth();
  // Quads from an edge of a caster above the ground to infinity away from a light above it.
  const glm::vec3 light(2.0f, 12.0f, -6.0f);
  std::vector<glm::vec4> slivers;
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 a(4.0f * unit(rng), 1.0f + unit(rng), -10.0f + 4.0f * unit(rng));
    const glm::vec3 b = a + 0.3f * glm::vec3(unit(rng), unit(rng), unit(rng));
    const glm::vec4 a_far(a - light, 0.0f), b_far(b - light, 0.0f);
    for (const glm::vec4& p :
         {glm::vec4(a, 1), glm::vec4(b, 1), b_far, glm::vec4(a, 1), b_far, a_far})
      slivers.push_back(proj * p);
  }
  const std::vector<std::int32_t> weights(slivers.size() / 3, 1);
  for (const bool zfail : {false, true}) {
    const auto counts = [&](CountRule rule, const SplitPlane& split, Counters& counters) {
      draw_counts(target, slivers, weights, rule, counters, {0.0f, 1.0f}, split);
      std::vector<std::int32_t> out = target.count;
      std::fill(target.count.begin(), target.count.end(), 0);
      return out;
    };
    Counters blocks, tiles;
    const std::vector<std::int32_t> by_blocks =
        counts(zfail ? CountRule::zfail : CountRule::zpass, {}, blocks);
    // Every stored depth (0 where no surface is, up to 1) lies on the camera's side of the
    // plane z = -1 (z-pass) and away from it behind z = 5 (z-fail).
    const SplitPlane every_tile_alike{zfail ? glm::vec4(0.0f, 0.0f, 1.0f, -5.0f)
                                            : glm::vec4(0.0f, 0.0f, 1.0f, 1.0f)};
    EXPECT_EQ(by_blocks, counts(CountRule::split, every_tile_alike, tiles)) << zfail;
    EXPECT_EQ(blocks.count_updates, tiles.count_updates);
    EXPECT_GT(blocks.count_updates, 1000u);
    EXPECT_EQ(tiles.block_rows_skipped, 0u);
    if (!zfail) {
      EXPECT_GT(blocks.block_rows_skipped, 100u);
      EXPECT_LT(blocks.tiles_touched, tiles.tiles_touched);
    }
  }
}

// Reversed depth keeps float's relative precision far away: two walls 1000 and 1000.01 units
// out (near 0.1) are 1e-9 apart in the conventional depth 1 - near / distance, below its float
// steps near 1 (6e-8), but 1e-9 of 1e-4 in near / distance, a hundred thousand steps apart.
TEST(Raster, WallsAHundredthApartAThousandUnitsOutAreResolved) {
  const int w = 32, h = 32;
  const glm::mat4 proj = infinite_reversed_perspective(glm::radians(60.0f), 1.0f, 0.1f);
  const auto wall = [&](float distance) {
    const float r = 2.0f * distance;  // wider than the view
    return std::vector<glm::vec4>{proj * glm::vec4(-r, -r, -distance, 1),
                                  proj * glm::vec4(r, -r, -distance, 1),
                                  proj * glm::vec4(0, r, -distance, 1)};
  };
  for (const bool far_first : {true, false}) {
    Target target(w, h);
    Counters counters;
    draw_depth(target, wall(far_first ? 1000.01f : 1000.0f), far_first ? 1 : 2, counters);
    draw_depth(target, wall(far_first ? 1000.0f : 1000.01f), far_first ? 2 : 1, counters);
    for (const std::uint32_t id : target.id) ASSERT_EQ(id, 2u) << "the nearer wall (id 2) wins";
  }
}

// A cap drawn over the surface it came from must meet it at exactly the stored depth, whatever
// the slope: z-fail counts it at every pixel the surface won, z-pass at none. Then
// take_nonzero_counts reports those pixels and leaves every count zero.
TEST(Raster, ATriangleDrawnAgainMeetsItsOwnDepthExactly) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-1.5f, 1.5f), depth(0.001f, 0.999f);
  const int w = 83, h = 47;  // neither a multiple of the tile size
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<glm::vec4> tri;
    for (int k = 0; k < 3; ++k) tri.emplace_back(coord(rng), coord(rng), depth(rng), 1.0f);
    Target target(w, h);
    Counters drawn;
    draw_depth(target, tri, 0, drawn);
    target.update_tile_depth();
    Counters zfail, zpass;
    draw_counts(target, tri, std::vector<std::int32_t>{1}, CountRule::zfail, zfail);
    draw_counts(target, tri, std::vector<std::int32_t>{1}, CountRule::zpass, zpass);
    EXPECT_EQ(zfail.count_updates, drawn.pixels_passed) << "trial " << trial;
    EXPECT_EQ(zpass.count_updates, 0u) << "trial " << trial;
    std::vector<std::uint8_t> nonzero(static_cast<std::size_t>(w) * h, 7);
    target.take_nonzero_counts(nonzero);
    for (std::size_t p = 0; p < nonzero.size(); ++p)
      ASSERT_EQ(nonzero[p], target.id[p] != Target::kNoId ? 1 : 0) << "pixel " << p;
    EXPECT_EQ(std::count(target.count.begin(), target.count.end(), 0),
              static_cast<std::ptrdiff_t>(target.count.size()));
  }
}

// Laine 2005 Eq. 3: z-pass and z-fail give a closed volume the same count at every surface the
// near plane does not see inside it, so a per-tile choice between them, by any split plane, must
// too. Closed tetrahedra in front of and through a bumpy surface; random split planes.
TEST(Raster, ASplitPlaneChoosesPerTileWithoutChangingAnyCount) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const int w = 93, h = 61;  // neither a multiple of the tile size
  const glm::mat4 proj = infinite_reversed_perspective(glm::radians(60.0f), float(w) / h, 0.1f);
  std::ptrdiff_t shadowed = 0;  // surface pixels inside a tetrahedron, over all trials
  for (int trial = 0; trial < 12; ++trial) {
    Target target(w, h);
    Counters ignored;
    // The surface: jittered triangles at eye depth 4 to 8 before a backdrop that fills the view.
    std::vector<glm::vec4> surface = {proj * glm::vec4(-100, -100, -30, 1),
                                      proj * glm::vec4(100, -100, -30, 1),
                                      proj * glm::vec4(0, 100, -30, 1)};
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 3; ++k)
        surface.push_back(
            proj * glm::vec4(4.0f * unit(rng), 3.0f * unit(rng), -6.0f + 2.0f * unit(rng), 1));
    draw_depth(target, surface, 0, ignored);
    target.update_tile_depth();
    // The volume: a tetrahedron, faces wound outwards, between eye depth 2 and 9.
    glm::vec4 v[4];
    for (glm::vec4& p : v)
      p = glm::vec4(2.5f * unit(rng), 2.0f * unit(rng), -5.5f + 3.5f * unit(rng), 1);
    const glm::vec3 a(v[0]), b(v[1]), c(v[2]), d(v[3]);
    if (glm::dot(glm::cross(b - a, c - a), d - a) > 0.0f) std::swap(v[1], v[2]);  // d behind abc
    const int faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
    std::vector<glm::vec4> volume;
    for (const auto& f : faces)
      for (const int k : f) volume.push_back(proj * v[k]);
    const std::vector<std::int32_t> weights(4, 1);
    const auto counts = [&](CountRule rule, const SplitPlane& split, Counters& counters) {
      draw_counts(target, volume, weights, rule, counters, {}, split);
      std::vector<std::int32_t> out = target.count;
      std::fill(target.count.begin(), target.count.end(), 0);
      return out;
    };
    Counters zpass, zfail;
    const std::vector<std::int32_t> expected = counts(CountRule::zfail, {}, zfail);
    ASSERT_EQ(counts(CountRule::zpass, {}, zpass), expected) << "trial " << trial;
    shadowed += std::count_if(expected.begin(), expected.end(), [](int c) { return c != 0; });
    for (int plane = 0; plane < 8; ++plane) {
      const SplitPlane split{{unit(rng), unit(rng), unit(rng), unit(rng)}};
      Counters all, zfail_tiles, zpass_tiles;
      EXPECT_EQ(counts(CountRule::split, split, all), expected) << trial << "/" << plane;
      // The two halves of the tiles add up to the whole, tile for tile.
      std::vector<std::int32_t> halves =
          counts(CountRule::split, {split.plane, SplitTiles::zfail_only}, zfail_tiles);
      const std::vector<std::int32_t> other =
          counts(CountRule::split, {split.plane, SplitTiles::zpass_only}, zpass_tiles);
      for (std::size_t p = 0; p < halves.size(); ++p) halves[p] += other[p];
      EXPECT_EQ(halves, expected) << trial << "/" << plane;
      EXPECT_EQ(zfail_tiles.pixels_processed + zpass_tiles.pixels_processed, all.pixels_processed);
    }
    // A plane that every surface lies in front of picks z-pass everywhere, one with every
    // surface behind it z-fail: the same work as those rules.
    Counters front, behind;
    counts(CountRule::split, {{0.0f, 0.0f, 1.0f, -1e-6f}}, front);
    counts(CountRule::split, {{0.0f, 0.0f, -1.0f, 2.0f}}, behind);
    EXPECT_EQ(front.pixels_processed, zpass.pixels_processed);
    EXPECT_EQ(front.count_updates, zpass.count_updates);
    EXPECT_EQ(behind.pixels_processed, zfail.pixels_processed);
    EXPECT_EQ(behind.count_updates, zfail.count_updates);
  }
  EXPECT_GT(shadowed, w * h / 10);
}

// Where the plane cuts a tile's range of stored depths, the tile's rule follows the middle of
// that range: z-pass when the middle lies on the camera's side, whatever its nearest and
// farthest depths say.
TEST(Raster, TheSplitTestTakesTheMiddleOfTheTilesDepths) {
  Target target(8, 8);
  target.tile_depth[0] = {0.2f, 0.8f};  // farthest 0.2, nearest 0.8 (reversed depth)
  // The planes depth = c in normalized device coordinates, the camera (depth 1) on the side
  // where depth > c.
  const auto rule = [&](float c) { return split_rule(target, 0, 0, {0.0f, 0.0f, 1.0f, -c}); };
  EXPECT_EQ(rule(0.4f), CountRule::zpass);  // the farthest depth alone would say z-fail
  EXPECT_EQ(rule(0.6f), CountRule::zfail);  // the nearest alone would say z-pass
  EXPECT_EQ(rule(0.1f), CountRule::zpass);
  EXPECT_EQ(rule(0.9f), CountRule::zfail);
}

// CC shadow volumes' measures: `fill` touches every covered pixel whatever its depth and writes
// nothing; a ScreenStrip keeps the pixels whose centres lie within it, whatever the direction.
TEST(Raster, FillCountsCoveredPixelsAndAStripKeepsItsPixels) {
  const int w = 40, h = 30;
  Target target(w, h);
  target.clear_depth(1.0f);  // every stored depth nearest: z-pass would pass nowhere
  std::vector<glm::vec4> tris;
  add_ndc(tris, {-1, -1}, {1, -1}, {1, 1});
  add_ndc(tris, {-1, -1}, {1, 1}, {-1, 1});  // the whole viewport
  const std::vector<std::int32_t> weights(2, 3);
  Counters fill;
  draw_counts(target, tris, weights, CountRule::fill, fill);
  EXPECT_EQ(fill.pixels_processed, std::uint64_t(w * h));
  EXPECT_EQ(fill.pixels_passed, std::uint64_t(w * h));
  EXPECT_EQ(fill.count_updates, 0u);
  EXPECT_TRUE(std::all_of(target.count.begin(), target.count.end(), [](int c) { return c == 0; }));
  // A slanted strip, 0.1 <= 0.6 x + 0.8 y <= 0.5 in NDC.
  const ScreenStrip strip{{0.6f, 0.8f}, 0.1f, 0.5f};
  auto inside = [&](int px, int py) {
    const glm::vec2 p = ndc_of_pixel(px, py, w, h);
    const float s = 0.6f * p.x + 0.8f * p.y;
    return s >= 0.1f && s <= 0.5f;
  };
  Counters counted;
  target.clear_depth(0.0f);
  draw_counts(target, tris, weights, CountRule::zpass, counted, {}, {}, strip);
  int pixels = 0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      EXPECT_EQ(target.count[py * w + px], inside(px, py) ? 3 : 0) << px << "," << py;
      pixels += inside(px, py);
    }
  EXPECT_GT(pixels, w * h / 8);
  Counters strip_fill;
  draw_counts(target, tris, weights, CountRule::fill, strip_fill, {}, {}, strip);
  EXPECT_EQ(strip_fill.pixels_processed, std::uint64_t(pixels));
}

// reached_depths bounds what a volume's triangles can draw: a closed box counted under either
// rule changes no pixel outside them, so the counts are the same with them as without, and
// fewer pixels are processed. Vertices beyond the near plane reach depth 1; one behind the eye
// bounds nothing.
TEST(Raster, TheDepthsTrianglesReachBoundTheirCountsAndGiveUpBehindTheEye) {
  const int w = 64, h = 64;
  const float near = 0.1f;
  const glm::mat4 proj = infinite_reversed_perspective(glm::radians(60.0f), 1.0f, near);
  // A box 2 wide, from eye depth 4 to 6, faces counter-clockwise seen from outside.
  const glm::vec3 lo(-1, -1, -6), hi(1, 1, -4);
  auto corner = [&](int i) {
    return glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<glm::vec4> box;
  for (const auto& q : quads)
    for (const int t : {0, 1, 2, 0, 2, 3}) box.push_back(proj * glm::vec4(corner(q[t]), 1.0f));
  const DepthBounds reached = reached_depths(box);
  EXPECT_NEAR(reached.zmin, near / 6.0f, 2e-5f);
  EXPECT_NEAR(reached.zmax, near / 4.0f, 2e-5f);
  EXPECT_LE(reached.zmin, near / 6.0f);
  EXPECT_GE(reached.zmax, near / 4.0f);
  // Receivers in front of the box, inside it and behind it (eye depths 3, 5, 7), tile by tile.
  auto receivers = [&](Target& target) {
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px)
        target.depth[py * w + px] = near / (3.0f + 2.0f * ((px / kTileSize + py / kTileSize) % 3));
    target.update_tile_depth();
  };
  const std::vector<std::int32_t> weights(box.size() / 3, 1);
  for (const CountRule rule : {CountRule::zpass, CountRule::zfail}) {
    Target unbounded(w, h), bounded(w, h);
    receivers(unbounded);
    receivers(bounded);
    Counters all, within;
    draw_counts(unbounded, box, weights, rule, all);
    draw_counts(bounded, box, weights, rule, within, reached);
    EXPECT_EQ(bounded.count, unbounded.count);
    EXPECT_GT(std::count(bounded.count.begin(), bounded.count.end(), 1), w);  // inside the box
    EXPECT_LT(within.pixels_processed, all.pixels_processed);
  }
  // Beyond the near plane (eye depth 0.05): depth 1. At infinity ahead (w = 0): depth 0.
  const std::vector<glm::vec4> to_near = {proj * glm::vec4(0, 0, -0.05f, 1),
                                          proj * glm::vec4(1, 0, -5, 1),
                                          proj * glm::vec4(0, 1, -5, 0)};
  EXPECT_EQ(reached_depths(to_near).zmax, 1.0f);
  EXPECT_EQ(reached_depths(to_near).zmin, 0.0f);
  // Behind the eye (w < 0): no bound.
  const std::vector<glm::vec4> behind_eye = {
      proj * glm::vec4(0, 0, 1, 1), proj * glm::vec4(1, 0, -5, 1), proj * glm::vec4(0, 1, -5, 1)};
  EXPECT_EQ(reached_depths(behind_eye).zmin, 0.0f);
  EXPECT_EQ(reached_depths(behind_eye).zmax, 1.0f);
  // Nothing drawn: an empty range.
  EXPECT_GT(reached_depths({}).zmin, reached_depths({}).zmax);
}

}  // namespace
}  // namespace shadowvol::raster

namespace shadowvol::raster {
namespace {

// An occlusion query passes where a fragment lies at or in front of the stored depth, writes
// nothing, and with bounds above 0 ignores the background (depth 0: no surface).
TEST(Query, PassesAtOrInFrontOfTheStoredDepthAndWritesNothing) {
  Target target(16, 16);
  target.clear_depth();
  auto screen = [](float z) {
    return std::vector<glm::vec4>{{-1, -1, z, 1}, {3, -1, z, 1}, {-1, 3, z, 1}};
  };
  const DepthBounds surfaces{std::numeric_limits<float>::denorm_min(), 1.0f};
  Counters c;
  EXPECT_EQ(query(target, screen(0.3f), {}, c), 256u);  // over the background
  EXPECT_EQ(query(target, screen(0.3f), surfaces, c), 0u);
  draw_depth(target, screen(0.5f), 0, c);
  target.update_tile_depth();
  const std::vector<float> depth = target.depth;
  EXPECT_EQ(query(target, screen(0.4f), surfaces, c), 0u);    // behind
  EXPECT_EQ(query(target, screen(0.5f), surfaces, c), 256u);  // at
  EXPECT_EQ(query(target, screen(0.6f), surfaces, c), 256u);  // in front
  EXPECT_EQ(target.depth, depth);
  // A quarter of the image in front: its pixels only.
  const std::vector<glm::vec4> corner{{-1, -1, 0.9f, 1}, {0, -1, 0.9f, 1}, {-1, 0, 0.9f, 1},
                                      {0, -1, 0.9f, 1},  {0, 0, 0.9f, 1},  {-1, 0, 0.9f, 1}};
  EXPECT_EQ(query(target, corner, surfaces, c), 64u);
  // Stopping at the first pixel: only whether any passed.
  EXPECT_GE(query(target, screen(0.6f), surfaces, c, true), 1u);
  EXPECT_EQ(query(target, screen(0.4f), surfaces, c, true), 0u);
}

// A depth pass of several objects' triangles in one draw, each with its own id, leaves what
// drawing them one by one leaves.
TEST(DepthPass, OneDrawWithAnIdPerTriangleIsTheSameAsOneDrawPerObject) {
  const std::vector<glm::vec4> a{{-1, -1, 0.2f, 1}, {1, -1, 0.7f, 1}, {-1, 1, 0.4f, 1}};
  const std::vector<glm::vec4> b{{1, 1, 0.6f, 1}, {-1, 1, 0.3f, 1}, {1, -1, 0.2f, 1}};
  Target apart(32, 24), together(32, 24);
  Counters c;
  apart.clear_depth();
  together.clear_depth();
  draw_depth(apart, a, 10, c);
  draw_depth(apart, b, 20, c);
  std::vector<glm::vec4> both = a;
  both.insert(both.end(), b.begin(), b.end());
  const std::vector<std::uint32_t> ids{10, 20};
  draw_depth(together, both, ids, c);
  EXPECT_EQ(together.depth, apart.depth);
  EXPECT_EQ(together.id, apart.id);
  EXPECT_NE(std::count(together.id.begin(), together.id.end(), 20u), 0);
}

}  // namespace
}  // namespace shadowvol::raster

namespace shadowvol::raster {
namespace {

// The scissor: tiles wholly outside it keep their counts; the tiles it meets are counted whole,
// as without it.
TEST(Raster, ScissorLeavesTilesOutsideItAlone) {
  const int w = 64, h = 48;
  std::vector<glm::vec4> tris;
  add_ndc(tris, {-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f});
  add_ndc(tris, {-1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f});
  const std::vector<std::int32_t> whole = coverage(w, h, tris);
  Target target(w, h);
  target.scissor = {13, 9, 40, 30};
  Counters counters;
  draw_counts(target, tris, std::vector<std::int32_t>(tris.size() / 3, 1), CountRule::zpass,
              counters);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      const bool in_tiles = x >= 8 && x < 40 && y >= 8 && y < 32;  // the tiles it meets
      EXPECT_EQ(target.count[p], in_tiles ? whole[p] : 0) << x << "," << y;
    }
  target.scissor = {};
  std::fill(target.count.begin(), target.count.end(), 0);
  draw_counts(target, tris, std::vector<std::int32_t>(tris.size() / 3, 1), CountRule::zpass,
              counters);
  EXPECT_EQ(std::count(target.count.begin(), target.count.end(), 0), w * h);  // empty: nothing
}

}  // namespace
}  // namespace shadowvol::raster
