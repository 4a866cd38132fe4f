// `bench --suite lights`: frame time against the number of lights, on the night street (scene/
// night_street.h), each lamp a point light of limited range; beside it, frame for frame in turn,
// the same street with every range lifted, where each light's passes cover the whole image and
// every caster casts for every light.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_suite.h"
#include "cli.h"
#include "plot.h"
#include "render/frame_timing.h"
#include "scene/night_street.h"

namespace shadowvol {

int run_lights_suite(const LightsSuiteOptions& options) {
  if (options.frames < 1) {
    std::cerr << "shadowvol: error: --frames: " << options.frames << " is not a positive count\n";
    return 1;
  }
  const RenderOptions frame_options{options.width, options.height, options.method};
  auto make = [&] { return suite_renderer(options.backend, options.gl, frame_options); };
  std::unique_ptr<Renderer> probe = make();
  if (!probe) return 1;
  const std::string backend(probe->backend().name());
  probe.reset();
  const bool to_stdout = options.json == "-";
  std::FILE* table = to_stdout ? stderr : stdout;
  std::fprintf(table,
               "night-street, %s, %dx%d, %d frames after a warm-up; each lamp a point light of "
               "range 8, beside the same street with the ranges lifted\n",
               backend.c_str(), options.width, options.height, options.frames);
  std::fprintf(table, "%6s %8s %10s %10s %10s %9s %10s %12s %10s %8s\n", "lamps", "objects",
               "ms/frame", "ms/light", "counts ms", "shade ms", "unlimited", "ranged/unl.",
               "beyond", "scissor");
  nlohmann::json rows = nlohmann::json::array();
  // --plot: the frame, and the frame per light, with the ranges and with them lifted.
  const glm::vec3 kRanged{0.10f, 0.60f, 0.25f}, kUnlimited{0.45f, 0.45f, 0.45f};
  PlotPanel frame_panel{
      "ms a frame", {{"ranges", kRanged, {}}, {"ranges lifted", kUnlimited, {}}}, ""};
  PlotPanel light_panel{
      "ms a frame per light", {{"ranges", kRanged, {}}, {"ranges lifted", kUnlimited, {}}}, ""};
  std::vector<std::string> lamp_counts;  // the x axis's labels
  cli::StatusLine status;
  for (const int lamps : options.lamps) {
    const Scene ranged = make_night_street(lamps);
    Scene unlimited = ranged;
    for (SceneLight& light : unlimited.lights) light.range = kUnlimitedRange;
    std::unique_ptr<Renderer> a = make(), b = make();
    if (!a || !b) return 1;
    const std::vector<TimedRenderer> timed{{*a, ranged, frame_options},
                                           {*b, unlimited, frame_options}};
    const std::vector<FrameTiming> t =
        time_frames(timed, options.frames, false, [&](int done, int of) {
          status.show(ranged.name + ": frame " + std::to_string(done + 1) + " of " +
                      std::to_string(of));
        });
    status.clear();
    const double n = options.frames;
    const FrameStats& s = t[0].total;
    const double pixels = double(options.width) * options.height * double(lamps);
    const double beyond = s.volumes_out_of_range / n;
    const double scissor_share = s.scissor_pixels_saved / n / pixels;
    std::fprintf(table, "%6d %8zu %10.2f %10.3f %10.2f %9.2f %10.2f %12.2f %10.0f %7.0f%%\n", lamps,
                 ranged.objects.size(), t[0].frame_ms, t[0].frame_ms / lamps, s.ms_counts / n,
                 s.ms_shade / n, t[1].frame_ms, t[0].frame_ms / t[1].frame_ms, beyond,
                 100.0 * scissor_share);
    frame_panel.series[0].values.push_back(t[0].frame_ms);
    frame_panel.series[1].values.push_back(t[1].frame_ms);
    light_panel.series[0].values.push_back(t[0].frame_ms / lamps);
    light_panel.series[1].values.push_back(t[1].frame_ms / lamps);
    lamp_counts.push_back(std::to_string(lamps));
    rows.push_back({{"lamps", lamps},
                    {"objects", ranged.objects.size()},
                    {"frame_ms", t[0].frame_ms},
                    {"ms_per_light", t[0].frame_ms / lamps},
                    {"depth_ms", s.ms_depth / n},
                    {"volumes_ms", s.ms_volumes / n},
                    {"counts_ms", s.ms_counts / n},
                    {"shade_ms", s.ms_shade / n},
                    {"readback_ms", s.ms_readback / n},
                    {"unlimited_frame_ms", t[1].frame_ms},
                    {"unlimited_counts_ms", t[1].total.ms_counts / n},
                    {"ranged_over_unlimited", t[0].frame_ms / t[1].frame_ms},
                    {"volumes_out_of_range", beyond},
                    {"volumes_drawn", s.volumes_drawn / n},
                    {"unlimited_volumes_drawn", t[1].total.volumes_drawn / n},
                    {"scissor_pixels_saved_share", scissor_share}});
  }
  std::fprintf(table,
               "  beyond: volumes of casters beyond a lamp's range, not built or drawn, a frame; "
               "scissor: the share of the lights' pixels outside their scissors\n");
  Chart chart;
  chart.title = "night-street, " + backend + ", " + std::to_string(options.width) + "x" +
                std::to_string(options.height) + ": frame time against the lamps";
  chart.x_label = "lamps";
  chart.columns = 2;
  frame_panel.x_ticks = light_panel.x_ticks = lamp_counts;
  chart.panels = {frame_panel, light_panel};
  const nlohmann::json json{{"suite", "lights"},
                            {"scene", "night-street"},
                            {"backend", backend},
                            {"width", options.width},
                            {"height", options.height},
                            {"frames", options.frames},
                            {"rows", rows}};
  if (!write_suite_outputs(options.json, options.json.empty() ? "" : json.dump(2) + "\n", "", "",
                           options.plot, chart, "the frame time against the lamps", table))
    return 1;
  return 0;
}

}  // namespace shadowvol
