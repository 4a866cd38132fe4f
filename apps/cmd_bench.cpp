// shadowvol bench: frame times of scenes on a backend (the library's timing harness,
// render/frame_timing.h), or a measurement suite (bench_suite.h).
#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_suite.h"
#include "bench_versus.h"
#include "cli.h"
#include "output_file.h"
#include "image_file.h"
#include "plot.h"
#include "render/frame_json.h"
#include "render/frame_timing.h"
#include "scene/city.h"
#include "scene/stage.h"

namespace shadowvol::cli {
namespace {

struct BenchArgs {
  FrameArgs frame{"demo", "auto", "auto", "1920x1080"};
  std::vector<std::string> scenes;
  int frames = 10;
  std::string json_file, suite, csv, plot;
  std::vector<int> city_sizes;
  std::vector<std::string> stages;  // --stage: timed instead of the scenes
  std::string versus;               // --versus: embree, gl or both
  bool animate = false;             // --animate: step the scenes' animation frame by frame
  bool serial_baseline = false;     // --serial-baseline: also time with the volumes built after
  bool volume_paths = false;        // --volume-paths: also time gl's other volume paths
  CLI::App* cmd = nullptr;
  CLI::Option* json = nullptr;
  bool given(const char* option) const { return cmd->get_option(option)->count() > 0; }
};

// The scene with every caster made opaque: what transparency costs is measured against it.
Scene all_opaque(Scene scene) {
  for (SceneObject& object : scene.objects) object.material.opacity = 1.0f;
  return scene;
}

// Frame times of scenes on one backend: the mean over `frames` frames after one warm-up frame
// (which builds volumes and compiles shaders), per stage. A scene with transparent casters is
// also drawn all opaque, frame for frame in turn, for the ratio of their frame times.
int bench(const BenchArgs& args) {
  if (args.frames < 1)
    return fail("--frames: " + std::to_string(args.frames) + " is not a positive count");
  Baselines baselines;
  if (!args.versus.empty()) {
    auto parsed = parse_baselines(args.versus);
    if (!parsed) return fail("--versus: " + parsed.error().message);
    baselines = *parsed;
  }
  if (!args.plot.empty() && !baselines.any())
    return fail("--plot needs --suite spsv, cc, city or lights, or --versus");
  nlohmann::json out = nlohmann::json::array();
  Chart chart;  // --plot: the comparisons' panels
  const bool json = args.json->count() > 0;
  StatusLine status;
  const bool stages = !args.stages.empty();
  for (const std::string& name : stages ? args.stages : args.scenes) {
    FrameArgs frame = args.frame;
    frame.scene = name;
    std::optional<Scene> stage;
    if (stages) {
      auto made = load_stage(name);
      if (!made) return fail(made.error().message);
      stage = std::move(*made);
    }
    auto resolved = resolve(frame, std::move(stage));
    if (!resolved) return fail(resolved.error().message);
    const RenderOptions& options = resolved->options;
    // New renderers per scene, so that each scene's first frame is a cold one. The opaque twin
    // draws the scene with every caster opaque; the classic gl frame is a baseline.
    auto renderer = make_frame_renderer(*resolved, options);
    if (!renderer) return fail(renderer.error().message);
    const bool glass = has_transparent_casters(resolved->scene);
    const Scene opaque = all_opaque(resolved->scene);
    std::vector<TimedRenderer> timed{{**renderer, resolved->scene, options}};
    std::unique_ptr<Renderer> opaque_renderer;
    if (glass) {
      auto made = make_frame_renderer(*resolved, options);
      if (!made) return fail(made.error().message);
      opaque_renderer = std::move(*made);
      timed.push_back({*opaque_renderer, opaque, options});
    }
    // The update manager's baseline: the same frames with the volumes built after the depth pass.
    RenderOptions serial = options;
    serial.overlap_volumes = false;
    std::unique_ptr<Renderer> serial_renderer;
    std::size_t serial_at = 0;
    if (args.serial_baseline) {
      auto made = make_frame_renderer(*resolved, serial);
      if (!made) return fail(made.error().message);
      serial_renderer = std::move(*made);
      serial_at = timed.size();
      timed.push_back({*serial_renderer, resolved->scene, serial});
    }
    // gl's other two volume paths (CPU, geometry shader, vertex shader), frame for frame in turn.
    std::vector<std::pair<gl::VolumePath, std::unique_ptr<Renderer>>> paths;
    std::size_t paths_at = timed.size();
    if (args.volume_paths) {
      if (resolved->backend != Backend::gl)
        return fail("--volume-paths compares the gl backend's volume paths: give --backend gl");
      for (const gl::VolumePath path :
           {gl::VolumePath::cpu, gl::VolumePath::gpu, gl::VolumePath::vertex}) {
        if (path == resolved->gl.volumes) continue;
        ResolvedFrame other = *resolved;
        other.gl.volumes = path;
        auto made = make_frame_renderer(other, options);
        if (!made) return fail(made.error().message);
        paths.emplace_back(path, std::move(*made));
      }
      for (auto& [path, r] : paths) timed.push_back({*r, resolved->scene, options});
    }
    std::optional<ClassicGl> classic;
    if (baselines.gl) {
      auto made = classic_gl(options);
      if (!made) return fail("--versus gl: " + made.error().message);
      classic = std::move(*made);
      timed.push_back({*classic->renderer, resolved->scene, classic->options});
    }
    const std::vector<FrameTiming> t =
        time_frames(timed, args.frames, args.animate, [&](int done, int of) {
          status.show(resolved->scene.name + ": frame " + std::to_string(done + 1) + " of " +
                      std::to_string(of));
        });
    status.clear();
    const FrameStats& sum = t[0].total;
    const double n = args.frames;
    const std::string backend((*renderer)->backend().name());
    nlohmann::json row = to_json(options);
    row.update({{"scene", resolved->scene.name},
                {"backend", backend},
                {"volumes", frame.volumes},
                {"frames", args.frames},
                {"animated", args.animate},
                {"frame_ms", t[0].frame_ms},
                {"first_frame_ms", t[0].first_frame_ms},
                {"depth_ms", sum.ms_depth / n},
                {"volumes_ms", sum.ms_volumes / n},
                {"counts_ms", sum.ms_counts / n},
                {"shade_ms", sum.ms_shade / n},
                {"readback_ms", sum.ms_readback / n},
                {"volume_primitives", sum.volume_primitives / args.frames},
                {"volumes_built", double(sum.volumes_built) / n}});
    row.update(cc_json(sum, args.frames, false));  // fill: bench --suite cc
    row.update(nlohmann::json::object({occlusion_json(sum, args.frames)}));
    for (std::size_t k = 0; k < paths.size(); ++k) {
      const FrameTiming& other = t[paths_at + k];
      row["volume_paths"][std::string(gl::to_string(paths[k].first))] = {
          {"frame_ms", other.frame_ms},
          {"volumes_ms", other.total.ms_volumes / n},
          {"counts_ms", other.total.ms_counts / n},
          {"ratio", t[0].frame_ms / other.frame_ms}};
    }
    row["volume_builds_ms"] = sum.ms_volume_builds / n;
    row["volumes_hidden_ms"] = sum.ms_volumes_hidden / n;
    if (serial_renderer) {
      row["serial_frame_ms"] = t[serial_at].frame_ms;
      row["serial_volumes_ms"] = t[serial_at].total.ms_volumes / n;
      row["overlapped_over_serial"] = t[0].frame_ms / t[serial_at].frame_ms;
    }
    if (glass) {
      row["all_opaque_frame_ms"] = t[1].frame_ms;
      row["transparent_over_opaque"] = t[0].frame_ms / t[1].frame_ms;
    }
    if ((*renderer)->backend().counts_work()) {  // the rasterizer's work, per frame
      row["count_pass"] = to_json(sum.counts, args.frames);
      row["split_sampling"] = to_json(sum.split_sampling, args.frames);
    }
    Versus versus;  // printed under the frame's line
    if (baselines.any()) {
      const MeasuredFrame ours = measured(t[0]);
      versus_cold(ours, versus);
      if (classic) versus_gl(ours, t.back(), classic->note, versus);
      if (baselines.embree) {
        status.show(resolved->scene.name + ": timing the baselines");
        auto ok = versus_embree(resolved->scene, options, args.frames, args.animate, **renderer,
                                ours, versus);
        status.clear();
        if (!ok) return fail(ok.error().message);
      }
      row["versus"] = versus.json;
      for (PlotPanel& panel : versus_panels(resolved->scene.name, t[0], versus))
        chart.panels.push_back(std::move(panel));
      chart.title = "shadowvol (" + backend + ") against its baselines, " +
                    std::to_string(options.width) + "x" + std::to_string(options.height) + ", " +
                    std::to_string(args.frames) + (args.animate ? " animated" : "") + " frames";
      chart.x_label = "frame";
      chart.columns = classic ? 3 : 2;
    }
    if (json) {
      out.push_back(row);
      continue;
    }
    std::printf(
        "%-16s %s %dx%d%s: %7.2f ms a frame (depth %.2f, volumes %.2f, counts %.2f, shade %.2f, "
        "read-back %.2f)\n",
        resolved->scene.name.c_str(), backend.c_str(), options.width, options.height,
        args.animate ? " animated" : "", t[0].frame_ms, sum.ms_depth / n, sum.ms_volumes / n,
        sum.ms_counts / n, sum.ms_shade / n, sum.ms_readback / n);
    if (glass)
      std::printf("%-16s %s %dx%d: %7.2f ms a frame all opaque: transparency costs %.2fx\n", "",
                  backend.c_str(), options.width, options.height, t[1].frame_ms,
                  t[0].frame_ms / t[1].frame_ms);
    for (std::size_t k = 0; k < paths.size(); ++k) {
      const FrameTiming& other = t[paths_at + k];
      std::printf(
          "%-16s gl %dx%d --volumes %s: %7.2f ms a frame (volumes %.2f, counts %.2f): "
          "--volumes %s's frame is %.2fx\n",
          "", options.width, options.height, std::string(gl::to_string(paths[k].first)).c_str(),
          other.frame_ms, other.total.ms_volumes / n, other.total.ms_counts / n,
          frame.volumes.c_str(), t[0].frame_ms / other.frame_ms);
    }
    if (serial_renderer)
      std::printf(
          "%-16s %s %dx%d: volume builds %.2f ms, %.2f of them beside the depth pass; built "
          "after it instead: %.2f ms a frame (volumes %.2f): the overlap's frame is %.2fx\n",
          "", backend.c_str(), options.width, options.height, sum.ms_volume_builds / n,
          sum.ms_volumes_hidden / n, t[serial_at].frame_ms, t[serial_at].total.ms_volumes / n,
          t[0].frame_ms / t[serial_at].frame_ms);
    std::printf("%s", versus.text.c_str());
  }
  if (json) std::cout << out.dump(2) << "\n";
  if (!args.plot.empty()) {
    if (auto ok = write_chart(args.plot, chart); !ok) return fail(ok.error().message);
    std::fprintf(json ? stderr : stdout, "wrote %s (the frames against the baselines)\n",
                 args.plot.c_str());
  }
  return 0;
}

// A suite's image size: --size where given, else the suite's own.
Expected<void> suite_size(const BenchArgs& args, int& width, int& height) {
  if (args.given("--size")) {
    auto size = parse_size(args.frame.size);
    if (!size) return size.error();
    width = size->first, height = size->second;
  }
  if (auto ok = check_options({width, height}); !ok)
    return make_error("--size: " + ok.error().message);
  return {};
}

// A suite sets the rest of the frame's options itself: one given that it does not take is an
// error, not silently ignored. Every suite takes these; `taken` names its others.
Expected<void> refuse_options_not_taken(const BenchArgs& args,
                                        std::initializer_list<std::string_view> taken) {
  constexpr std::string_view kEverySuite[] = {"--suite", "--frames", "--size",
                                              "--json",  "--csv",    "--plot"};
  auto among = [](std::span<const std::string_view> names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  for (const CLI::Option* option : args.cmd->get_options()) {
    const std::string name = option->get_name();
    if (option->count() == 0 || among(kEverySuite, name) ||
        among({taken.begin(), taken.size()}, name))
      continue;
    return make_error(name + ": --suite " + args.suite +
                      " does not take it (the suite sets its own)");
  }
  return {};
}

// A timed suite's outputs, frames, size, method and backend, as given, else the suite's own.
template <class Suite>
Expected<void> take_suite_options(const BenchArgs& args, Suite& suite) {
  suite.json = args.json_file;
  suite.csv = args.csv;
  suite.plot = args.plot;
  if (args.json->count() > 0 && args.json_file.empty()) suite.json = "-";
  if (args.given("--frames")) suite.frames = args.frames;
  if (auto ok = suite_size(args, suite.width, suite.height); !ok) return ok;
  auto method = parse_method(args.frame.method);
  if (!method) return make_error("--method: " + method.error().message);
  suite.method = *method;
  auto backend = parse_backend(args.frame.backend);
  if (!backend) return make_error("--backend: " + backend.error().message);
  suite.backend = *backend;
  auto volumes = gl::parse_volume_path(args.frame.volumes);
  if (!volumes) return make_error("--volumes: " + volumes.error().message);
  auto counts = gl::parse_count_target(args.frame.counts);
  if (!counts) return make_error("--counts: " + counts.error().message);
  suite.gl = {*volumes, *counts};
  return {};
}

// `bench --suite cc`: the size, method, frames, backend, slices and light views' side as given,
// else the suite's own.
int cc_suite(const BenchArgs& args) {
  if (auto ok = refuse_options_not_taken(
          args, {"--method", "--backend", "--volumes", "--counts", "--slices", "--light-view"});
      !ok)
    return fail(ok.error().message);
  CcSuiteOptions suite;
  if (auto ok = take_suite_options(args, suite); !ok) return fail(ok.error().message);
  if (auto ok = check_slices(args.frame.slices); !ok)
    return fail("--slices: " + ok.error().message);
  suite.slices = args.frame.slices;
  if (auto ok = check_light_view_size(args.frame.light_view); !ok)
    return fail("--light-view: " + ok.error().message);
  suite.light_view_size = args.frame.light_view;
  return run_cc_suite(suite);
}

// `bench --suite city`: the size, method, frames and backend as given, else the suite's own.
int city_suite(const BenchArgs& args) {
  if (auto ok = refuse_options_not_taken(
          args, {"--method", "--backend", "--volumes", "--counts", "--city-sizes"});
      !ok)
    return fail(ok.error().message);
  CitySuiteOptions suite;
  if (auto ok = take_suite_options(args, suite); !ok) return fail(ok.error().message);
  if (!args.city_sizes.empty()) {
    if (args.city_sizes.size() < 2) return fail("--city-sizes: give at least two sizes");
    for (const int b : args.city_sizes)
      if (b < 1 || b > kMaxCityBuildings)
        return fail("--city-sizes: " + std::to_string(b) + " is outside 1 .. " +
                    std::to_string(kMaxCityBuildings));
    if (!std::is_sorted(args.city_sizes.begin(), args.city_sizes.end()))
      return fail("--city-sizes: give the sizes smallest first");
    suite.sizes = args.city_sizes;
  }
  return run_city_suite(suite);
}

// `bench --suite lights`: the size, method, frames and backend as given, else the suite's own.
int lights_suite(const BenchArgs& args) {
  if (auto ok = refuse_options_not_taken(args, {"--method", "--backend", "--volumes", "--counts"});
      !ok)
    return fail(ok.error().message);
  if (!args.csv.empty()) return fail("--suite lights writes a table, --json and --plot, no --csv");
  LightsSuiteOptions suite;
  if (auto ok = take_suite_options(args, suite); !ok) return fail(ok.error().message);
  return run_lights_suite(suite);
}

int suite(const BenchArgs& args) {
  if (args.suite.empty())
    return fail(args.csv.empty() ? "--plot needs --suite spsv, cc, city or lights, or --versus"
                                 : "--csv needs --suite spsv, cc or city");
  if (args.suite == "cc") return cc_suite(args);
  if (args.suite == "city") return city_suite(args);
  if (args.suite == "lights") return lights_suite(args);
  if (args.suite != "spsv")
    return fail("--suite: unknown suite '" + args.suite + "': expected spsv, cc, city or lights");
  if (auto ok = refuse_options_not_taken(args, {"--extrusion"}); !ok)
    return fail(ok.error().message);
  SuiteOptions suite{args.frames, 1024, 768, args.json_file, args.csv, args.plot};
  if (args.json->count() > 0 && args.json_file.empty()) suite.json = "-";
  if (auto ok = suite_size(args, suite.width, suite.height); !ok) return fail(ok.error().message);
  if (args.given("--extrusion")) {
    auto extrusion = parse_extrusion(args.frame.extrusion);
    if (!extrusion) return fail("--extrusion: " + extrusion.error().message);
    suite.extrusion = *extrusion;
  }
  return run_spsv_suite(suite);
}

int run(const BenchArgs& args) {
  std::vector<std::string> inputs = args.scenes;
  inputs.insert(inputs.end(), args.stages.begin(), args.stages.end());
  if (auto ok = check_outputs({args.json_file, args.csv, args.plot}, inputs); !ok)
    return fail(ok.error().message);
  if (args.given("--city-sizes") && args.suite != "city")
    return fail("--city-sizes needs --suite city");
  if (!args.suite.empty() || !args.csv.empty() || (!args.plot.empty() && args.versus.empty()))
    return suite(args);
  if (!args.json_file.empty())
    return fail("--json " + args.json_file + ": a file is for --suite; without it --json prints");
  return bench(args);
}

}  // namespace

void add_bench_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<BenchArgs>();
  for (std::string_view n : builtin_scene_names()) args->scenes.emplace_back(n);
  CLI::App* cmd = app.add_subcommand(
      "bench", "Time frames of scenes on a backend: the mean per stage over --frames frames");
  args->cmd = cmd;
  add_frame_options(cmd, args->frame);
  cmd->remove_option(cmd->get_option("--scene"));
  cmd->add_option("--scenes", args->scenes, "Scenes to time (names, .json files or meshes)")
      ->capture_default_str();
  cmd->add_option("--stage", args->stages,
                  "Time these meshes on the benchmark stage instead of --scenes: a mesh file, "
                  "sphere:N (a UV sphere of 2 N^2 triangles) or cad (a CAD-like assembly of "
                  "about 150,000 triangles); the stage: docs/performance.md");
  cmd->add_option("--versus", args->versus,
                  "Also time baselines on the same scene and size, in the same run, and print the "
                  "ratios against issue 22's goals: embree (ray casting: primary and shadow rays "
                  "in 8-wide packets over every thread, its BVH built in the frame and kept; and "
                  "the hybrid: our depth pass, then Embree's shadow rays), gl (the classic frame "
                  "on the gl backend: CPU volumes, z-fail, stencil), or embree,gl");
  cmd->add_flag("--volume-paths", args->volume_paths,
                "With --backend gl: also time each scene with gl's other volume paths (cpu, gpu: "
                "the geometry shader, vs: the vertex shader), frame for frame in turn");
  cmd->add_flag("--serial-baseline", args->serial_baseline,
                "Also time each scene with its CPU volumes built after the depth pass (not beside "
                "it, by the update manager), frame for frame in turn, and print the ratio");
  cmd->add_flag("--animate", args->animate,
                "Draw the scenes' animation frame by frame (the stage's mesh slides), so that "
                "volumes and Embree's BVH are rebuilt every frame");
  cmd->add_option("--frames", args->frames, "Frames to time per scene, after one warm-up")
      ->capture_default_str();
  args->json = cmd->add_option("--json", args->json_file,
                               "Print one JSON array (with --suite: write the suite's JSON to "
                               "this file, - for standard output)")
                   ->expected(0, 1);
  cmd->add_option(
      "--suite", args->suite,
      "Run a measurement suite instead: spsv (Laine 2005's counters over the animated "
      "knight, knights16, tree and tree-decomposed, with zp+db, zf+db, spsv, "
      "spsv-laine and spsv-whole; 1024x768 unless --size) or cc (CC shadow volumes' "
      "fill, stencil writes and shadow-volume time over the corridor's and the "
      "robots' paths, with sv, cull, ccc, ccd and cc, and the slice sweep; "
      "1280x1024 and 48 frames unless --size and --frames; --method, --backend) or city "
      "(occlusion culling on the city of 1,000 to 10,000 buildings, street and above, "
      "none and --occlusion both: fill, frame and shadow-volume time, objects and "
      "volumes drawn, the scaling; 1280x720 and 8 frames unless --size, --frames, "
      "--city-sizes; --method, --backend) or lights (the night street's frame time against its "
      "1 to 48 lamps, each of limited range, beside the same with the ranges lifted; 1920x1080 "
      "and 5 frames unless --size, --frames; --method, --backend)");
  cmd->add_option("--city-sizes", args->city_sizes,
                  "With --suite city: the city sizes in buildings, smallest first (default "
                  "1000 2500 5000 10000)");
  cmd->add_option("--csv", args->csv,
                  "With --suite: write one row per scene, method and frame to this file");
  cmd->add_option("--plot", args->plot,
                  "With --suite: draw every counter's per-frame series, per scene and method, to "
                  "this PNG (or SVG, where the name ends in .svg); with --versus: each scene's "
                  "frames against the baselines'");
  cmd->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace shadowvol::cli
