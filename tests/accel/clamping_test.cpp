// CC shadow volumes' clamping in light space (accel/continuous_clamping.h), its slices
// (accel/slices.h) and sub-objects (accel/sub_objects.h), by hand-made boxes and meshes whose
// answer is known.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/ext/matrix_transform.hpp>

#include "accel/continuous_clamping.h"
#include "accel/slices.h"
#include "accel/sub_objects.h"
#include "core/projection.h"
#include "core/shapes.h"
#include "core/topology.h"

namespace shadowvol {
namespace {

using Item = ContinuousClamping::Item;
using LightBox = LightViews::LightBox;

// A caster in light space over [0, 1] x [0, 1] at depths [1, 2].
Item caster() {
  Item item;
  item.casts = true;
  item.caster = {0, 1, 0, 1, 1, 2};
  item.interval_vertices = 100;
  return item;
}
Item receiver(LightBox box) {
  Item item;
  item.receives = true;
  item.receiver = box;
  return item;
}

struct Clamped {
  std::vector<std::uint32_t> offsets;
  std::vector<Interval> intervals;
  ContinuousClamping::Stats stats;
  std::vector<Interval> of(std::size_t i) const {
    return {intervals.begin() + offsets[i], intervals.begin() + offsets[i + 1]};
  }
};

Clamped clamp(ContinuousClamping& clamping, const std::vector<Item>& items, double vertex_cost,
              double gap_cost) {
  Clamped out;
  clamping.clamp(
      items, 0.01, vertex_cost, [&](std::size_t, double, double) { return gap_cost; }, out.offsets,
      out.intervals, out.stats);
  return out;
}

constexpr double kMargin = 0.01;

// §3.2.1's three cases: a receiver held by the last interval changes nothing, one that reaches
// past it extends it, one beyond it starts a new interval; one beside the caster's rectangle, or
// wholly nearer than the caster, takes no part.
TEST(ContinuousClamping, BuildsTheOccupiedIntervalsByThePapersThreeCases) {
  ContinuousClamping clamping;
  const std::vector<Item> items{
      caster(),
      receiver({0.2, 0.4, 0.2, 0.4, 5, 6}),      // a new interval
      receiver({0.5, 0.9, 0.5, 0.9, 5.2, 5.8}),  // held by it (case 1)
      receiver({0.1, 0.3, 0.6, 0.7, 5.5, 7}),    // extends it (case 2)
      receiver({0.0, 1.0, 0.0, 1.0, 10, 11}),    // another interval (case 3)
      receiver({2.0, 3.0, 0.0, 1.0, 8, 9}),      // beside it in u
      receiver({0.0, 1.0, 0.0, 1.0, 0.2, 0.5}),  // nearer than the caster
  };
  const Clamped c = clamp(clamping, items, 0.0, 1.0);  // no gap too cheap to keep
  const std::vector<Interval> own = c.of(0);
  ASSERT_EQ(own.size(), 3u);
  EXPECT_EQ(own[0].begin, -INFINITY);  // from the caster itself
  EXPECT_DOUBLE_EQ(own[0].end, 2 + kMargin);
  EXPECT_DOUBLE_EQ(own[1].begin, 5 - kMargin);
  EXPECT_DOUBLE_EQ(own[1].end, 7 + kMargin);
  EXPECT_DOUBLE_EQ(own[2].begin, 10 - kMargin);
  EXPECT_DOUBLE_EQ(own[2].end, 11 + kMargin);
  for (std::size_t i = 1; i < items.size(); ++i) EXPECT_TRUE(c.of(i).empty()) << i;
  EXPECT_EQ(c.stats.pairs, 4u);  // the four receivers over the caster, beyond its nearest depth
  EXPECT_EQ(c.stats.merged_by_cost, 0u);
}

// V > R: where drawing the new interval's caps and sides costs more than the gap it skips, the
// receiver is merged as in case 2: one interval.
TEST(ContinuousClamping, MergesAGapThatCostsLessThanANewInterval) {
  ContinuousClamping clamping;
  const std::vector<Item> items{caster(), receiver({0.2, 0.4, 0.2, 0.4, 5, 6})};
  const Clamped kept = clamp(clamping, items, 1e-6, 1.0);  // V = 1e-4 < R = 1: a gap of its own
  EXPECT_EQ(kept.of(0).size(), 2u);
  const Clamped merged = clamp(clamping, items, 1.0, 1e-3);  // V = 100 > R: merged
  ASSERT_EQ(merged.of(0).size(), 1u);
  EXPECT_DOUBLE_EQ(merged.of(0)[0].end, 6 + kMargin);
  EXPECT_EQ(merged.stats.merged_by_cost, 1u);
}

// Temporal coherence: a frame whose boxes moved a little is sorted in few interchanges, and one
// whose order changed gets the same intervals as a fresh sort would.
TEST(ContinuousClamping, SortsTheNextFrameFromTheLastOrder) {
  std::vector<Item> items{caster()};
  for (int i = 0; i < 40; ++i)
    items.push_back(receiver({0.02 * i, 0.02 * i + 0.1, 0.5, 0.6, 3.0 + i, 3.5 + i}));
  ContinuousClamping clamping;
  const Clamped first = clamp(clamping, items, 0.0, 1.0);
  EXPECT_EQ(first.stats.swaps, 0u);  // a fresh set is sorted whole, not by interchanges
  for (Item& item : items) item.receiver.u0 += 1e-3, item.receiver.u1 += 1e-3;
  const Clamped moved = clamp(clamping, items, 0.0, 1.0);
  EXPECT_EQ(moved.stats.swaps, 0u);  // still in order
  EXPECT_EQ(moved.intervals.size(), first.intervals.size());
  std::swap(items[3].receiver, items[30].receiver);  // two trade places in u and in depth
  const Clamped swapped = clamp(clamping, items, 0.0, 1.0);
  EXPECT_GT(swapped.stats.swaps, 0u);
  ContinuousClamping fresh;
  const Clamped expected = clamp(fresh, items, 0.0, 1.0);
  ASSERT_EQ(swapped.intervals.size(), expected.intervals.size());
  for (std::size_t i = 0; i < expected.intervals.size(); ++i) {
    EXPECT_EQ(swapped.intervals[i].begin, expected.intervals[i].begin) << i;
    EXPECT_EQ(swapped.intervals[i].end, expected.intervals[i].end) << i;
  }
}

// The slicing planes through the eye split the image into strips across the way shadows run:
// for a light far to the left of the view, vertical strips, numbered left to right; a point
// within a pixel and a half of a strip's edge belongs to both strips.
TEST(Slices, RunAcrossTheShadowsAndOverlapByAPixelAndAHalf) {
  const glm::mat4 view_proj = infinite_reversed_perspective(1.0f, 1.0f, 0.1f) *
                              glm::lookAt(glm::vec3(0.0f), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
  const Slices s = make_slices(view_proj, {-100.0f, 0.0f, -10.0f, 1.0f}, 100, 100, 4);
  EXPECT_NEAR(s.across.x, 1.0, 1e-9);  // shadows run right, away from the light
  EXPECT_NEAR(s.across.y, 0.0, 1e-9);
  EXPECT_EQ(s.count, 4);
  EXPECT_NEAR(s.first, -1.0, 1e-9);
  EXPECT_NEAR(s.width, 0.5, 1e-9);
  EXPECT_NEAR(s.margin, 1.5 * 2.0 / 100.0, 1e-9);
  const LayerRange middle = s.of(-0.25);
  EXPECT_EQ(middle.first, 1);
  EXPECT_EQ(middle.last, 1);
  const LayerRange edge = s.of(0.0 - 0.02);  // within the margin of the edge at 0
  EXPECT_EQ(edge.first, 1);
  EXPECT_EQ(edge.last, 2);
  const LayerRange all = s.of(-5.0, 5.0);
  EXPECT_EQ(all.first, 0);
  EXPECT_EQ(all.last, 3);
  // Strips 1 and 2 as one: bounded on both sides; from the first strip: open to the left.
  const raster::ScreenStrip inner = s.strip(1, 2);
  EXPECT_FLOAT_EQ(inner.lo, -0.5f);
  EXPECT_FLOAT_EQ(inner.hi, 0.5f);
  const raster::ScreenStrip left = s.strip(0, 1);
  EXPECT_EQ(left.lo, -INFINITY);
  EXPECT_FLOAT_EQ(left.hi, 0.0f);
  EXPECT_TRUE(s.strip(0, 3).whole());
}

// A floor of two triangles, 16 x 16, split into cells of 4: each triangle belongs to the cell of
// its centroid; every cell holds the part of the floor within it as a receiver.
TEST(SubObjects, SplitALargeMeshIntoCellsEachWithItsPartOfTheSurface) {
  const Topology floor = build_topology(make_ground(8.0f));
  const SubObjects split = split_sub_objects(floor, 4.0f, 256);
  ASSERT_EQ(split.leaves.size(), 16u);
  ASSERT_EQ(split.face_leaf.size(), 2u);
  std::size_t casting = 0;
  for (const SubObjects::Leaf& leaf : split.leaves) {
    casting += leaf.casts();
    EXPECT_LE(leaf.receiver_hi.x - leaf.receiver_lo.x, 4.0f + 1e-5f);
    EXPECT_LE(leaf.receiver_hi.z - leaf.receiver_lo.z, 4.0f + 1e-5f);
    EXPECT_EQ(leaf.receiver_lo.y, 0.0f);
    EXPECT_EQ(leaf.receiver_hi.y, 0.0f);
  }
  EXPECT_EQ(casting, 2u);  // the two triangles' cells
  for (std::uint32_t f = 0; f < 2; ++f) {
    const SubObjects::Leaf& own = split.leaves[split.face_leaf[f]];
    EXPECT_EQ(own.faces, 1u);
    EXPECT_EQ(own.caster_hi.x - own.caster_lo.x, 16.0f);  // the whole triangle
  }
  // Every vertex: the leaves of the faces around it (a corner of both triangles: two).
  ASSERT_EQ(split.vertex_leaf_offsets.size(), floor.positions.size() + 1);
  std::size_t shared = 0;
  for (std::size_t v = 0; v < floor.positions.size(); ++v)
    shared += split.vertex_leaf_offsets[v + 1] - split.vertex_leaf_offsets[v] == 2;
  EXPECT_EQ(shared, 2u);  // the diagonal's ends
  // A mesh no longer than a cell stays whole.
  EXPECT_EQ(split_sub_objects(floor, 32.0f, 256).leaves.size(), 1u);
  // The limit on leaves holds.
  EXPECT_LE(split_sub_objects(floor, 0.5f, 10).leaves.size(), 10u);
}

}  // namespace
}  // namespace shadowvol
