// The shadowvol command line. Thin by design: parses arguments, calls the library, prints.
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "bench_suite.h"
#include "core/topology.h"
#include "core/volume.h"
#include "backend/backend.h"
#include "gl/context.h"
#include "image_file.h"
#include "render/heatmap.h"
#include "render/light_map.h"
#include "render/renderer.h"
#include "scene/mesh_io.h"
#include "scene/scene.h"
#include "scene/scene_io.h"
#include "trace/reference.h"
#include "verify/verify.h"
#include "view.h"

#ifndef SHADOWVOL_VERSION
#error "SHADOWVOL_VERSION is set by CMake"
#endif

namespace {

using namespace shadowvol;

int fail(const std::string& message) {
  std::cerr << "shadowvol: error: " << message << "\n";
  return 1;
}

nlohmann::json report_json(const std::string& file, const TopologyReport& r) {
  return {
      {"file", file},
      {"input_vertices", r.input_vertices},
      {"vertices", r.vertices},
      {"triangles", r.triangles},
      {"edges", r.edges},
      {"boundary_edges", r.boundary_edges},
      {"nonmanifold_edges", r.nonmanifold_edges},
      {"inconsistent_edges", r.inconsistent_edges},
      {"degenerate_triangles", r.degenerate_triangles},
      {"components", r.components},
      {"closed_manifold", r.closed_manifold},
      {"generator", std::string(to_string(resolve_generator(Generator::automatic, r)))},
  };
}

void print_report(const std::string& file, const TopologyReport& r) {
  auto row = [](const char* name, const std::string& value) {
    std::printf("  %-22s %s\n", name, value.c_str());
  };
  std::printf("%s\n", file.c_str());
  row("vertices", std::to_string(r.vertices) + " welded from " + std::to_string(r.input_vertices));
  row("triangles", std::to_string(r.triangles));
  row("edges", std::to_string(r.edges));
  row("boundary edges", std::to_string(r.boundary_edges));
  row("non-manifold edges", std::to_string(r.nonmanifold_edges));
  row("inconsistent edges", std::to_string(r.inconsistent_edges));
  row("degenerate triangles", std::to_string(r.degenerate_triangles));
  row("components", std::to_string(r.components));
  row("closed 2-manifold", r.closed_manifold ? "yes" : "no");
  const Generator g = resolve_generator(Generator::automatic, r);
  row("generator (auto)",
      std::string(to_string(g)) +
          (r.closed_manifold ? " (silhouette edges, weight 1)" : " (signed edge multiplicities)"));
}

// One status line on stderr, redrawn in place, only when stderr is a terminal: a person waiting
// on a large file sees it move; pipes and logs get nothing.
class StatusLine {
 public:
  StatusLine() : enabled_(isatty(STDERR_FILENO) == 1) {}
  ~StatusLine() { clear(); }
  void show(const std::string& text) {
    if (enabled_) std::cerr << "\r\033[K" << text << std::flush;
  }
  void clear() { show(""); }

 private:
  bool enabled_;
};

// "x,y,z,w" -> a homogeneous light, or an error naming what is wrong.
Expected<glm::vec4> parse_light(const std::string& text) {
  glm::vec4 light(0.0f);
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 4; ++i) {
    if (i > 0 && (p == end || *p++ != ','))
      return make_error("--light: '" + text + "' is not four numbers x,y,z,w");
    const auto [next, ec] = std::from_chars(p, end, light[i]);
    if (ec != std::errc()) return make_error("--light: '" + text + "' is not four numbers x,y,z,w");
    p = next;
  }
  if (p != end) return make_error("--light: '" + text + "' has more than four numbers");
  if (auto ok = check_light(light); !ok) return make_error("--light: " + ok.error().message);
  return light;
}

// What each generator makes of the mesh under one light.
struct VolumeStats {
  Generator generator;
  std::size_t side_quads = 0;
  std::int64_t unit_quads = 0;  // sum of |weight|: the draws a +-1 stencil backend needs
  int max_weight = 0;
  std::size_t light_caps = 0, dark_caps = 0;
};

std::vector<VolumeStats> volume_stats(const Topology& topo, const glm::vec4& light) {
  std::vector<VolumeStats> out;
  VolumeScratch scratch;
  VolumeBuffer volume;
  for (Generator g : {Generator::standard, Generator::robust, Generator::multiplicity}) {
    if (!check_generator(g, topo.report, "").ok()) continue;
    build_volume(topo, light, {g, true}, scratch, volume);
    VolumeStats s{g};
    s.side_quads = volume.sides.size();
    for (std::int32_t w : volume.sides.weights) {
      s.unit_quads += std::abs(w);
      s.max_weight = std::max(s.max_weight, std::abs(w));
    }
    s.light_caps = volume.light_caps.size();
    s.dark_caps = volume.dark_caps.size();
    out.push_back(s);
  }
  return out;
}

