#include "cli.h"

#include <charconv>
#include <iostream>

#include <unistd.h>

#include "scene/scene_io.h"

namespace shadowvol::cli {

int fail(const std::string& message, int code) {
  std::cerr << "shadowvol: error: " << message << "\n";
  return code;
}

void warn(const std::string& message) { std::cerr << "shadowvol: warning: " << message << "\n"; }

StatusLine::StatusLine() : enabled_(isatty(STDERR_FILENO) == 1) {}

void StatusLine::show(const std::string& text) {
  if (enabled_) std::cerr << "\r\033[K" << text << std::flush;
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

void add_frame_options(CLI::App* cmd, FrameArgs& args, bool with_backend) {
  std::string scenes;
  for (std::string_view n : builtin_scene_names())
    scenes += (scenes.empty() ? "" : ", ") + std::string(n);
  cmd->add_option("--scene", args.scene,
                  "A built-in scene (" + scenes +
                      "; city:N and city-above:N, a city of N buildings; night-street:N, N lamps), "
                      "a scene file (.json) "
                      "or a mesh file")
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
  cmd->add_option("--cull", args.cull,
                  "CC shadow volumes' culling of casters whose volumes change no pixel: none, "
                  "frustum (receivers in the view frustum; casters outside the light's views of "
                  "them) or occlusion (receivers the image shows; casters in shadow or whose "
                  "shadow is unseen, tested conservatively in the light's views)")
      ->capture_default_str();
  cmd->add_option("--occlusion", args.occlusion,
                  "Hierarchical occlusion culling over the scene's BVH by occlusion queries (CHC): "
                  "none, eye (the depth pass front to back, leaving out what the depth drawn so "
                  "far hides), shadows (volumes whose object's box extruded away from the light "
                  "holds no visible surface) or both; exact")
      ->capture_default_str();
  cmd->add_option("--clamp", args.clamp,
                  "CC shadow volumes' clamping of volumes to where receivers lie: none, "
                  "continuous (per caster, the intervals of depth from the light that hold "
                  "receivers' boxes), discrete (only the strips of the image where a visible "
                  "point may lie in the caster's shadow) or both")
      ->capture_default_str();
  cmd->add_option(
         "--slices", args.slices,
         "--clamp discrete or both: the strips of the image, 1 .. " + std::to_string(kMaxSlices))
      ->capture_default_str();
  cmd->add_flag("--serial-volumes", args.serial_volumes,
                "Build the CPU volumes per light after the depth pass, instead of on worker "
                "threads beside it (the update manager; Intel, \"Threading Shadow Volumes\")");
  cmd->add_option("--light-view", args.light_view,
                  "--cull, --clamp: the side of each light view, in pixels (a cube's faces each)")
      ->capture_default_str();
  cmd->add_option("--size", args.size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_flag("--flat", args.flat,
                "Shade every face flat, ignoring the mesh files' normals (shadows do not change)");
  cmd->add_flag("--opaque", args.opaque,
                "Make every object opaque: plain shadows, whatever the files' materials say of "
                "transparency (their colours kept)");
  cmd->add_option("--camera", args.camera,
                  "A mesh file's own camera, by name (glTF, COLLADA, FBX); without it, the file's "
                  "first camera, or the default stage's where it has none");
  if (with_backend)
    cmd->add_option("--backend", args.backend,
                    "soft (CPU rasterizer), gl (OpenGL 4.5, headless) or auto (gl if a context "
                    "can be made and draws the method, else soft)")
        ->capture_default_str();
  cmd->add_option("--volumes", args.volumes,
                  "gl: volumes built on the cpu (any generator), in a geometry shader on the gpu "
                  "(standard or robust), or extruded in the vertex shader from a volume mesh made "
                  "once per mesh (vs; standard or robust)")
      ->capture_default_str();
  cmd->add_option("--counts", args.counts,
                  "gl: count volumes in the stencil buffer (weights other than +-1 drawn "
                  "|weight| times), an additive R32F target, or auto (stencil where all weights "
                  "are +-1)")
      ->capture_default_str();
}

void add_frame_number_option(CLI::App* cmd, FrameArgs& args) {
  cmd->add_option("--frame", args.frame,
                  "Draw the scene as it stands at this frame of its animation: the motions of "
                  "built-in scenes and scene files, and a mesh file's own animation (glTF, "
                  "COLLADA, FBX) at 30 frames a second or its scene file's frames_per_second")
      ->capture_default_str();
}

namespace {

// `value` parsed by `parse`, or the error prefixed by the option's name.
template <class Parse>
auto parsed(const char* option, const std::string& value, Parse&& parse) -> decltype(parse(value)) {
  auto result = parse(value);
  if (!result) return make_error(std::string(option) + ": " + result.error().message);
  return result;
}

}  // namespace

Expected<ResolvedFrame> resolve(const FrameArgs& args, std::optional<Scene> scene) {
  StatusLine status;
  if (!scene) status.show("reading " + args.scene);
  auto loaded = scene ? Expected<LoadedScene>(LoadedScene{std::move(*scene), {}, {}})
                      : load_scene(args.scene);
  status.clear();
  if (!loaded) return loaded.error();
  if (args.frame < 0)
    return make_error("--frame: " + std::to_string(args.frame) +
                      " is not a frame (0, the scene as given, or more)");
  if (args.frame > 0) loaded->scene = scene_at_frame(loaded->scene, args.frame);
  if (!args.camera.empty())
    if (auto ok = use_camera(*loaded, args.camera); !ok) return ok.error();
  if (args.flat) shade_flat(loaded->scene);
  if (args.opaque) make_opaque(loaded->scene);
  for (const std::string& w : loaded->warnings) warn(w);
  auto method = parsed("--method", args.method, parse_method);
  if (!method) return method.error();
  auto generator = parsed("--generator", args.generator, parse_generator);
  if (!generator) return generator.error();
  auto size = parse_size(args.size);
  if (!size) return size.error();
  auto extrusion = parsed("--extrusion", args.extrusion, parse_extrusion);
  if (!extrusion) return extrusion.error();
  auto split_planes = parsed("--split-planes", args.split_planes, parse_split_planes);
  if (!split_planes) return split_planes.error();
  auto split_parts = parsed("--split-parts", args.split_parts, parse_split_parts);
  if (!split_parts) return split_parts.error();
  auto cull = parsed("--cull", args.cull, parse_cull);
  if (!cull) return cull.error();
  auto occlusion = parsed("--occlusion", args.occlusion, parse_occlusion);
  if (!occlusion) return occlusion.error();
  auto clamp = parsed("--clamp", args.clamp, parse_clamp);
  if (!clamp) return clamp.error();
  if (auto ok = check_slices(args.slices); !ok)
    return make_error("--slices: " + ok.error().message);
  auto backend = parsed("--backend", args.backend, parse_backend);
  if (!backend) return backend.error();
  auto volumes = parsed("--volumes", args.volumes, gl::parse_volume_path);
  if (!volumes) return volumes.error();
  auto counts = parsed("--counts", args.counts, gl::parse_count_target);
  if (!counts) return counts.error();
  RenderOptions options{size->first, size->second, *method, *generator, *extrusion};
  options.split_planes = *split_planes;
  options.split_parts = *split_parts;
  options.cull = *cull;
  options.clamp = *clamp;
  options.occlusion = *occlusion;
  options.slices = args.slices;
  options.light_view_size = args.light_view;
  options.overlap_volumes = !args.serial_volumes;
  if (auto ok = check_light_view_size(args.light_view); !ok)
    return make_error("--light-view: " + ok.error().message);
  if (auto ok = check_options(options); !ok) return make_error("--size: " + ok.error().message);
  if (auto ok = check_frame(loaded->scene, options); !ok) return ok.error();
  return ResolvedFrame{std::move(loaded->scene), options, *backend, {*volumes, *counts}};
}

Expected<std::unique_ptr<Renderer>> make_frame_renderer(const ResolvedFrame& frame,
                                                        const RenderOptions& options) {
  auto made = make_renderer(frame.backend, frame.gl, options);
  if (!made) return made.error();
  if (!made->note.empty()) std::cerr << "shadowvol: " << made->note << "\n";
  return std::move(made->renderer);
}

std::string method_label(const RenderOptions& options) {
  const bool split = options.method == Method::split_plane;
  std::string label(to_string(options.method));
  if (split && options.split_planes == SplitPlanes::laine) label += " (Laine's planes)";
  if (split && options.split_parts == SplitParts::whole) label += " (one plane per object)";
  if (options.extrusion == Extrusion::bounded) label += " (bounded)";
  if (options.cull != Cull::none)
    label += " (culled by " + std::string(to_string(options.cull)) + ")";
  if (options.occlusion != Occlusion::none)
    label += " (occlusion culling: " + std::string(to_string(options.occlusion)) + ")";
  if (options.clamp != Clamp::none) {
    label += " (clamped " + std::string(to_string(options.clamp));
    if (clamps_discrete(options.clamp))
      label += ", " + std::to_string(options.slices) + (options.slices == 1 ? " slice" : " slices");
    label += ")";
  }
  return label;
}

}  // namespace shadowvol::cli
