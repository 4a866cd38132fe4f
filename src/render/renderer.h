// shadowvol render: Renderer, the frame pipeline, written once for every backend.
//
// Owns: the sequence of a frame and what it keeps between frames (the plan's storage, the CPU
// volume cache, the backend's measured volume costs). Per frame: the plan (render/frame_plan.h);
// the opaque layer's depth pass (front to back by hierarchical occlusion culling, where asked:
// render/occlusion_culling.h); CC shadow volumes' culling of casters whose volumes change no
// pixel and clamping of the rest to where receivers lie (render/cc_shadow_volumes.h); the
// volumes whose extruded boxes show nothing culled (occlusion_culling.h again); per light its
// volumes, the opaque casters' counts (the shadow mask), the transparent casters' light intensity
// map group by group, and the lit pass; with transparent casters, what is seen through them and the
// glass layer, lit the same way; the colour; read-back. Each step is a verb of a FrameBackend
// (render/frame_backend.h): the software rasterizer (soft/) or OpenGL (gl/); backend/backend.h
// makes one by name.
//
// Papers: Intel "mainstream shadow volumes" and GPU Gems 3 ch. 11 (the passes of a frame),
// Kim, Kim & Turk 2008 (transparent casters: the light map and the glass layer).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "render/cc_shadow_volumes.h"
#include "render/frame.h"
#include "render/frame_backend.h"
#include "render/frame_plan.h"
#include "render/occlusion_culling.h"
#include "render/volume_cache.h"
#include "scene/scene.h"

namespace shadowvol {

class Renderer {
 public:
  explicit Renderer(std::unique_ptr<FrameBackend> backend);

  // Renders one frame into `frame`, reusing its buffers where the size is that of its last
  // frame. The scene's lights must pass check_light and the options check_options (asserted).
  // Objects whose light, seen from the object, did not change since the last frame reuse their
  // volume.
  void render(const Scene& scene, const RenderOptions& options, Frame& frame);
  Frame render(const Scene& scene, const RenderOptions& options);
  // Renders one frame and shows it on the backend's device, with no read-back (frame holds its
  // stats). Needs backend().can_present().
  void present(const Scene& scene, const RenderOptions& options, Frame& frame);

  FrameBackend& backend() { return *backend_; }
  const FrameBackend& backend() const { return *backend_; }

 private:
  void draw(const Scene& scene, const RenderOptions& options, Frame& frame, bool read_back);
  // The update manager's builds of one frame (RenderOptions::overlap_volumes): on a worker
  // thread from the plan until the first count pass (or the colour) joins them.
  struct Builds;
  // Per light, the layer's shadows and light against the depth target as it stands; into `out`
  // where read_back. `builds`: the frame's, joined before the first count pass.
  void light_layer(const FrameInputs& in, std::size_t light, Layer layer, SurfaceLayer& out,
                   bool read_back, Builds& builds);

  std::unique_ptr<FrameBackend> backend_;
  FramePlan plan_;
  CcShadowVolumes cc_;
  OcclusionCulling occlusion_;
  std::vector<std::uint32_t> all_;      // a layer's objects, for a depth pass drawn whole
  std::vector<std::uint32_t> counted_;  // the volumes of one count_volumes
  VolumeCosts costs_;  // measured on the backend at the first frame that clamps continuously
  VolumeCache volumes_;
  std::vector<std::uint8_t> none_rebuilt_;  // for a backend that builds its own volumes
};

}  // namespace shadowvol