int inspect(const std::string& file, bool json, float weld_epsilon,
            const std::optional<glm::vec4>& light) {
  StatusLine status;
  status.show("reading " + file);
  auto loaded = load_mesh(file, [&](float fraction) {
    status.show("reading " + file + " " + std::to_string(static_cast<int>(fraction * 100)) + "%");
  });
  status.clear();
  if (!loaded) return fail(loaded.error().message);
  for (const std::string& w : loaded->warnings) std::cerr << "shadowvol: warning: " << w << "\n";
  status.show("building the topology of " + std::to_string(loaded->mesh.triangle_count()) +
              " triangles");
  const Topology topo = build_topology(loaded->mesh, WeldOptions{weld_epsilon});
  status.clear();
  std::vector<VolumeStats> volumes;
  if (light) volumes = volume_stats(topo, *light);
  if (json) {
    nlohmann::json out = report_json(file, topo.report);
    if (light) {
      out["light"] = {light->x, light->y, light->z, light->w};
      for (const VolumeStats& v : volumes)
        out["volumes"][std::string(to_string(v.generator))] = {{"side_quads", v.side_quads},
                                                               {"unit_weight_quads", v.unit_quads},
                                                               {"max_weight", v.max_weight},
                                                               {"light_caps", v.light_caps},
                                                               {"dark_caps", v.dark_caps}};
    }
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  print_report(file, topo.report);
  if (light) {
    std::printf("\nvolumes under the %s light (%g, %g, %g, %g)\n",
                light->w == 0.0f ? "directional" : "point", light->x, light->y, light->z, light->w);
    std::printf("  %-13s %11s %17s %11s %11s %10s\n", "generator", "side quads", "as +-1 quads",
                "max |w|", "light caps", "dark caps");
    for (const VolumeStats& v : volumes)
      std::printf("  %-13s %11zu %17lld %11d %11zu %10zu\n",
                  std::string(to_string(v.generator)).c_str(), v.side_quads,
                  static_cast<long long>(v.unit_quads), v.max_weight, v.light_caps, v.dark_caps);
  }
  return 0;
}

// A built-in scene by name, or a mesh file on a default stage.
Expected<Scene> load_scene(const std::string& name) {
  auto builtin = builtin_scene(name);
  if (builtin) return builtin;
  std::error_code ec;
  if (!std::filesystem::exists(name, ec)) return builtin.error();  // lists the built-in names
  if (std::filesystem::path(name).extension() == ".json") return load_scene_file(name);
  auto loaded = load_mesh(name);
  if (!loaded) return loaded.error();
  for (const std::string& w : loaded->warnings) std::cerr << "shadowvol: warning: " << w << "\n";
  return default_stage(std::filesystem::path(name).filename().string(), std::move(loaded->mesh));
}

Expected<std::pair<int, int>> parse_size(const std::string& text) {
  int w = 0, h = 0;
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, w);
  if (ec == std::errc() && p != end && (*p == 'x' || *p == 'X')) {
    auto [q, ec2] = std::from_chars(p + 1, end, h);
    if (ec2 == std::errc() && q == end) return std::pair{w, h};
  }
  return make_error("--size: '" + text + "' is not WIDTHxHEIGHT, e.g. 1280x720");
}

// What render and verify both take: a scene and how to draw it.
struct FrameArgs {
  std::string scene = "demo";
  std::string method = "auto";
  std::string generator = "auto";
  std::string size;
  std::string backend = "soft";
  std::string volumes = "cpu";
  std::string counts = "auto";
  std::string extrusion = "infinite";
  std::string split_planes = "sampled";
  std::string split_parts = "each";
};

