#include "render/occlusion_culling.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <utility>

#include <glm/common.hpp>

#include "accel/box_queries.h"
#include "accel/near_plane.h"

namespace shadowvol {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The squared distance from the eye (the origin) to a box.
float distance2(const BvhBox& box) {
  const glm::vec3 d = glm::max(glm::max(box.lo, -box.hi), glm::vec3(0.0f));
  return d.x * d.x + d.y * d.y + d.z * d.z;
}

}  // namespace

void OcclusionCulling::begin_frame(const FramePlan& plan, FrameStats& stats) {
  const auto start = Clock::now();
  ++frame_;
  boxes_.resize(plan.objects.size());
  for (std::size_t o = 0; o < plan.objects.size(); ++o)
    boxes_[o] = {plan.objects[o].lo, plan.objects[o].hi};
  if (built_for_ != boxes_.size() || bvh_.empty()) {
    bvh_.build(boxes_);
    built_for_ = boxes_.size();
    ++stats.bvh_rebuilt;
  } else {
    bvh_.refit(boxes_);
    if (bvh_.needs_rebuild()) bvh_.build(boxes_), ++stats.bvh_rebuilt;
  }
  if (stats.bvh_rebuilt > 0) {  // new nodes: no history
    eye_.assign(bvh_.nodes().size(), NodeState{});
    for (std::vector<NodeState>& light : lights_) light.assign(bvh_.nodes().size(), NodeState{});
    parent_.assign(bvh_.nodes().size(), 0);
    for (std::uint32_t n = 0; n < bvh_.nodes().size(); ++n)
      if (!bvh_.nodes()[n].leaf()) parent_[n + 1] = parent_[bvh_.second_child(n)] = n;
  }
  stats.ms_bvh += ms_since(start);
}

template <class Classify, class Query, class OpenLeaf, class BeforeQuery>
void OcclusionCulling::walk(FrameBackend& backend, std::vector<NodeState>& state,
                            bool surfaces_only, Classify&& classify, Query&& query,
                            OpenLeaf&& open_leaf, BeforeQuery&& before_query, FrameStats& stats) {
  if (bvh_.empty()) return;
  const std::span<const SceneBvh::Node> nodes = bvh_.nodes();
  opened_.assign(nodes.size(), 0);
  // The nodes to visit, nearest first: a heap in storage kept between walks.
  std::vector<Entry>& nearest = nearest_;
  nearest.clear();
  auto push = [&](std::uint32_t n) {
    nearest.emplace_back(distance2(nodes[n].box), n);
    std::push_heap(nearest.begin(), nearest.end(), std::greater<Entry>());
  };
  auto open = [&](std::uint32_t n) {
    opened_[n] = 1;
    if (nodes[n].leaf()) return open_leaf(nodes[n]);
    for (const std::uint32_t child : {n + 1, bvh_.second_child(n)}) push(child);
  };
  auto pull_up = [&](std::uint32_t n) {
    for (;;) {
      if (state[n].visible && state[n].frame == frame_) return;
      state[n] = {true, frame_};
      if (n == 0) return;
      n = parent_[n];
    }
  };
  push(0);
  queries_.clear();
  while (!nearest.empty() || !queries_.empty()) {
    // Answers first, in order: those ready, or the next one when nothing else is left to do.
    while (!queries_.empty() && (nearest.empty() || backend.query_ready(queries_.front().query))) {
      const Pending done = queries_.front();
      queries_.pop_front();
      stats.queries_waited += !backend.query_ready(done.query);
      if (!backend.query_visible(done.query)) continue;
      if (!opened_[done.node]) open(done.node);
      pull_up(done.node);
    }
    if (nearest.empty()) continue;
    std::pop_heap(nearest.begin(), nearest.end(), std::greater<Entry>());
    const std::uint32_t n = nearest.back().second;
    nearest.pop_back();
    ++stats.nodes_visited;
    const bool was_visible = state[n].visible && state[n].frame == frame_ - 1;
    state[n] = {false, frame_};
    switch (classify(nodes[n].box)) {
      case Standing::outside:
        continue;
      case Standing::visible:
        pull_up(n);
        open(n);
        continue;
      case Standing::query:
        break;
    }
    // A node visible last frame is opened now; an inner one needs no query (its children's
    // answers pull its visibility up), a leaf is queried for the next frame.
    if (!was_visible || nodes[n].leaf()) {
      before_query();
      triangles_.clear();
      query(nodes[n].box, triangles_);
      queries_.push_back({n, backend.issue_query(triangles_, surfaces_only)});
      ++stats.queries;
    }
    if (was_visible) open(n);
  }
}

