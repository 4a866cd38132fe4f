// shadowvol app: `bench --versus`, shadowvol's frame against what a user would otherwise take
// for exact hard shadows on a CPU, on the same scene and size, in the same run (issue 22):
//
//   embree  Embree ray casting (trace/embree_baseline.h): primary and shadow rays in 8-wide
//           packets, its BVH built in the frame and kept from frame to frame; and the hybrid an
//           engine would write: shadowvol's depth pass, the visible points rebuilt from it, then
//           Embree's shadow rays from them, BVH built and kept.
//   gl      the OpenGL backend drawing the frame as a classic engine does (CPU volumes, z-fail,
//           8-bit stencil) on whatever EGL gives (llvmpipe on a CPU server), timed in turn with
//           shadowvol's frame.
//
// Animated (`--animate`), every timed frame is the next of the scene's animation, so that
// volumes and the BVH are rebuilt each frame: Embree's "kept" figures do not apply there.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "plot.h"
#include "render/frame_timing.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace shadowvol {

struct Baselines {
  bool embree = false, gl = false;
  bool any() const { return embree || gl; }
};
// "embree", "gl" or both, comma-separated.
Expected<Baselines> parse_baselines(const std::string& text);

// The gl backend set up as a classic engine draws shadow volumes, with the options it draws by
// (`options` with z-fail); its note (what EGL gave) in `note`.
struct ClassicGl {
  std::unique_ptr<Renderer> renderer;
  RenderOptions options;
  std::string note;
};
Expected<ClassicGl> classic_gl(const RenderOptions& options);

// What a bench row measured of shadowvol's frame, per frame.
struct MeasuredFrame {
  double frame_ms = 0, first_frame_ms = 0, depth_ms = 0, volumes_counts_ms = 0, shade_ms = 0;
};
MeasuredFrame measured(const FrameTiming& timing);

// The comparison of one scene: figures and ratios as JSON (`versus`) and as lines of text, and
// the baselines' times frame by frame (empty where not timed) for the plot.
struct Versus {
  nlohmann::json json = nlohmann::json::object();
  std::string text;
  std::vector<double> embree_built, embree_kept, hybrid_built, hybrid_kept, gl;
};

// The plot's panels of one scene (`bench --versus --plot`): shadowvol's frame against Embree's,
// its volumes and counts against the hybrid's shadow rays, and its frame against the classic gl
// frame, each frame by frame.
std::vector<PlotPanel> versus_panels(const std::string& scene, const FrameTiming& ours,
                                     const Versus& versus);

// Times Embree's frame and the hybrid's over `frames` frames after a warm-up (the scene's
// animation frames 1 .. frames where `animate`), the hybrid's depth pass by `renderer` (the
// renderer of `ours`), and adds them and their ratios to `versus`.
Expected<void> versus_embree(const Scene& scene, const RenderOptions& options, int frames,
                             bool animate, Renderer& renderer, const MeasuredFrame& ours,
                             Versus& versus);

// Adds the classic gl frame's figures and ratios (timed in turn with shadowvol's) to `versus`.
void versus_gl(const MeasuredFrame& ours, const FrameTiming& gl, const std::string& device,
               Versus& versus);

// The cold frame against the warm ones.
void versus_cold(const MeasuredFrame& ours, Versus& versus);

}  // namespace shadowvol