// `with_backend`: false for the viewer, which is OpenGL by nature.
void add_frame_options(CLI::App* cmd, FrameArgs& args, const std::string& scene_list,
                       bool with_backend = true) {
  cmd->add_option("--scene", args.scene,
                  "A built-in scene (" + scene_list + "), a scene file (.json) or a mesh file")
      ->capture_default_str();
  cmd->add_option("--method", args.method,
                  "zpass, zfail, auto (per object); soft backend only: spsv (per tile, by a split "
                  "plane) or zp+db (z-pass with the ZP+ near-plane pre-fill)")
      ->capture_default_str();
  cmd->add_option("--generator", args.generator, "standard, robust, multiplicity or auto")
      ->capture_default_str();
  cmd->add_option("--extrusion", args.extrusion,
                  "infinite (volumes to w = 0) or bounded (ended on a plane just beyond the "
                  "scene, closed by dark caps: less to rasterize)")
      ->capture_default_str();
  cmd->add_option("--split-planes", args.split_planes,
                  "spsv: laine (Laine 2005's Point-Camera-Light / Point-Point-Light, flat for "
                  "flat objects) or sampled (that plane and 39 others, the cheapest on a sample "
                  "of each volume's tiles)")
      ->capture_default_str();
  cmd->add_option("--split-parts", args.split_parts,
                  "spsv: each (a split plane for each connected part of a caster, up to " +
                      std::to_string(kMaxSplitParts) +
                      " parts, as Laine 2005 sec. 6 decomposes casters) or whole (one plane per "
                      "object)")
      ->capture_default_str();
  cmd->add_option("--size", args.size, "Image size WIDTHxHEIGHT")->capture_default_str();
  if (with_backend)
    cmd->add_option("--backend", args.backend,
                    "soft (CPU rasterizer), gl (OpenGL 4.5, headless) or auto (gl if a context "
                    "can be made, else soft)")
        ->capture_default_str();
  cmd->add_option("--volumes", args.volumes,
                  "gl: volumes built on the cpu (any generator) or in a geometry shader on the gpu "
                  "(standard or robust)")
      ->capture_default_str();
  cmd->add_option("--counts", args.counts,
                  "gl: count volumes in the stencil buffer (weights other than +-1 drawn "
                  "|weight| times), an additive R32F target, or auto (stencil where all weights "
                  "are +-1)")
      ->capture_default_str();
}

struct ResolvedFrame {
  Scene scene;
  RenderOptions options;
  Backend backend;
  gl::GlSettings gl;
};

// The method as the command line reports it, "(Laine's planes)" after spsv where they are not
// sampled, "(one plane per object)" where parts do not get their own, "(bounded)" where volumes
// are.
std::string method_label(const RenderOptions& options) {
  const bool split = options.method == Method::split_plane;
  const bool laine = split && options.split_planes == SplitPlanes::laine;
  const bool whole = split && options.split_parts == SplitParts::whole;
  return std::string(to_string(options.method)) + (laine ? " (Laine's planes)" : "") +
         (whole ? " (one plane per object)" : "") +
         (options.extrusion == Extrusion::bounded ? " (bounded)" : "");
}

// Takes the soft backend for something only it draws (`reason` says what and why): an error
// under --backend gl, a note under auto.
Expected<void> take_soft_backend(Backend& backend, const std::string& reason) {
  if (backend == Backend::gl) return make_error(reason + "; use --backend soft");
  if (backend == Backend::automatic)
    std::cerr << "shadowvol: backend auto: soft, since " << reason << "\n";
  backend = Backend::soft;
  return {};
}

// The scene and the options, every value checked, or the first problem as a message.
Expected<ResolvedFrame> resolve(const FrameArgs& args) {
  auto scene = load_scene(args.scene);
  if (!scene) return scene.error();
  for (const SceneLight& l : scene->lights)
    if (auto ok = check_light(l.position); !ok)
      return make_error("scene " + scene->name + ": " + ok.error().message);
  auto method = parse_method(args.method);
  if (!method) return make_error("--method: " + method.error().message);
  auto generator = parse_generator(args.generator);
  if (!generator) return make_error("--generator: " + generator.error().message);
  if (*generator == Generator::standard && has_transparent_casters(*scene))
    return make_error(
        "--generator standard counts only the surfaces that face the light, but scene " +
        scene->name +
        " has transparent casters, whose every surface filters the light: use robust, "
        "multiplicity or auto");
  auto size = parse_size(args.size);
  if (!size) return size.error();
  auto extrusion = parse_extrusion(args.extrusion);
  if (!extrusion) return make_error("--extrusion: " + extrusion.error().message);
  auto split_planes = parse_split_planes(args.split_planes);
  if (!split_planes) return make_error("--split-planes: " + split_planes.error().message);
  auto split_parts = parse_split_parts(args.split_parts);
  if (!split_parts) return make_error("--split-parts: " + split_parts.error().message);
  RenderOptions options{size->first, size->second, *method, *generator, *extrusion};
  options.split_planes = *split_planes;
  options.split_parts = *split_parts;
  if (auto ok = check_options(options); !ok) return make_error("--size: " + ok.error().message);
  auto backend = parse_backend(args.backend);
  if (!backend) return make_error("--backend: " + backend.error().message);
  if (soft_only(*method))
    if (auto ok = take_soft_backend(
            *backend, "--method " + std::string(to_string(*method)) +
                          " runs in the soft backend only (the split test and the ZP+ pre-fill "
                          "are built in the software rasterizer)");
        !ok)
      return ok.error();
  auto volumes = gl::parse_volume_path(args.volumes);
  if (!volumes) return make_error("--volumes: " + volumes.error().message);
  auto counts = gl::parse_count_target(args.counts);
  if (!counts) return make_error("--counts: " + counts.error().message);
  const gl::GlSettings gl{*volumes, *counts};
  if (auto ok = gl::check_settings(gl, *generator); !ok) return make_error(ok.error().message);
  return ResolvedFrame{std::move(*scene), options, *backend, gl};
}

