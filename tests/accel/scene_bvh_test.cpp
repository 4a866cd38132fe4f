// The scene BVH's promises (accel/scene_bvh.h): every item with a box in exactly one leaf, every
// node's box the union of what lies below it (after build and after refit), depth-first order,
// the surface area heuristic doing better than halving by index on clustered scenes, and the
// rebuild cue as items drift.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/common.hpp>

#include "accel/scene_bvh.h"

namespace shadowvol {
namespace {

BvhBox box_at(glm::vec3 centre, float half) { return {centre - half, centre + half}; }

// Checks the tree against `boxes`: returns the items reached, in leaf order, and expects every
// node's box to be exactly the union of its children's or items' boxes.
std::vector<std::uint32_t> check_tree(const SceneBvh& bvh, const std::vector<BvhBox>& boxes) {
  std::vector<std::uint32_t> reached;
  const auto nodes = bvh.nodes();
  for (std::uint32_t n = 0; n < nodes.size(); ++n) {
    const SceneBvh::Node& node = nodes[n];
    BvhBox expected;
    auto grow = [&](const BvhBox& b) {
      expected.lo = glm::min(expected.lo, b.lo);
      expected.hi = glm::max(expected.hi, b.hi);
    };
    if (node.leaf()) {
      EXPECT_LE(node.count, SceneBvh::kMaxLeafItems);
      for (const std::uint32_t item : bvh.items_of(node)) {
        grow(boxes[item]);
        reached.push_back(item);
      }
    } else {
      const std::uint32_t second = bvh.second_child(n);
      EXPECT_GT(second, n + 1) << "the second child follows the first's subtree";
      EXPECT_LT(second, nodes.size());
      grow(nodes[n + 1].box);
      grow(nodes[second].box);
    }
    EXPECT_EQ(node.box.lo, expected.lo) << "node " << n;
    EXPECT_EQ(node.box.hi, expected.hi) << "node " << n;
  }
  return reached;
}

// Boxes in a few tight clusters far apart, as buildings stand in blocks.
std::vector<BvhBox> clustered(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-1.0f, 1.0f);
  std::vector<BvhBox> boxes;
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3 block(float(i % 5) * 100.0f, 0.0f, float(i % 3) * 100.0f);
    boxes.push_back(box_at(block + glm::vec3(jitter(rng), jitter(rng), jitter(rng)) * 5.0f,
                           0.5f + 0.5f * std::abs(jitter(rng))));
  }
  return boxes;
}

TEST(SceneBvh, HoldsEveryItemWithABoxOnceUnderTightBoxes) {
  std::vector<BvhBox> boxes = clustered(1000, 1);
  boxes[17] = {};   // an object without vertices
  boxes[400] = {};  // and another
  SceneBvh bvh;
  bvh.build(boxes);
  ASSERT_FALSE(bvh.empty());
  std::vector<std::uint32_t> reached = check_tree(bvh, boxes);
  std::sort(reached.begin(), reached.end());
  std::vector<std::uint32_t> expected;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    if (i != 17 && i != 400) expected.push_back(i);
  EXPECT_EQ(reached, expected);
  EXPECT_EQ(bvh.nodes().size() % 2, 1u) << "a binary tree: one more leaf than inner nodes";
}

TEST(SceneBvh, SmallAndEmptyInputs) {
  SceneBvh bvh;
  bvh.build({});
  EXPECT_TRUE(bvh.empty());
  EXPECT_EQ(bvh.sah_cost(), 0.0);
  const std::vector<BvhBox> nothing(3);  // all without vertices
  bvh.build(nothing);
  EXPECT_TRUE(bvh.empty());
  const std::vector<BvhBox> one = {box_at(glm::vec3(1, 2, 3), 1)};
  bvh.build(one);
  ASSERT_EQ(bvh.nodes().size(), 1u);
  EXPECT_TRUE(bvh.root().leaf());
  EXPECT_EQ(check_tree(bvh, one), std::vector<std::uint32_t>{0});
  // Many items at one point: no axis separates them, the tree halves them by index.
  const std::vector<BvhBox> stacked(100, box_at(glm::vec3(5), 1));
  bvh.build(stacked);
  EXPECT_EQ(check_tree(bvh, stacked).size(), stacked.size());
}

TEST(SceneBvh, TheSurfaceAreaHeuristicSeparatesClusters) {
  const std::vector<BvhBox> boxes = clustered(600, 2);
  SceneBvh bvh;
  bvh.build(boxes);
  // No inner node below the root's children straddles two clusters: each node's box fits in one
  // block's 100-unit cell, the top few levels excepted (15 blocks: at most 14 splits between them).
  std::size_t straddling = 0;
  for (const SceneBvh::Node& node : bvh.nodes())
    if (std::max(node.box.hi.x - node.box.lo.x, node.box.hi.z - node.box.lo.z) > 50.0f)
      ++straddling;
  EXPECT_LE(straddling, 14u);
  // Halving by index (every item of a leaf from every cluster) costs far more.
  SceneBvh by_index;
  std::vector<BvhBox> collapsed(boxes.size(), box_at(glm::vec3(0), 1));
  by_index.build(collapsed);  // the same shape of tree, refitted over the real boxes
  by_index.refit(boxes);
  EXPECT_LT(bvh.sah_cost() * 4.0, by_index.sah_cost());
}

