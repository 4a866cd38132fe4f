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
  // What only the gl backend does, asked for by name: never dropped in silence on the soft one.
  const bool gpu_volumes = gl_settings.volumes != gl::VolumePath::cpu;
  const bool gl_counts = gl_settings.counts != gl::CountTarget::automatic;
  const bool gl_only = gpu_volumes || gl_counts;
  const std::string path = gpu_volumes ? "volumes built in a shader (--volumes " +
                                             std::string(gl::to_string(gl_settings.volumes)) + ")"
                                       : "counting in a target of gl's (--counts " +
                                             std::string(gl::to_string(gl_settings.counts)) + ")";
  const std::string needs_gl = path + (gpu_volumes ? " need" : " needs") + " the gl backend";
  auto soft = [] { return std::make_unique<Renderer>(std::make_unique<soft::SoftBackend>()); };
  if (backend == Backend::soft) {
    if (gl_only) return make_error(needs_gl);
    return MadeRenderer{soft(), ""};
  }
  if (auto ok = gl::check_settings(gl_settings, options.generator); !ok) return ok.error();
  if (auto drawable = gl::check_frame(gl_settings, options); !drawable) {
    const std::string& reason = drawable.error().message;
    if (backend == Backend::gl) return make_error(reason + "; use --backend soft");
    if (gl_only) return make_error(needs_gl + ", but " + reason);
    return MadeRenderer{soft(), "backend auto: soft, since " + reason};
  }
  auto gl = make_gl(gl_settings);
  if (gl) {
    std::string note =
        backend == Backend::automatic ? "backend auto: gl (an OpenGL 4.5 context was made)" : "";
    return MadeRenderer{std::move(*gl), note};
  }
  if (backend == Backend::gl) return gl.error();
  if (gl_only) return make_error(needs_gl + ", and " + gl.error().message);
  return MadeRenderer{soft(), "backend auto: soft, since " + gl.error().message};
}

}  // namespace shadowvol