// The renderer the arguments ask for; says on stderr which one `auto` took.
Expected<std::unique_ptr<Renderer>> make_frame_renderer(const ResolvedFrame& frame) {
  auto made = make_renderer(frame.backend, frame.gl);
  if (!made) return made.error();
  if (!made->note.empty()) std::cerr << "shadowvol: " << made->note << "\n";
  return std::move(made->renderer);
}

struct RenderArgs {
  FrameArgs frame{"demo", "auto", "auto", "960x540"};
  std::string out = "shadowvol.png";
  bool stats = false;
  bool show_volumes = false;
  int frames = 1;
  std::string heatmap;    // PNG of the count passes' work per tile; soft backend
  std::string light_map;  // PNG of the light that reaches each surface
};

int render(const RenderArgs& args) {
  auto resolved = resolve(args.frame);
  if (!resolved) return fail(resolved.error().message);
  const Scene& scene = resolved->scene;
  RenderOptions options = resolved->options;
  options.show_volumes = args.show_volumes;
  options.tile_work = !args.heatmap.empty();
  if (options.tile_work)
    if (auto ok =
            take_soft_backend(resolved->backend, "--heatmap maps the software rasterizer's tiles");
        !ok)
      return fail(ok.error().message);
  if (args.frames < 1)
    return fail("--frames: " + std::to_string(args.frames) + " is not a positive count");

  auto renderer = make_frame_renderer(*resolved);
  if (!renderer) return fail(renderer.error().message);
  Frame frame;
  StatusLine status;
  for (int i = 0; i < args.frames; ++i) {
    if (args.frames > 1)
      status.show("frame " + std::to_string(i + 1) + " of " + std::to_string(args.frames));
    (*renderer)->render(scene_at_frame(scene, i), options, frame);
  }
  status.clear();
  const Image& img = frame.image;
  if (auto ok = write_png(args.out, img); !ok) return fail(ok.error().message);
  std::cout << "wrote " << args.out << " (" << scene.name << ", " << img.width << "x" << img.height
            << ", " << method_label(options) << ", " << (*renderer)->backend_name() << ")\n";
  if (options.tile_work) {
    const Heatmap map = tile_work_heatmap(frame);
    if (auto ok = write_png(args.heatmap, map.image); !ok) return fail(ok.error().message);
    std::printf(
        "wrote %s (pixels processed | pixels updated per tile; brightest: %.1f passes "
        "per pixel)\n",
        args.heatmap.c_str(), map.passes_at_top);
  }
  if (!args.light_map.empty()) {
    if (auto ok = write_png(args.light_map,
                            light_map_image(scene_at_frame(scene, args.frames - 1), frame));
        !ok)
      return fail(ok.error().message);
    std::printf("wrote %s (the light that reaches each surface, all lights at full = white)\n",
                args.light_map.c_str());
  }
  if (args.stats) {
    const FrameStats& s = frame.stats;
    std::printf(
        "  depth %.1f ms, volumes %.1f ms, counts %.1f ms, shade %.1f ms, read-back %.1f ms\n",
        s.ms_depth, s.ms_volumes, s.ms_counts, s.ms_shade, s.ms_readback);
    std::printf(
        "  %zu triangles, %zu volume primitives, objects by z-pass %d, by z-fail %d, by a split "
        "plane %d, volumes built %d, reused %d\n",
        s.triangles, s.volume_primitives, s.objects_zpass, s.objects_zfail, s.objects_split,
        s.volumes_built, s.volumes_reused);
    if ((*renderer)->backend_name() == "soft")
      std::printf(
          "  count pass: %llu triangles in, %llu clipped, %llu tiles touched, %llu skipped by hi-z "
          "or depth bounds,"
          " %llu pixels processed, %llu count updates\n",
          (unsigned long long)s.counts.triangles_in, (unsigned long long)s.counts.triangles_clipped,
          (unsigned long long)s.counts.tiles_touched, (unsigned long long)s.counts.tiles_skipped,
          (unsigned long long)s.counts.pixels_processed,
          (unsigned long long)s.counts.count_updates);
    if (s.split_sampling.triangles_in > 0)
      std::printf(
          "  split-plane sampling: %llu triangles in, %llu tiles touched, %llu skipped, %llu "
          "samples processed, %llu counted\n",
          (unsigned long long)s.split_sampling.triangles_in,
          (unsigned long long)s.split_sampling.tiles_touched,
          (unsigned long long)s.split_sampling.tiles_skipped,
          (unsigned long long)s.split_sampling.pixels_processed,
          (unsigned long long)s.split_sampling.count_updates);
  }
  return 0;
}