TEST(SceneBvh, RefitFollowsMovingItemsAndCuesARebuildAsTheyScatter) {
  std::vector<BvhBox> boxes = clustered(500, 3);
  SceneBvh bvh;
  bvh.build(boxes);
  const double built = bvh.sah_cost();
  EXPECT_FALSE(bvh.needs_rebuild());
  // A small move: still tight, about as cheap.
  for (BvhBox& b : boxes) b = {b.lo + glm::vec3(0.1f, 0, 0), b.hi + glm::vec3(0.1f, 0, 0)};
  bvh.refit(boxes);
  check_tree(bvh, boxes);
  EXPECT_NEAR(bvh.sah_cost(), built, built * 0.05);
  EXPECT_FALSE(bvh.needs_rebuild());
  // Scattered anywhere: still tight and correct, but costly; a rebuild restores the cost.
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> anywhere(0.0f, 500.0f);
  for (BvhBox& b : boxes) b = box_at(glm::vec3(anywhere(rng), 0, anywhere(rng)), 1.0f);
  bvh.refit(boxes);
  std::vector<std::uint32_t> reached = check_tree(bvh, boxes);
  EXPECT_EQ(reached.size(), boxes.size());
  EXPECT_TRUE(bvh.needs_rebuild());
  const double refitted = bvh.sah_cost();
  bvh.build(boxes);
  EXPECT_LT(bvh.sah_cost() * 2.0, refitted);
  EXPECT_FALSE(bvh.needs_rebuild());
  // An item that loses its vertices keeps its place, with nothing in it.
  boxes[0] = {};
  bvh.refit(boxes);
  check_tree(bvh, boxes);
}

// The leaves' items in the order a depth-first walk that takes the nearer child first meets them.
std::vector<std::uint32_t> front_to_back(const SceneBvh& bvh, const glm::vec3& eye) {
  std::vector<std::uint32_t> order, stack{0};
  while (!stack.empty()) {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    const SceneBvh::Node& node = bvh.nodes()[n];
    if (node.leaf()) {
      for (const std::uint32_t item : bvh.items_of(node)) order.push_back(item);
      continue;
    }
    const auto [near, far] = bvh.children_near_first(n, eye);
    stack.push_back(far);
    stack.push_back(near);
  }
  return order;
}

TEST(SceneBvh, AWalkNearerChildFirstMeetsItemsFrontToBack) {
  // A row of boxes along x, 3 apart; leaves hold up to 4, so order is checked leaf by leaf.
  std::vector<BvhBox> row;
  for (int i = 0; i < 100; ++i) row.push_back(box_at(glm::vec3(3.0f * i, 0, 0), 1.0f));
  SceneBvh bvh;
  bvh.build(row);
  auto position = [&](const std::vector<std::uint32_t>& order, std::size_t k) {
    return row[order[k]].lo.x;
  };
  for (const float eye_x : {-50.0f, 400.0f}) {
    const std::vector<std::uint32_t> order = front_to_back(bvh, glm::vec3(eye_x, 0, 0));
    ASSERT_EQ(order.size(), row.size());
    // Every item meets the walk before any item more than a leaf's width (4 boxes) farther away.
    for (std::size_t k = 0; k + 1 < order.size(); ++k)
      for (std::size_t j = k + 1; j < order.size(); ++j)
        EXPECT_LE(std::abs(position(order, k) - eye_x),
                  std::abs(position(order, j) - eye_x) + 3.0f * SceneBvh::kMaxLeafItems)
            << "eye at " << eye_x;
  }
  // An eye in the middle of the row meets the item it stands at among the first leaf's.
  const std::vector<std::uint32_t> order = front_to_back(bvh, glm::vec3(150.0f, 0, 0));
  const auto first = std::find(order.begin(), order.end(), 50u);
  EXPECT_LT(first - order.begin(), std::ptrdiff_t(SceneBvh::kMaxLeafItems));
}

TEST(SceneBvh, IsDeterministic) {
  const std::vector<BvhBox> boxes = clustered(300, 5);
  SceneBvh a, b;
  a.build(boxes);
  b.build(boxes);
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  EXPECT_TRUE(std::equal(a.items().begin(), a.items().end(), b.items().begin()));
  for (std::size_t n = 0; n < a.nodes().size(); ++n) {
    EXPECT_EQ(a.nodes()[n].first, b.nodes()[n].first);
    EXPECT_EQ(a.nodes()[n].count, b.nodes()[n].count);
  }
}

}  // namespace
}  // namespace shadowvol
