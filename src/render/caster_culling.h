// shadowvol render: CasterCulling, CC shadow volumes' culling of casters (Lloyd, Wendt,
// Govindaraju and Manocha 2004, §3.1 and §3.4), for every backend alike.
//
// Owns: the potential shadow receivers (PSR) of a frame, and per light the potential shadow
// casters (PSC): the volumes of the others are marked culled in the plan, and the pipeline
// neither builds nor counts them.
//   - PSR, Cull::frustum: the objects whose bounding box meets the view frustum. Cull::occlusion:
//     the objects the opaque layer's ids show (the eye's depth test, at the precision the image
//     has: a receiver seen at no pixel receives nowhere) and the transparent ones in the frustum
//     (the glass layer is drawn later).
//   - PSC: the light's views are fitted to the PSR boxes (accel/light_views.h). Cull::frustum: a
//     caster outside them is culled (its shadow misses every receiver). Cull::occlusion: the
//     opaque objects are drawn into the views' occluder depths, the visible samples (each
//     pixel's point, from its face's plane) and the transparent receivers into the receiver
//     depths, and each caster's box is tested: culled in shadow where every ray to it is blocked
//     first, unseen where no receiver lies behind it.
// Runs on the CPU in double whatever the backend, so both cull the same casters: the tests'
// conservative coverage (inner for occluders, outer for boxes and receivers) is what GPU
// rasterization cannot give without conservative-raster extensions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "accel/light_views.h"
#include "render/frame.h"
#include "render/frame_plan.h"
#include "scene/scene.h"

namespace shadowvol {

class CasterCulling {
 public:
  // Marks VolumePlan::culled under options.cull and counts the culled casters, queries and
  // light views into stats. `opaque`: the opaque layer's object and face per pixel, needed under
  // Cull::occlusion.
  void cull(const Scene& scene, const RenderOptions& options, FramePlan& plan,
            const SurfaceLayer* opaque, FrameStats& stats);

 private:
  void find_receivers(const Scene& scene, const RenderOptions& options, const FramePlan& plan,
                      const SurfaceLayer* opaque);
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
  // (object, face) of visible faces seen edge-on, whose plane gives no point: receivers whole.
  std::vector<std::pair<std::size_t, std::uint32_t>> edge_on_;
  std::vector<glm::dvec3> world_;  // every object's vertices, eye-relative
  std::vector<std::size_t> world_first_;
};

}  // namespace shadowvol
