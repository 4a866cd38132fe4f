// shadowvol render: CcShadowVolumes, CC shadow volumes' culling and clamping (Lloyd, Wendt,
// Govindaraju and Manocha 2004, §3.1 to §3.4), for every backend alike, exact.
//
// Owns: the potential shadow receivers (PSR) of a frame, the sub-objects of large objects, and
// per light the potential shadow casters (PSC) and where each one's volume is kept; it writes
// them into the plan (VolumePlan::culled, clamp, strips), and the pipeline builds and counts
// accordingly.
//   - Sub-objects (§3, §3.3; accel/sub_objects.h): a spatially large object (kLargeAcross) is
//     split by a k-D tree into cells (kCellsAcross), once per mesh and cell size; each leaf is
//     culled and clamped as an object of its own, and the edges between leaves are merged.
//   - PSR, Cull::frustum and Cull::none: the objects whose bounding box meets the view frustum.
//     Cull::occlusion: the objects the opaque layer's ids show (the eye's depth test, at the
//     precision the image has: a receiver seen at no pixel receives nowhere) and the transparent
//     ones in the frustum (the glass layer is drawn later).
//   - PSC: the light's views are fitted to the PSR boxes (accel/light_views.h). Cull::frustum: a
//     caster outside them is culled (its shadow misses every receiver). Cull::occlusion: the
//     opaque objects are drawn into the views' occluder depths, the visible samples (each
//     pixel's point, from its face's plane) and the transparent receivers into the receiver
//     depths, and each caster's box is tested: culled in shadow where every ray to it is blocked
//     first, unseen where no receiver lies behind it.
//   - Continuous clamping (§3.2.1; accel/continuous_clamping.h): per light view, every sub-object
//     that casts (kept, and wholly in the view its object falls in) gets the intervals of depth
//     that hold receivers' boxes; its volume is built as those segments.
//   - Discrete clamping (§3.2.2, conservative as §3.2.3 asks; accel/slices.h): the samples go
//     into the light views' layers by the strip of the image they lie in; a volume is drawn only
//     in the runs of strips where one of its kept sub-objects passes the culling's test over that
//     strip's receivers (without Cull::occlusion, over the receivers alone). The paper's query
//     draws the caster projected onto the slice's far plane, depth test GREATER; here its box,
//     fattened by a pixel, over-covers that projection in the conservative light views.
// Runs on the CPU in double whatever the backend, so both cull and clamp the same: the tests'
// conservative coverage (inner for occluders, outer for boxes and receivers) is what GPU
// rasterization cannot give without conservative-raster extensions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "accel/continuous_clamping.h"
#include "accel/light_views.h"
#include "accel/sub_objects.h"
#include "render/frame.h"
#include "render/frame_plan.h"
#include "scene/scene.h"

namespace shadowvol {

class CcShadowVolumes {
 public:
  // Sub-objects: an object longer than the scene's longest side / kLargeAcross is split into cells
  // of about the scene's longest side / kCellsAcross (a power of two), at most kMaxSubObjects.
  // Smaller objects stay whole: each sub-object's segments add caps, whose fill a small object's
  // shorter volumes do not repay (the robots' fill grows by a sixth when they are split).
  static constexpr double kLargeAcross = 8.0, kCellsAcross = 32.0;
  static constexpr std::size_t kMaxSubObjects = 256;
  // Continuous clamping widens every depth by this much of the view's depth range, so that a
  // receiver lies strictly inside its interval and a segment reaches well beyond its caster: at a
  // tenth of this, the short side quads where a caster's first segment ends left single pixels
  // miscounted by gl's z-fail (the exactness matrix's edge-on parts).
  static constexpr double kDepthMargin = 1e-2;
  // And by at least this much of the largest coordinate the segments are built and drawn from
  // (the meshes' own, their eye-relative boxes and translations, the light's): the float planes
  // and positions of a mesh whose coordinates lie far from the origin err by that much.
  static constexpr double kFloatSlack = 1e-6;

