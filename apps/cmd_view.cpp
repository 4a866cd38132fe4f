// shadowvol view: a window on a scene through the OpenGL backend (view.h).
#include <memory>
#include <string>

#include "cli.h"
#include "view.h"

namespace shadowvol::cli {
namespace {

struct ViewCommandArgs {
  FrameArgs frame{"demo", "auto", "auto", "1280x720", "gl"};
  int frames = 0;
  std::string screenshot;
};

int run(const ViewCommandArgs& args) {
  if (args.frames < 0) return fail("--frames: " + std::to_string(args.frames) + " is not a count");
  auto resolved = resolve(args.frame);
  if (!resolved) return fail(resolved.error().message);
  if (auto ok = gl::check_frame(resolved->gl, resolved->options); !ok)
    return fail(ok.error().message + "; the viewer draws with OpenGL");
  return run_viewer(
      {std::move(resolved->scene), resolved->options, resolved->gl, args.frames, args.screenshot});
}

}  // namespace

void add_view_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ViewCommandArgs>();
  CLI::App* cmd = app.add_subcommand(
      "view",
      "Open a window on a scene (OpenGL): drag to orbit, right-drag to pan, wheel to zoom, "
      "shift-drag the light; M method, V volumes, G cpu/gpu/vs volumes, Tab select an object, C "
      "its casting, R its receiving, F12 screenshot");
  add_frame_options(cmd, args->frame, false);
  cmd->add_option("--frames", args->frames, "Close after this many frames (0: when closed)")
      ->capture_default_str();
  cmd->add_option("--screenshot", args->screenshot, "Write the last frame to this PNG");
  cmd->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace shadowvol::cli
