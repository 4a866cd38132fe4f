// `bench --suite cc`: CC shadow volumes' measurement (Lloyd et al. 2004 §4, Fig. 7 to 9).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_suite.h"
#include "cli.h"
#include "plot.h"
#include "render/frame_json.h"
#include "scene/scene.h"

namespace shadowvol {
namespace {

struct CcMethod {
  const char* name;
  bool cull;  // the scene's culling (CcScene::cull), else none
  Clamp clamp;
  glm::vec3 color;  // in --plot
};
const CcMethod kCcMethods[] = {{"sv", false, Clamp::none, {0.45f, 0.45f, 0.45f}},
                               {"cull", true, Clamp::none, {0.85f, 0.33f, 0.10f}},
                               {"ccc", true, Clamp::continuous, {0.13f, 0.40f, 0.75f}},
                               {"ccd", true, Clamp::discrete, {0.55f, 0.30f, 0.65f}},
                               {"cc", true, Clamp::both, {0.10f, 0.60f, 0.25f}}};
constexpr std::size_t kSv = 0, kCc = 4, kCcd = 3;  // in kCcMethods

// The paper culls the corridor by the view frustum alone ("there is very little occlusion in the
// scene") and the robots by occlusion.
struct CcScene {
  std::string_view name;
  Cull cull;
};
constexpr CcScene kCcScenes[] = {{"corridor", Cull::frustum}, {"robots", Cull::occlusion}};

// The goals, on the corridor over its path, standard volumes over CC (cull and both clampings):
// the paper's best fill reduction, and its average speed-up of the shadow volumes.
constexpr double kGoalFill = 7.0, kGoalTime = 2.5;
// Fig. 9's sweep: discrete clamping with these many slices, on frames of the corridor's walk.
constexpr int kSweepSlices[] = {1, 2, 4, 8, 16, 32, 64};
constexpr int kSweepFrames = 8, kCorridorWalk = 48;  // frames: the walk is 48 long

// One scene and method, a value per frame.
struct CcSeries {
  std::vector<std::uint64_t> fill, stencil_writes, segments;
  std::vector<double> volumes_ms, cull_ms, clamp_ms, frame_ms;

