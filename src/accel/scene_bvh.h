// shadowvol accel: the scene's bounding volume hierarchy over its objects' boxes, the tree that
// hierarchical occlusion culling walks (Bittner, Wimmer, Piringer and Purgathofer 2004, "CHC";
// GPU Gems 3 ch. 11 §11.3.3 tests each node's box extruded away from the light).
//
// Owns: a binary tree of axis-aligned boxes over items (objects, by index), built by the surface
// area heuristic over binned centroids, and its refit when the items move. Nodes are stored
// depth first: a node's first child follows it, its second is at `second`; a leaf holds
// items[first .. first + count). Every node's box is the union of its items' boxes (tight), so a
// node hidden from a view hides everything below it.
//
// Moving items: refit() keeps the tree and recomputes its boxes bottom up (linear, no
// allocation); as items drift apart its boxes overlap more and the tree culls less, which
// sah_cost() measures. needs_rebuild() says when the refitted tree costs more than kRebuildFactor
// times what it cost when built, the caller's cue to build again (O(n log n)).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace shadowvol {

struct BvhBox {
  glm::vec3 lo{INFINITY}, hi{-INFINITY};
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
};

class SceneBvh {
 public:
  struct Node {
    BvhBox box;
    std::uint32_t first = 0;  // a leaf: its first item; an inner node: its second child
    std::uint32_t count = 0;  // a leaf: its items (at least 1); an inner node: 0
    bool leaf() const { return count > 0; }
  };
  // One object a leaf: occlusion culling culls a leaf only where all of it is hidden.
  static constexpr std::size_t kMaxLeafItems = 1;
  static constexpr double kRebuildFactor = 1.5;

  // Builds over `boxes` (one per item). Items with an empty box (lo > hi: an object without
  // vertices) have nothing to draw and are left out of the tree. Deterministic.
  void build(std::span<const BvhBox> boxes);
  // The same tree over the items' new boxes (as many as at build). An item whose box became
  // empty keeps its place with nothing in it.
  void refit(std::span<const BvhBox> boxes);

  std::span<const Node> nodes() const { return nodes_; }
  std::span<const std::uint32_t> items() const { return items_; }  // leaves' items, in order
  const Node& root() const { return nodes_.front(); }
  bool empty() const { return nodes_.empty(); }
  std::uint32_t second_child(std::uint32_t node) const { return nodes_[node].first; }
  std::span<const std::uint32_t> items_of(const Node& leaf) const {
    return std::span(items_).subspan(leaf.first, leaf.count);
  }
  // An inner node's children, the one nearer `eye` first (by distance to its box, then to its
  // box's centre): the order in which a front-to-back walk, as CHC's, takes them.
  std::array<std::uint32_t, 2> children_near_first(std::uint32_t node, const glm::vec3& eye) const;

  // The surface area heuristic's cost of the tree: the expected number of node and item boxes a
  // random ray that meets the root tests, sum over nodes of area(node) / area(root) times 1 for
  // an inner node, its items for a leaf. 0 for an empty tree.
  double sah_cost() const;
  // Whether refits have made the tree kRebuildFactor times costlier than when it was built.
  bool needs_rebuild() const { return sah_cost() > kRebuildFactor * built_cost_; }

 private:
  void build_nodes(std::span<const BvhBox> boxes);

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> items_;
  double built_cost_ = 0.0;
};

}  // namespace shadowvol