  // Whether a frame of these options needs the opaque layer's ids first: occlusion culling and
  // discrete clamping take the visible samples.
  static bool needs_ids(const RenderOptions& options) {
    return options.cull == Cull::occlusion || clamps_discrete(options.clamp);
  }
  // Culls (options.cull) and clamps (options.clamp) the plan's volumes, after the opaque layer's
  // depth pass, and counts what it did into stats (ms_cull, ms_clamp and the counters).
  // `opaque`: the opaque layer's object and face per pixel, where needs_ids. `costs`: v and r of
  // V > R (continuous clamping). `sub_objects`: whether the backend builds volumes the clamp can
  // split (CPU volumes); else objects are culled and clamped whole.
  void apply(const Scene& scene, const RenderOptions& options, FramePlan& plan,
             const SurfaceLayer* opaque, const VolumeCosts& costs, bool sub_objects,
             FrameStats& stats);

 private:
  struct Leaves {  // one object's sub-objects this frame, eye-relative
    std::size_t first = 0, count = 1;
    const SubObjects* split = nullptr;  // null: one leaf, the object
  };
  void split_objects(const Scene& scene, const FramePlan& plan, bool sub_objects);
  void find_receivers(const Scene& scene, const RenderOptions& options, const FramePlan& plan,
                      const SurfaceLayer* opaque);
  // Per light: the views and their depths, the culling of each leaf, the clamping.
  void cull_light(const Scene& scene, const RenderOptions& options, const FramePlan& plan,
                  std::size_t light, FrameStats& stats);
  void clamp_continuously(const RenderOptions& options, const FramePlan& plan, std::size_t light,
                          const VolumeCosts& costs, FrameStats& stats);
  void clamp_discretely(const RenderOptions& options, FramePlan& plan, std::size_t light,
                        FrameStats& stats);
  void write_plan(const RenderOptions& options, FramePlan& plan, std::size_t light,
                  FrameStats& stats);
  // The vertices of object o's topology (welded), eye-relative, in double (Cull::occlusion).
  const glm::dvec3* world(std::size_t o) const { return world_.data() + world_first_[o]; }
  // Face f of object o, eye-relative.
  std::array<glm::dvec3, 3> face(const Scene& scene, std::size_t o, std::uint32_t f) const;

  LightViews views_;
  std::vector<Box> boxes_;              // per object, eye-relative
  std::vector<std::uint8_t> receiver_;  // per object: in the PSR
  std::vector<Box> receiver_boxes_;
  std::vector<LightViews::Occluder> occluders_;
  std::vector<glm::dvec3> samples_;  // per pixel, the point it shows (find_receivers)
  std::vector<LayerRange> sample_strips_;
  // (object, face) of visible faces seen edge-on, whose plane gives no point: receivers whole.
  std::vector<std::pair<std::size_t, std::uint32_t>> edge_on_;
  std::vector<glm::dvec3> world_;  // every object's vertices, eye-relative
  std::vector<std::size_t> world_first_;

  // Sub-objects: per object its leaves; per leaf its boxes (eye-relative) and this light's verdict.
  struct Cached {
    const Topology* topology = nullptr;
    std::unique_ptr<SubObjects> split;
  };
  std::vector<Cached> split_cache_;  // per object
  std::vector<Leaves> leaves_;
  std::vector<Box> leaf_caster_, leaf_receiver_;
  std::vector<std::uint8_t> leaf_kept_;  // this light: cast (not culled)
  std::vector<std::size_t> leaf_object_;
  std::vector<std::size_t> leaf_faces_;  // the faces it casts
  // Continuous clamping: per light view, its sweep-and-prune state; per leaf its intervals.
  std::vector<std::vector<ContinuousClamping>> clampers_;  // [light][view]
  std::vector<ContinuousClamping::Item> items_;
  std::vector<std::uint32_t> item_offsets_;
  std::vector<Interval> item_intervals_;
  std::vector<std::uint32_t> leaf_offsets_;  // per leaf: its intervals this light, CSR
  std::vector<Interval> leaf_intervals_;
  std::vector<std::uint8_t> leaf_clamped_;  // per leaf: its intervals are its own (else whole)
  std::vector<std::size_t> object_view_;    // per object: the view it is clamped in
  std::vector<std::uint8_t> strips_;        // discrete: per strip, occupied
};

}  // namespace shadowvol
