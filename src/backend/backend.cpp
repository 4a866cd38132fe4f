#include "backend/backend.h"

#include "core/names.h"
#include "soft/soft_backend.h"

namespace shadowvol {

std::string_view to_string(Backend backend) {
  switch (backend) {
    case Backend::soft:
      return "soft";
    case Backend::gl:
      return "gl";
    case Backend::automatic:
      return "auto";
  }
  return "unknown";
}

Expected<Backend> parse_backend(std::string_view name) {
  return parse_name(name, {Backend::soft, Backend::gl, Backend::automatic}, "backend");
}

namespace {

Expected<std::unique_ptr<Renderer>> make_gl(const gl::GlSettings& settings) {
  auto context = gl::Context::create_headless();
  if (!context) return make_error("cannot create an OpenGL context: " + context.error().message);
  auto backend = gl::GlBackend::create(settings, std::move(*context));
  if (!backend) return backend.error();
  return std::make_unique<Renderer>(std::move(*backend));
}

}  // namespace

Expected<MadeRenderer> make_renderer(Backend backend, const gl::GlSettings& gl_settings,
                                     const RenderOptions& options) {
  // Volumes built in a shader: only the gl backend has one.
  const bool gpu_volumes = gl_settings.volumes != gl::VolumePath::cpu;
  const std::string path = "--volumes " + std::string(gl::to_string(gl_settings.volumes));
  auto soft = [] { return std::make_unique<Renderer>(std::make_unique<soft::SoftBackend>()); };
  if (backend == Backend::soft) {
    if (gpu_volumes)
      return make_error("volumes built in a shader (" + path + ") need the gl backend");
    return MadeRenderer{soft(), ""};
  }
  if (auto ok = gl::check_settings(gl_settings, options.generator); !ok) return ok.error();
  if (auto drawable = gl::check_frame(gl_settings, options); !drawable) {
    const std::string& reason = drawable.error().message;
    if (backend == Backend::gl) return make_error(reason + "; use --backend soft");
    if (gpu_volumes) return make_error(path + " needs the gl backend, but " + reason);
    return MadeRenderer{soft(), "backend auto: soft, since " + reason};
  }
  auto gl = make_gl(gl_settings);
  if (gl) {
    std::string note =
        backend == Backend::automatic ? "backend auto: gl (an OpenGL 4.5 context was made)" : "";
    return MadeRenderer{std::move(*gl), note};
  }
  if (backend == Backend::gl) return gl.error();
  if (gpu_volumes) return make_error(path + " needs the gl backend, and " + gl.error().message);
  return MadeRenderer{soft(), "backend auto: soft, since " + gl.error().message};
}

}  // namespace shadowvol