struct VerifyArgs {
  FrameArgs frame{"demo", "auto", "auto", "480x270"};
  std::string diff;
  bool json = false;
  int frame_number = 0;
};

int verify(const VerifyArgs& args) {
  auto resolved = resolve(args.frame);
  if (!resolved) return fail(resolved.error().message);
  const RenderOptions& options = resolved->options;
  if (args.frame_number < 0)
    return fail("--frame: " + std::to_string(args.frame_number) + " is not a frame number");
  const Scene scene = scene_at_frame(resolved->scene, args.frame_number);
  auto renderer = make_frame_renderer(*resolved);
  if (!renderer) return fail(renderer.error().message);
  const std::string backend((*renderer)->backend_name());
  const Frame frame = (*renderer)->render(scene, options);
  auto reference = trace_reference(scene, options.width, options.height);
  if (!reference) return fail(reference.error().message);
  const Comparison c = compare(frame, *reference);
  const bool glass = has_transparent_casters(scene);
  if (c.pixels_compared == 0)  // a comparison of nothing proves nothing
    return fail(
        "nothing to compare: no visible surface faces a light (check the camera and the "
        "lights of " +
        scene.name + ")");
  if (!args.diff.empty())
    if (auto ok = write_png(args.diff, diff_image(frame, c)); !ok) return fail(ok.error().message);
  if (args.json) {
    std::cout << nlohmann::json{{"scene", scene.name},
                                {"method", std::string(to_string(options.method))},
                                {"generator", std::string(to_string(options.generator))},
                                {"extrusion", std::string(to_string(options.extrusion))},
                                {"split_planes", std::string(to_string(options.split_planes))},
                                {"split_parts", std::string(to_string(options.split_parts))},
                                {"backend", backend},
                                {"frame", args.frame_number},
                                {"width", options.width},
                                {"height", options.height},
                                {"pixels_compared", c.pixels_compared},
                                {"mismatched", c.mismatched},
                                {"mismatched_outside_band", c.mismatched_outside_band},
                                {"transparent_casters", glass},
                                {"max_light_error", c.max_light_error},
                                {"max_light_error_outside_band", c.max_light_error_outside_band}}
                     .dump(2)
              << "\n";
  } else {
    char light[160] = "";
    if (glass)
      std::snprintf(light, sizeof light,
                    "; light through transparent casters off by at most %.2g outside the band "
                    "(%.2g allowed; %.2g within it)",
                    c.max_light_error_outside_band, kLightTolerance, c.max_light_error);
    std::printf(
        "%s, %s, %s backend, %dx%d: %zu pixels compared, %zu mismatched, %zu outside the "
        "one-pixel band%s: %s\n",
        scene.name.c_str(), method_label(options).c_str(), backend.c_str(), options.width,
        options.height, c.pixels_compared, c.mismatched, c.mismatched_outside_band, light,
        c.mismatched_outside_band == 0 ? "matches the reference" : "DIFFERS from the reference");
  }
  return c.mismatched_outside_band == 0 ? 0 : 1;
}

int view(const FrameArgs& frame, int frames, const std::string& screenshot) {
  if (auto method = parse_method(frame.method); method && soft_only(*method))
    return fail("--method " + frame.method +
                " runs in the soft backend only; the viewer draws with OpenGL");
  auto resolved = resolve(frame);
  if (!resolved) return fail(resolved.error().message);
  if (frames < 0) return fail("--frames: " + std::to_string(frames) + " is not a count");
  return run_viewer(
      {std::move(resolved->scene), resolved->options, resolved->gl, frames, screenshot});
}

// The scene with every caster made opaque: what transparency costs is measured against it.
Scene all_opaque(Scene scene) {
  for (SceneObject& object : scene.objects) object.material.opacity = 1.0f;
  return scene;
}

