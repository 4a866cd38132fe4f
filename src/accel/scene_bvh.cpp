#include "accel/scene_bvh.h"

#include <algorithm>
#include <array>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace shadowvol {
namespace {

constexpr int kBins = 16;

BvhBox merged(const BvhBox& a, const BvhBox& b) {
  return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}

double area(const BvhBox& b) {
  if (b.empty()) return 0.0;
  const glm::dvec3 d = glm::dvec3(b.hi) - glm::dvec3(b.lo);
  return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

glm::vec3 centroid(const BvhBox& b) { return (b.lo + b.hi) * 0.5f; }

}  // namespace

void SceneBvh::build(std::span<const BvhBox> boxes) {
  nodes_.clear();
  items_.clear();
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (!boxes[i].empty()) items_.push_back(static_cast<std::uint32_t>(i));
  if (!items_.empty()) {
    nodes_.reserve(2 * items_.size() / kMaxLeafItems + 1);
    build_nodes(boxes);
  }
  built_cost_ = sah_cost();
}

// Depth first with an explicit stack (a skewed scene would recurse as deep as it has items):
// each task makes one node; an inner node's first child is the next node made, its second is
// patched in when that task is taken.
void SceneBvh::build_nodes(std::span<const BvhBox> boxes) {
  struct Task {
    std::size_t first, count;
    std::uint32_t parent;  // whose second child this is; UINT32_MAX: none
  };
  std::vector<Task> stack{{0, items_.size(), UINT32_MAX}};
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    if (task.parent != UINT32_MAX) nodes_[task.parent].first = index;
    Node node;
    BvhBox centroids;
    for (std::size_t i = task.first; i < task.first + task.count; ++i) {
      const BvhBox& b = boxes[items_[i]];
      node.box = merged(node.box, b);
      centroids = merged(centroids, {centroid(b), centroid(b)});
    }
    if (task.count <= kMaxLeafItems) {
      node.first = static_cast<std::uint32_t>(task.first);
      node.count = static_cast<std::uint32_t>(task.count);
      nodes_.push_back(node);
      continue;
    }
    // The surface area heuristic over kBins bins of centroids on each axis: the split that
    // minimises area(left) * |left| + area(right) * |right|.
    double best_cost = INFINITY;
    int best_axis = -1, best_split = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = centroids.lo[axis], extent = centroids.hi[axis] - lo;
      if (!(extent > 0.0f)) continue;
      std::array<BvhBox, kBins> bin_box{};
      std::array<std::size_t, kBins> bin_count{};
      for (std::size_t i = task.first; i < task.first + task.count; ++i) {
        const BvhBox& b = boxes[items_[i]];
        const int bin = std::min(kBins - 1, int((centroid(b)[axis] - lo) / extent * kBins));
        bin_box[bin] = merged(bin_box[bin], b);
        ++bin_count[bin];
      }
      std::array<double, kBins> right_cost{};  // of bins [k, kBins)
      BvhBox right;
      std::size_t right_count = 0;
      for (int k = kBins - 1; k > 0; --k) {
        right = merged(right, bin_box[k]);
        right_count += bin_count[k];
        right_cost[k] = area(right) * double(right_count);
      }
      BvhBox left;
      std::size_t left_count = 0;
      for (int k = 1; k < kBins; ++k) {  // left: bins [0, k)
        left = merged(left, bin_box[k - 1]);
        left_count += bin_count[k - 1];
        if (left_count == 0 || left_count == task.count) continue;
        const double cost = area(left) * double(left_count) + right_cost[k];
        if (cost < best_cost) best_cost = cost, best_axis = axis, best_split = k;
      }
    }
    std::size_t middle = task.first + task.count / 2;  // coincident centroids: halves by index
    if (best_axis >= 0) {
      const float lo = centroids.lo[best_axis];
      const float extent = centroids.hi[best_axis] - lo;
      auto* begin = items_.data() + task.first;
      auto* split = std::stable_partition(begin, begin + task.count, [&](std::uint32_t item) {
        const int bin =
            std::min(kBins - 1, int((centroid(boxes[item])[best_axis] - lo) / extent * kBins));
        return bin < best_split;
      });
      // The binning above saw both sides non-empty; were rounding to disagree, halve instead.
      const auto at = static_cast<std::size_t>(split - items_.data());
      if (at > task.first && at < task.first + task.count) middle = at;
    }
    nodes_.push_back(node);
    stack.push_back({middle, task.first + task.count - middle, index});
    stack.push_back({task.first, middle - task.first, UINT32_MAX});
  }
}

std::array<std::uint32_t, 2> SceneBvh::children_near_first(std::uint32_t node,
                                                           const glm::vec3& eye) const {
  const std::uint32_t first = node + 1, second = second_child(node);
  auto key = [&](std::uint32_t child) {
    const BvhBox& b = nodes_[child].box;
    const glm::vec3 outside = glm::max(glm::max(b.lo - eye, eye - b.hi), glm::vec3(0.0f));
    const glm::vec3 to_centre = centroid(b) - eye;
    return std::pair(glm::dot(outside, outside), glm::dot(to_centre, to_centre));
  };
  if (key(second) < key(first)) return {second, first};
  return {first, second};
}

void SceneBvh::refit(std::span<const BvhBox> boxes) {
  // Children follow their parents, so one pass from the back sees every child first.
  for (std::size_t n = nodes_.size(); n-- > 0;) {
    Node& node = nodes_[n];
    node.box = {};
    if (node.leaf()) {
      for (const std::uint32_t item : items_of(node)) node.box = merged(node.box, boxes[item]);
    } else {
      node.box = merged(nodes_[n + 1].box, nodes_[node.first].box);
    }
  }
}

double SceneBvh::sah_cost() const {
  if (nodes_.empty()) return 0.0;
  const double root_area = area(root().box);
  double cost = 0.0;
  for (const Node& node : nodes_) {
    const double weight = node.leaf() ? double(node.count) : 1.0;
    cost += weight * (root_area > 0.0 ? area(node.box) / root_area : 1.0);
  }
  return cost;
}

}  // namespace shadowvol
