#include "render/frame_timing.h"

#include <chrono>

namespace shadowvol {

std::vector<FrameTiming> time_frames(std::span<const TimedRenderer> renderers, int frames,
                                     bool animate,
                                     const std::function<void(int done, int of)>& progress) {
  std::vector<FrameTiming> timings(renderers.size());
  std::vector<Frame> out(renderers.size());
  for (int round = -1; round < frames; ++round) {  // round -1: the warm-up
    if (progress) progress(round + 1, frames + 1);
    for (std::size_t r = 0; r < renderers.size(); ++r) {
      const TimedRenderer& timed = renderers[r];
      const Scene moved = animate ? scene_at_frame(timed.scene, round + 1) : Scene{};
      const auto start = std::chrono::steady_clock::now();
      timed.renderer.render(animate ? moved : timed.scene, timed.options, out[r]);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      if (round < 0) {
        timings[r].first_frame_ms = ms;
        continue;
      }
      timings[r].frame_ms += ms;
      timings[r].total += out[r].stats;
      timings[r].ms_per_frame.push_back(ms);
      timings[r].stats_per_frame.push_back(out[r].stats);
    }
  }
  for (FrameTiming& t : timings) {
    t.frames = frames;
    if (frames > 0) t.frame_ms /= frames;
  }
  return timings;
}

}  // namespace shadowvol