// Frame times of scenes on one backend: the mean over `frames` frames after one warm-up frame
// (which builds volumes and compiles shaders), per stage. A scene with transparent casters is
// also drawn all opaque, frame for frame in turn, for the ratio of their frame times.
int bench(const FrameArgs& frame, const std::vector<std::string>& scenes, int frames, bool json) {
  if (frames < 1) return fail("--frames: " + std::to_string(frames) + " is not a positive count");
  std::unique_ptr<Renderer> renderer, opaque_renderer;
  nlohmann::json out = nlohmann::json::array();
  StatusLine status;
  for (const std::string& name : scenes) {
    FrameArgs args = frame;
    args.scene = name;
    auto resolved = resolve(args);
    if (!resolved) return fail(resolved.error().message);
    if (!renderer) {
      auto made = make_frame_renderer(*resolved);
      if (!made) return fail(made.error().message);
      renderer = std::move(*made);
    }
    const RenderOptions& options = resolved->options;
    // The opaque twin on a renderer of its own, so that each keeps its volumes warm.
    const bool glass = has_transparent_casters(resolved->scene);
    const Scene opaque = all_opaque(resolved->scene);
    if (glass && !opaque_renderer) {
      auto made = make_renderer(resolved->backend, resolved->gl);
      if (!made) return fail(made.error().message);
      opaque_renderer = std::move(made->renderer);
    }
    auto timed = [&](Renderer& r, const Scene& scene, double& wall) {
      const auto start = std::chrono::steady_clock::now();
      Frame f = r.render(scene, options);
      wall += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                  .count();
      return f;
    };
    FrameStats sum;
    double wall = 0.0, opaque_wall = 0.0;
    for (int i = -1; i < frames; ++i) {
      status.show(resolved->scene.name + ": frame " + std::to_string(i + 2) + " of " +
                  std::to_string(frames + 1));
      if (i < 0) {  // warm-up
        double ignored = 0.0;
        timed(*renderer, resolved->scene, ignored);
        if (glass) timed(*opaque_renderer, opaque, ignored);
        continue;
      }
      const Frame f = timed(*renderer, resolved->scene, wall);
      if (glass) timed(*opaque_renderer, opaque, opaque_wall);
      sum.ms_depth += f.stats.ms_depth;
      sum.ms_volumes += f.stats.ms_volumes;
      sum.ms_counts += f.stats.ms_counts;
      sum.ms_shade += f.stats.ms_shade;
      sum.ms_readback += f.stats.ms_readback;
      sum.volume_primitives += f.stats.volume_primitives;
      sum.counts += f.stats.counts;
      sum.split_sampling += f.stats.split_sampling;
    }
    status.clear();
    const double n = frames;
    nlohmann::json row{{"scene", resolved->scene.name},
                       {"backend", std::string(renderer->backend_name())},
                       {"width", options.width},
                       {"height", options.height},
                       {"method", std::string(to_string(options.method))},
                       {"extrusion", std::string(to_string(options.extrusion))},
                       {"split_planes", std::string(to_string(options.split_planes))},
                       {"split_parts", std::string(to_string(options.split_parts))},
                       {"volumes", args.volumes},
                       {"frames", frames},
                       {"frame_ms", wall / n},
                       {"depth_ms", sum.ms_depth / n},
                       {"volumes_ms", sum.ms_volumes / n},
                       {"counts_ms", sum.ms_counts / n},
                       {"shade_ms", sum.ms_shade / n},
                       {"readback_ms", sum.ms_readback / n},
                       {"volume_primitives", sum.volume_primitives / frames}};
    if (glass) {
      row["all_opaque_frame_ms"] = opaque_wall / n;
      row["transparent_over_opaque"] = wall / opaque_wall;
    }
    if (renderer->backend_name() == "soft") {  // the rasterizer's work, per frame (gl has no counters)
      const auto per_frame = [frames](const raster::Counters& c) {
        return nlohmann::json{{"triangles", c.triangles_in / frames},
                              {"tiles_touched", c.tiles_touched / frames},
                              {"tiles_skipped", c.tiles_skipped / frames},
                              {"pixels_processed", c.pixels_processed / frames},
                              {"count_updates", c.count_updates / frames}};
      };
      row["count_pass"] = per_frame(sum.counts);
      row["split_sampling"] = per_frame(sum.split_sampling);
    }
    if (json) {
      out.push_back(row);
    } else {
      std::printf(
          "%-16s %s %dx%d: %7.2f ms a frame (depth %.2f, volumes %.2f, counts %.2f, shade %.2f, "
          "read-back %.2f)\n",
          resolved->scene.name.c_str(), std::string(renderer->backend_name()).c_str(), options.width,
          options.height, wall / n, sum.ms_depth / n, sum.ms_volumes / n, sum.ms_counts / n,
          sum.ms_shade / n, sum.ms_readback / n);
      if (glass)
        std::printf("%-16s %s %dx%d: %7.2f ms a frame all opaque: transparency costs %.2fx\n", "",
                    std::string(renderer->backend_name()).c_str(), options.width, options.height,
                    opaque_wall / n, wall / opaque_wall);
    }
  }
  if (json) std::cout << out.dump(2) << "\n";
  return 0;
}

