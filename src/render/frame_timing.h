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

// A renderer and the scene it draws.
struct TimedRenderer {
  Renderer& renderer;
  const Scene& scene;
};

struct FrameTiming {
  int frames = 0;
  double frame_ms = 0.0;  // mean wall time of a frame
  FrameStats total;       // the frames' stats added up
};

// One round to warm up (volumes built, shaders compiled, buffers sized), then `frames` rounds,
// each renderer drawing its scene with `options` into a Frame of its own that every round
// reuses. Per renderer, in order: its timing. `progress(done, of)` is called before each round.
std::vector<FrameTiming> time_frames(std::span<const TimedRenderer> renderers,
                                     const RenderOptions& options, int frames,
                                     const std::function<void(int done, int of)>& progress = {});

}  // namespace shadowvol