  // The shadow-volume time is building and counting the volumes (the count passes); culling's
  // and clamping's own times are kept apart, as Fig. 8 shows them.
  void add(const FrameStats& s) {
    fill.push_back(s.fill);
    stencil_writes.push_back(s.stencil_writes);
    segments.push_back(s.volume_segments);
    volumes_ms.push_back(s.ms_volumes + s.ms_counts);
    cull_ms.push_back(s.ms_cull);
    clamp_ms.push_back(s.ms_clamp);
    frame_ms.push_back(s.ms_depth + s.ms_volumes + s.ms_counts + s.ms_shade + s.ms_readback +
                       s.ms_cull + s.ms_clamp);
  }
};

double mean(const std::vector<double>& v) { return v.empty() ? 0.0 : total(v) / v.size(); }

}  // namespace

int run_cc_suite(const CcSuiteOptions& options) {
  if (options.frames < 1) {
    std::cerr << "shadowvol: error: --frames: " << options.frames << " is not a positive count\n";
    return 1;
  }
  RenderOptions base{options.width, options.height, options.method};
  base.count_fill = true;
  base.slices = options.slices;
  base.light_view_size = options.light_view_size;
  auto make = [&] { return suite_renderer(options.backend, options.gl, base); };
  std::unique_ptr<Renderer> probe = make();
  if (!probe) return 1;
  const std::string backend(probe->backend().name());
  nlohmann::json json{{"suite", "cc"},
                      {"width", options.width},
                      {"height", options.height},
                      {"frames", options.frames},
                      {"slices", options.slices},
                      {"light_view_size", options.light_view_size},
                      {"backend", backend},
                      {"method", std::string(to_string(options.method))},
                      {"goal", {{"scene", "corridor"}, {"fill", kGoalFill}, {"time", kGoalTime}}},
                      {"scenes", nlohmann::json::array()}};
  std::string csv =
      "scene,method,frame,fill,stencil_writes,segments,volumes_ms,cull_ms,clamp_ms,frame_ms\n";
  Chart chart{"CC shadow volumes (Lloyd et al. 2004): per frame, " + std::to_string(options.width) +
                  "x" + std::to_string(options.height) + ", " + backend,
              "frame",
              3,
              {}};
  std::FILE* table = options.json == "-" ? stderr : stdout;  // stdout may carry the JSON
  cli::StatusLine status;
  bool goal_met = false;
  double corridor_fill = 0, corridor_time = 0;
  std::fprintf(table, "%d frame%s a scene, %dx%d, %s, %s; ccd and cc with %d slice%s\n",
               options.frames, options.frames == 1 ? "" : "s", options.width, options.height,
               backend.c_str(), std::string(to_string(options.method)).c_str(), options.slices,
               options.slices == 1 ? "" : "s");
  std::fprintf(table, "%-9s %-5s %14s %14s %9s %11s %9s %9s %9s\n", "scene", "", "fill",
               "stencil wr.", "segments", "volumes ms", "cull ms", "clamp ms", "frame ms");
  for (const CcScene& cc_scene : kCcScenes) {
    const Scene scene = *builtin_scene(cc_scene.name);
    std::vector<std::unique_ptr<Renderer>> renderers;
    for (std::size_t m = 0; m < std::size(kCcMethods); ++m) {
      renderers.push_back(make());
      if (!renderers.back()) return 1;
    }
    std::vector<CcSeries> series(std::size(kCcMethods));
    for (int f = 0; f < options.frames; ++f) {
      status.show(scene.name + ": frame " + std::to_string(f + 1) + " of " +
                  std::to_string(options.frames));
      const Scene at = scene_at_frame(scene, f);
      for (std::size_t m = 0; m < std::size(kCcMethods); ++m) {
        RenderOptions o = base;
        o.cull = kCcMethods[m].cull ? cc_scene.cull : Cull::none;
        o.clamp = kCcMethods[m].clamp;
        series[m].add(renderers[m]->render(at, o).stats);
      }
    }
    status.clear();
    nlohmann::json scene_json{{"name", scene.name},
                              {"cull", std::string(to_string(cc_scene.cull))},
                              {"methods", nlohmann::json::object()}};
    const CcSeries& sv = series[kSv];
    for (std::size_t m = 0; m < std::size(kCcMethods); ++m) {
      const char* name = kCcMethods[m].name;
      const CcSeries& s = series[m];
      for (std::size_t f = 0; f < s.fill.size(); ++f)
        csv += scene.name + "," + name + "," + std::to_string(f) + "," + std::to_string(s.fill[f]) +
               "," + std::to_string(s.stencil_writes[f]) + "," + std::to_string(s.segments[f]) +
               "," + std::to_string(s.volumes_ms[f]) + "," + std::to_string(s.cull_ms[f]) + "," +
               std::to_string(s.clamp_ms[f]) + "," + std::to_string(s.frame_ms[f]) + "\n";
      const double fill_ratio =
          double(total(sv.fill)) / double(std::max<std::uint64_t>(total(s.fill), 1));
      const double time_ratio = total(sv.volumes_ms) / std::max(total(s.volumes_ms), 1e-9);
      scene_json["methods"][name] = {
          {"fill", total(s.fill)},
          {"stencil_writes", total(s.stencil_writes)},
          {"segments", total(s.segments)},
          {"ms_volumes_drawn", total(s.volumes_ms)},
          {"ms_cull", total(s.cull_ms)},
          {"ms_clamp", total(s.clamp_ms)},
          {"ms_frame", total(s.frame_ms)},
          {"sv_over_this", {{"fill", fill_ratio}, {"ms_volumes_drawn", time_ratio}}},
          {"per_frame",
           {{"fill", s.fill},
            {"stencil_writes", s.stencil_writes},
            {"segments", s.segments},
            {"ms_volumes_drawn", s.volumes_ms},
            {"ms_cull", s.cull_ms},
            {"ms_clamp", s.clamp_ms},
            {"ms_frame", s.frame_ms}}}};
      std::fprintf(table, "%-9s %-5s %14llu %14llu %9llu %11.1f %9.1f %9.1f %9.1f",
                   scene.name.c_str(), name, static_cast<unsigned long long>(total(s.fill)),
                   static_cast<unsigned long long>(total(s.stencil_writes)),
                   static_cast<unsigned long long>(total(s.segments)), total(s.volumes_ms),
                   total(s.cull_ms), total(s.clamp_ms), total(s.frame_ms));
      if (m == kSv)
        std::fprintf(table, "\n");
      else
        std::fprintf(table, "   sv / %s: fill %.2fx, volumes %.2fx\n", name, fill_ratio,
                     time_ratio);
      if (scene.name == "corridor" && m == kCc) {
        corridor_fill = fill_ratio;
        corridor_time = time_ratio;
      }
    }
    const char* titles[] = {"fill", "stencil writes", "shadow-volume ms"};
    for (int c = 0; c < 3; ++c) {
      PlotPanel panel{scene.name + ": " + titles[c], {}, {}};
      for (std::size_t m = 0; m < std::size(kCcMethods); ++m) {
        const CcSeries& s = series[m];
        const std::vector<double> values =
            c == 0   ? std::vector<double>(s.fill.begin(), s.fill.end())
            : c == 1 ? std::vector<double>(s.stencil_writes.begin(), s.stencil_writes.end())
                     : s.volumes_ms;
        panel.series.push_back({kCcMethods[m].name, kCcMethods[m].color, values});
      }
      chart.panels.push_back(std::move(panel));
    }
    json["scenes"].push_back(scene_json);
  }
  goal_met = corridor_fill >= kGoalFill && corridor_time >= kGoalTime;
  std::fprintf(table,
               "goal (corridor over its path, sv / cc): fill >= %.1fx: %.2fx, shadow-volume time "
               ">= %.1fx: %.2fx: %s\n",
               kGoalFill, corridor_fill, kGoalTime, corridor_time, goal_met ? "met" : "NOT MET");
  json["goal_met"] = goal_met;

  // Fig. 9: what discrete clamping saves against standard volumes, by the number of slices, on
  // frames spread over the corridor's walk: the volumes' time of sv less the clamping's and the
  // volumes' time of ccd.
  const Scene corridor = *builtin_scene("corridor");
  std::vector<Scene> sweep_frames;  // no more than the suite's own frames
  const int sweep_count = std::min(kSweepFrames, options.frames);
  for (int k = 0; k < sweep_count; ++k)
    sweep_frames.push_back(scene_at_frame(corridor, k * kCorridorWalk / sweep_count));
  std::unique_ptr<Renderer> sv_renderer = make();
  if (!sv_renderer) return 1;
  CcSeries sv_sweep;
  for (const Scene& at : sweep_frames) sv_sweep.add(sv_renderer->render(at, base).stats);
  nlohmann::json sweep = nlohmann::json::array();
  PlotPanel sweep_panel{"corridor, slice sweep: ms a frame", {}, "slices", {}};
  for (const int slices : kSweepSlices) sweep_panel.x_ticks.push_back(std::to_string(slices));
  std::vector<double> sv_ms, ccd_ms;
  std::fprintf(table, "slice sweep (corridor, %d frames over its walk, ccd against sv):\n",
               sweep_count);
  for (const int slices : kSweepSlices) {
    status.show("slice sweep: " + std::to_string(slices) + " slices");
    std::unique_ptr<Renderer> renderer = make();
    if (!renderer) return 1;
    RenderOptions o = base;
    o.cull = Cull::frustum;
    o.clamp = Clamp::discrete;
    o.slices = slices;
    CcSeries s;
    for (const Scene& at : sweep_frames) s.add(renderer->render(at, o).stats);
    const double ms_saved = mean(sv_sweep.volumes_ms) - mean(s.clamp_ms) - mean(s.volumes_ms);
    sv_ms.push_back(mean(sv_sweep.volumes_ms));
    ccd_ms.push_back(mean(s.clamp_ms) + mean(s.volumes_ms));
    sweep.push_back({{"slices", slices},
                     {"ms_saved", ms_saved},
                     {"ms_clamp", mean(s.clamp_ms)},
                     {"ms_volumes_drawn", mean(s.volumes_ms)},
                     {"fill", double(total(s.fill)) / sweep_count}});
    std::fprintf(table,
                 "  %2d slices: clamping %7.1f ms + volumes %7.1f ms against sv's %7.1f ms: "
                 "%+7.1f ms saved a frame; fill %.0f (sv %.0f)\n",
                 slices, mean(s.clamp_ms), mean(s.volumes_ms), mean(sv_sweep.volumes_ms), ms_saved,
                 double(total(s.fill)) / sweep_count, double(total(sv_sweep.fill)) / sweep_count);
  }
  status.clear();
  sweep_panel.series.push_back({"sv: volumes", kCcMethods[kSv].color, sv_ms});
  sweep_panel.series.push_back({"ccd: clamping + volumes", kCcMethods[kCcd].color, ccd_ms});
  chart.panels.push_back(std::move(sweep_panel));
  json["slice_sweep"] = sweep;

  return write_suite_outputs(options.json, json.dump(2) + "\n", options.csv, csv, options.plot,
                             chart, "the counters per frame, and the slice sweep", table)
             ? 0
             : 1;
}

}  // namespace shadowvol