int info(bool json) {
  auto context = gl::Context::create_headless();
  if (!context) return fail("cannot create an OpenGL context: " + context.error().message);
  const gl::Info i = context->info();
  const gl::Features& f = i.features;
  const std::pair<const char*, bool> features[] = {{"depth_clamp", f.depth_clamp},
                                                   {"two_sided_stencil", f.two_sided_stencil},
                                                   {"stencil_wrap", f.stencil_wrap},
                                                   {"geometry_shaders", f.geometry_shaders},
                                                   {"occlusion_queries", f.occlusion_queries},
                                                   {"depth_bounds", f.depth_bounds},
                                                   {"integer_targets", f.integer_targets},
                                                   {"clip_control", f.clip_control}};
  if (json) {
    nlohmann::json out{{"vendor", i.vendor},
                       {"renderer", i.renderer},
                       {"version", i.version},
                       {"fallbacks", f.fallbacks}};
    for (const auto& [name, has] : features) out["features"][name] = has;
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("OpenGL   %s\nrenderer %s\nvendor   %s\n", i.version.c_str(), i.renderer.c_str(),
              i.vendor.c_str());
  for (const auto& [name, has] : features) std::printf("  %-18s %s\n", name, has ? "yes" : "no");
  for (const std::string& line : f.fallbacks) std::printf("fallback: %s\n", line.c_str());
  return 0;
}

}  // namespace

// A frame's per-pixel buffers are allocated afresh each frame. glibc hands blocks this large
// back to the kernel when they are freed, and every page of the next frame's then faults in
// again: on this project's VMs that was half of a 1080p frame of `glass` (495 ms against 165)
// and most of the depth pass. The tool keeps freed memory in its heap instead.
namespace {
void keep_freed_frames_in_the_heap() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest: blocks below it come from the heap
  mallopt(M_TRIM_THRESHOLD, 1 << 30);   // and are not returned to the kernel on free
#endif
}
}  // namespace

