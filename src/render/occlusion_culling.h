// shadowvol render: OcclusionCulling, hierarchical occlusion culling of the depth pass and of the
// shadow volumes over the scene's BVH (Bittner, Wimmer, Piringer and Purgathofer 2004, "CHC";
// GPU Gems 3 ch. 11 §11.3.3), on any backend through its occlusion queries.
//
// Owns: the scene BVH over the objects' eye-relative boxes (refit every frame, rebuilt where the
// refits made it kRebuildFactor costlier, or the objects changed), and per node, for the eye and
// for each light, whether it was visible and in which frame: the coherence that lets a node
// visible last frame be drawn without waiting for its query.
//   - Eye (depth_pass): the opaque layer's depth pass front to back. A node outside the frustum is
//     skipped; one that may meet the near plane is visible without a query; one visible last frame
//     is opened at once (an inner node, without a query; a leaf is drawn and queried for the next
//     frame); any other is queried against the depth drawn so far and opened where it shows.
//     Objects go to the backend in batches, one draw each, sent before every query (whose answer
//     needs them in the depth target).
//   - Shadows (cull_volumes): per light, after the depth pass, each node's box extruded away from
//     the light (accel/box_queries.h) is queried against the finished depth: a hidden one holds no
//     visible surface, so no volume below it can change a pixel, and those volumes are culled. A
//     point light in the box or a region that may meet the near plane is visible without a query.
// Queries are answered in the order they were issued; a query not ready when the walk has nothing
// else to do is waited for (FrameStats::queries_waited). The queries over-cover (box_queries.h),
// so no visible surface and no shadow is ever lost: the frame is the one drawn without culling.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#include "accel/scene_bvh.h"
#include "render/frame.h"
#include "render/frame_backend.h"
#include "render/frame_plan.h"

namespace shadowvol {

class OcclusionCulling {
 public:
  // A new frame: the tree made current for the plan's boxes (ms_bvh, bvh_rebuilt).
  void begin_frame(const FramePlan& plan, FrameStats& stats);
  // The opaque layer's depth pass (begin_depth .. end_depth) by CHC; drawn[o] = 1 for the
  // objects drawn. Counts its work into stats (nodes, queries, objects culled and drawn, ms_bvh).
  void depth_pass(const FramePlan& plan, FrameBackend& backend, FrameStats& stats);
  // Culls light l's volumes whose objects' extruded boxes show nothing (VolumePlan::culled), on
  // the finished depth target; `surfaces_only`: only surfaces receive (no transparent ones are
  // drawn later). Counts into stats (volumes_culled, queries, ms_occlusion).
  void cull_volumes(FramePlan& plan, std::size_t light, FrameBackend& backend, bool surfaces_only,
                    FrameStats& stats);
  // Per object, 1 where the last depth_pass drew it.
  const std::vector<std::uint8_t>& drawn() const { return drawn_; }

 private:
  struct NodeState {
    bool visible = false;
    std::int64_t frame = -2;  // the frame `visible` was decided in
  };
  // CHC's walk over the tree with `state`: `classify` says where a node stands, `query` writes its
  // query's triangles, `open_leaf` takes a visible leaf's items, `before_query` runs before each
  // query is issued.
  enum class Standing : std::uint8_t { outside, visible, query };
  template <class Classify, class Query, class OpenLeaf, class BeforeQuery>
  void walk(FrameBackend& backend, std::vector<NodeState>& state, bool surfaces_only,
            Classify&& classify, Query&& query, OpenLeaf&& open_leaf, BeforeQuery&& before_query,
            FrameStats& stats);

  SceneBvh bvh_;
  std::vector<std::uint32_t> parent_;  // per node; the root's is itself
  std::size_t built_for_ = 0;          // objects the tree was built over
  std::int64_t frame_ = -1;
  std::vector<BvhBox> boxes_;
  std::vector<NodeState> eye_;                  // per node
  std::vector<std::vector<NodeState>> lights_;  // [light][node]
  std::vector<std::uint8_t> drawn_, kept_, opened_;
  std::vector<std::uint32_t> batch_;
  std::vector<glm::vec4> triangles_;
  struct Pending {
    std::uint32_t node;
    FrameBackend::QueryId query;
  };
  std::deque<Pending> queries_;
  using Entry = std::pair<float, std::uint32_t>;  // a node and its squared distance from the eye
  std::vector<Entry> nearest_;
};

}  // namespace shadowvol
