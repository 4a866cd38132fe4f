// shadowvol render: timing frames of renderers, as `shadowvol bench` does and as anyone who
// compares renderers on a shared, noisy machine should: in rounds, each renderer one frame in
// turn, so that the machine's slow moments fall on all of them alike.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "render/frame.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace shadowvol {

// A renderer, the scene it draws and how.
struct TimedRenderer {
  Renderer& renderer;
  const Scene& scene;
  const RenderOptions& options;
};

struct FrameTiming {
  int frames = 0;
  double frame_ms = 0.0;             // mean wall time of a frame
  double first_frame_ms = 0.0;       // the warm-up round's frame: cold where the renderer is new
  FrameStats total;                  // the frames' stats added up
  std::vector<double> ms_per_frame;  // each timed frame's wall time
  std::vector<FrameStats> stats_per_frame;  // and its stats
};

// One round to warm up (volumes built, shaders compiled, buffers sized), then `frames` rounds,
// each renderer drawing its scene into a Frame of its own that every round reuses. `animate`:
// round k draws frame k of the scene's animation (scene_at_frame; the warm-up frame 0), made
// before the clock starts; else every round draws the scene as it stands. Per renderer, in
// order: its timing. `progress(done, of)` is called before each round.
std::vector<FrameTiming> time_frames(std::span<const TimedRenderer> renderers, int frames,
                                     bool animate = false,
                                     const std::function<void(int done, int of)>& progress = {});

}  // namespace shadowvol
