// shadowvol backend: choosing a backend by name, the one place that knows both.
//
// Owns: "soft", "gl" and "auto" (gl where an OpenGL 4.5 context can be made and the options ask
// for nothing only the software rasterizer draws, else soft, and a line saying which and why),
// and making the renderer (the frame pipeline on that backend), headless.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "core/expected.h"
#include "gl/gl_backend.h"
#include "render/renderer.h"

namespace shadowvol {

enum class Backend : std::uint8_t { soft, gl, automatic };
std::string_view to_string(Backend backend);
Expected<Backend> parse_backend(std::string_view name);

struct MadeRenderer {
  std::unique_ptr<Renderer> renderer;
  std::string note;  // for `auto`: which backend it took and why; else empty
};

// The renderer of `backend` for frames drawn with `options`. gl makes a headless context
// (gl/context.h) and fails with what to install when it cannot, or with what it cannot draw of
// `options` (gl::check_frame); auto takes soft in either case, and says so in the note.
// `gl_settings` apply to gl only: they are checked against the generator whatever the backend,
// and gpu volumes with the soft backend are an error.
Expected<MadeRenderer> make_renderer(Backend backend, const gl::GlSettings& gl_settings = {},
                                     const RenderOptions& options = {});

}  // namespace shadowvol