void OcclusionCulling::depth_pass(const FramePlan& plan, FrameBackend& backend, FrameStats& stats) {
  drawn_.assign(plan.objects.size(), 0);
  batch_.clear();
  auto flush = [&] {
    if (batch_.empty()) return;
    backend.draw_depth(batch_);
    batch_.clear();
  };
  const std::array<glm::vec3, 4> near_rect = near_rectangle(plan.inv_view_proj);
  backend.begin_depth(Layer::opaque);
  walk(
      backend, eye_, false,
      [&](const BvhBox& box) {
        return box_outside_frustum(box.lo, box.hi, plan.view_proj) ? Standing::outside
               : box_meets_near(box.lo, box.hi, near_rect)         ? Standing::visible
                                                                   : Standing::query;
      },
      [](const BvhBox& box, std::vector<glm::vec4>& out) {
        box_query_triangles(box.lo, box.hi, out);
      },
      [&](const SceneBvh::Node& leaf) {
        for (const std::uint32_t o : bvh_.items_of(leaf))
          if (!plan.transparent(o) && !drawn_[o]) drawn_[o] = 1, batch_.push_back(o);
      },
      flush, stats);
  flush();
  backend.end_depth();
  for (std::size_t o = 0; o < plan.objects.size(); ++o) {
    if (plan.transparent(o)) continue;
    const bool has_box = plan.objects[o].lo.x <= plan.objects[o].hi.x;
    stats.objects_drawn += drawn_[o];
    stats.objects_culled += has_box && !drawn_[o];
  }
}

void OcclusionCulling::cull_volumes(FramePlan& plan, std::size_t l, FrameBackend& backend,
                                    bool surfaces_only, FrameStats& stats) {
  const auto start = Clock::now();
  if (lights_.size() <= l) lights_.resize(l + 1);
  if (lights_[l].size() != bvh_.nodes().size()) lights_[l].assign(bvh_.nodes().size(), NodeState{});
  const glm::vec4 light = plan.lights[l];
  const std::array<glm::vec3, 4> near_rect = near_rectangle(plan.inv_view_proj);
  kept_.assign(plan.objects.size(), 0);
  walk(
      backend, lights_[l], surfaces_only,
      [&](const BvhBox& box) {
        return shadow_meets_near(box.lo, box.hi, light, near_rect) ? Standing::visible
                                                                   : Standing::query;
      },
      [&](const BvhBox& box, std::vector<glm::vec4>& out) {
        shadow_query_triangles(box.lo, box.hi, light, out);
      },
      [&](const SceneBvh::Node& leaf) {
        for (const std::uint32_t o : bvh_.items_of(leaf)) kept_[o] = 1;
      },
      [] {}, stats);
  for (std::size_t o = 0; o < plan.objects.size(); ++o) {
    VolumePlan& v = plan.volume(l, o);
    const bool has_box = plan.objects[o].lo.x <= plan.objects[o].hi.x;
    if (v.culled || kept_[o] || !has_box) continue;
    v.culled = true;
    ++stats.volumes_culled;
    ++stats.culled_lights[o];
  }
  stats.ms_occlusion += ms_since(start);
}

}  // namespace shadowvol