int main(int argc, char** argv) {
  keep_freed_frames_in_the_heap();
  CLI::App app{"shadowvol: exact stencil shadow volumes for any mesh, on the GPU and the CPU"};
  app.set_version_flag("--version", std::string("shadowvol ") + SHADOWVOL_VERSION);
  app.require_subcommand(1);

  std::string file;
  bool json = false;
  float weld = 0.0f;
  CLI::App* inspect_cmd = app.add_subcommand(
      "inspect", "Print the topology report of a mesh file and the generator auto picks for it");
  inspect_cmd->add_option("FILE", file, "Mesh file (any format assimp reads: OBJ, PLY, glTF, ...)")
      ->required();
  inspect_cmd->add_flag("--json", json, "Print one JSON object instead of a table");
  inspect_cmd->add_option("--weld", weld,
                          "Weld vertices closer than this distance (default 0: exact positions)");
  std::string light_text;
  inspect_cmd->add_option("--light", light_text,
                          "Also build the shadow volumes for this light, x,y,z,w in the mesh's "
                          "space (w = 1 point light, w = 0 directional), and count what each "
                          "generator makes");

  RenderArgs render_args;
  std::string scene_list;
  for (std::string_view n : builtin_scene_names())
    scene_list += (scene_list.empty() ? "" : ", ") + std::string(n);
  CLI::App* render_cmd = app.add_subcommand("render", "Render a scene with exact shadows to a PNG");
  add_frame_options(render_cmd, render_args.frame, scene_list);
  render_cmd->add_option("--out", render_args.out, "PNG file to write")->capture_default_str();
  render_cmd->add_flag("--stats", render_args.stats, "Print the frame's timings and counters");
  render_cmd->add_flag("--show-volumes", render_args.show_volumes,
                       "Draw the shadow volumes' edges over the image (one colour per light)");
  render_cmd->add_option("--heatmap", render_args.heatmap,
                         "Also write a PNG of the count passes' work per 8x8 tile: pixels "
                         "processed and pixels updated, over the scene (soft backend)");
  render_cmd->add_option("--light-map", render_args.light_map,
                         "Also write a PNG of the light intensity map: the light that reaches "
                         "each surface through the casters (coloured where they are transparent)");
  render_cmd
      ->add_option("--frames", render_args.frames,
                   "Render frames 0 .. N-1 of the scene's animation; write the last")
      ->capture_default_str();

  VerifyArgs verify_args;
  CLI::App* verify_cmd = app.add_subcommand(
      "verify", "Render a scene and compare its shadows per pixel with the ray-traced reference");
  add_frame_options(verify_cmd, verify_args.frame, scene_list);
  verify_cmd->add_option("--diff", verify_args.diff,
                         "Write the mismatches over the scene to this PNG");
  verify_cmd->add_flag("--json", verify_args.json, "Print one JSON object");
  verify_cmd
      ->add_option("--frame", verify_args.frame_number,
                   "Verify this frame of the scene's animation")
      ->capture_default_str();

  FrameArgs view_args{"demo", "auto", "auto", "1280x720", "gl"};
  int view_frames = 0;
  std::string view_screenshot;
  CLI::App* view_cmd = app.add_subcommand(
      "view",
      "Open a window on a scene (OpenGL): drag to orbit, right-drag to pan, wheel to zoom, "
      "shift-drag the light; M method, V volumes, G cpu/gpu volumes, F12 screenshot");
  add_frame_options(view_cmd, view_args, scene_list, false);
  view_cmd->add_option("--frames", view_frames, "Close after this many frames (0: when closed)")
      ->capture_default_str();
  view_cmd->add_option("--screenshot", view_screenshot, "Write the last frame to this PNG");

  FrameArgs bench_args{"demo", "auto", "auto", "1920x1080"};
  std::vector<std::string> bench_scenes;
  for (std::string_view n : builtin_scene_names()) bench_scenes.emplace_back(n);
  int bench_frames = 10;
  CLI::App* bench_cmd = app.add_subcommand(
      "bench", "Time frames of scenes on a backend: the mean per stage over --frames frames");
  add_frame_options(bench_cmd, bench_args, scene_list);
  bench_cmd->remove_option(bench_cmd->get_option("--scene"));
  bench_cmd->add_option("--scenes", bench_scenes, "Scenes to time (names, .json files or meshes)")
      ->capture_default_str();
  bench_cmd->add_option("--frames", bench_frames, "Frames to time per scene, after one warm-up")
      ->capture_default_str();
  std::string bench_json_file, bench_suite, bench_csv, bench_plot;
  CLI::Option* json_opt =
      bench_cmd
          ->add_option("--json", bench_json_file,
                       "Print one JSON array (with --suite: write the suite's JSON to this file, "
                       "- for standard output)")
          ->expected(0, 1);
  bench_cmd->add_option("--suite", bench_suite,
                        "Run a measurement suite instead: spsv (Laine 2005's counters over the "
                        "animated knight, knights16, tree and tree-decomposed, with zp+db, zf+db, "
                        "spsv, spsv-laine and spsv-whole; 1024x768 unless --size)");
  bench_cmd->add_option("--csv", bench_csv,
                        "With --suite: write one row per scene, method and frame to this file");
  bench_cmd->add_option("--plot", bench_plot,
                        "With --suite: draw every counter's per-frame series, per scene and "
                        "method, to this PNG");

  bool info_json = false;
  CLI::App* info_cmd = app.add_subcommand(
      "info", "The OpenGL driver a headless context gets, and the features the backend uses");
  info_cmd->add_flag("--json", info_json, "Print one JSON object");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (info_cmd->parsed()) return info(info_json);
  if (view_cmd->parsed()) return view(view_args, view_frames, view_screenshot);
  if (bench_cmd->parsed()) {
    if (!bench_suite.empty() || !bench_csv.empty() || !bench_plot.empty()) {
      if (bench_suite.empty())
        return fail(std::string(bench_csv.empty() ? "--plot" : "--csv") + " needs --suite spsv");
      if (bench_suite != "spsv")
        return fail("--suite: unknown suite '" + bench_suite + "': expected spsv");
      SuiteOptions suite{bench_frames, 1024, 768, bench_json_file, bench_csv, bench_plot};
      if (json_opt->count() > 0 && bench_json_file.empty()) suite.json = "-";
      if (bench_cmd->get_option("--size")->count() > 0) {
        auto size = parse_size(bench_args.size);
        if (!size) return fail(size.error().message);
        suite.width = size->first, suite.height = size->second;
        const RenderOptions sized{suite.width, suite.height, Method::automatic,
                                  Generator::automatic};
        if (auto ok = check_options(sized); !ok) return fail("--size: " + ok.error().message);
      }
      if (bench_cmd->get_option("--extrusion")->count() > 0) {
        auto extrusion = parse_extrusion(bench_args.extrusion);
        if (!extrusion) return fail("--extrusion: " + extrusion.error().message);
        suite.extrusion = *extrusion;
      }
      return run_spsv_suite(suite);
    }
    if (!bench_json_file.empty())
      return fail("--json " + bench_json_file +
                  ": a file is for --suite; without it --json prints");
    return bench(bench_args, bench_scenes, bench_frames, json_opt->count() > 0);
  }
  if (render_cmd->parsed()) return render(render_args);
  if (verify_cmd->parsed()) return verify(verify_args);
  if (inspect_cmd->parsed()) {
    if (!std::isfinite(weld) || weld < 0.0f)
      return fail("--weld: " + std::to_string(weld) + " is not a distance (a finite number >= 0)");
    std::optional<glm::vec4> light;
    if (!light_text.empty()) {
      auto parsed = parse_light(light_text);
      if (!parsed) return fail(parsed.error().message);
      light = *parsed;
    }
    return inspect(file, json, weld, light);
  }
  return 0;
}
