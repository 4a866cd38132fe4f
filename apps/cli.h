// shadowvol CLI: what the subcommands share: errors and progress on stderr, and the options that
// say which frame to draw (scene, method, size, backend), parsed and checked by the library.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "backend/backend.h"
#include "core/expected.h"
#include "render/frame.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace shadowvol::cli {

// Exit codes: 0 done, 1 an error (verify: the frame differs from the reference), 2 a command line
// that cannot be parsed (verify: any error, so that a script tells "differs" from "could not
// compare").
inline constexpr int kUsageError = 2;
inline constexpr int kVerifyError = 2;

// Prints "shadowvol: error: message" on stderr; returns `code`.
int fail(const std::string& message, int code = 1);
void warn(const std::string& message);

// One status line on stderr, redrawn in place, only when stderr is a terminal: a person waiting
// on long work sees it move; pipes and logs get nothing.
class StatusLine {
 public:
  StatusLine();
  ~StatusLine() { clear(); }
  void show(const std::string& text);
  void clear() { show(""); }

 private:
  bool enabled_;
};

// "WIDTHxHEIGHT", e.g. 1280x720.
Expected<std::pair<int, int>> parse_size(const std::string& text);

// What render, verify, view and bench take: a scene and how to draw it, as typed.
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
  std::string cull = "none";
  std::string occlusion = "none";
  std::string clamp = "none";
  int slices = kDefaultSlices;
  int light_view = 512;
  bool serial_volumes = false;  // RenderOptions::overlap_volumes off
  bool flat = false;            // shade every face flat (shade_flat)
  bool opaque = false;          // every caster opaque (make_opaque)
  std::string camera = "";  // a mesh file's own camera by name; empty: its first, or the stage's
  int frame = 0;            // --frame: the scene as it stands at this frame of its animation
};
// `with_backend`: false for the viewer, which is OpenGL by nature.
void add_frame_options(CLI::App* cmd, FrameArgs& args, bool with_backend = true);
// `--frame N`, for the commands that draw one frame (render, verify).
void add_frame_number_option(CLI::App* cmd, FrameArgs& args);

// The arguments parsed and checked: the scene loaded (its warnings printed), every value valid
// and the frame one the library can draw (check_frame).
struct ResolvedFrame {
  Scene scene;
  RenderOptions options;
  Backend backend = Backend::soft;
  gl::GlSettings gl;
};
Expected<ResolvedFrame> resolve(const FrameArgs& args, std::optional<Scene> scene = {});

// The renderer for frames of `options`; prints which backend `auto` took and why.
Expected<std::unique_ptr<Renderer>> make_frame_renderer(const ResolvedFrame& frame,
                                                        const RenderOptions& options);

// The method as the command line reports it, "(Laine's planes)" after spsv where they are not
// sampled, "(one plane per object)" where parts do not get their own, "(bounded)" where volumes
// are.
std::string method_label(const RenderOptions& options);

// Each subcommand adds itself to the app; its callback sets `exit_code`.
void add_inspect_command(CLI::App& app, int& exit_code);
void add_render_command(CLI::App& app, int& exit_code);
void add_verify_command(CLI::App& app, int& exit_code);
void add_view_command(CLI::App& app, int& exit_code);
void add_bench_command(CLI::App& app, int& exit_code);
void add_info_command(CLI::App& app, int& exit_code);

}  // namespace shadowvol::cli
