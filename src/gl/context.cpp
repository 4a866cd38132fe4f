#include "gl/context.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

namespace shadowvol::gl {
namespace {

constexpr const char* kInstall =
    " (on Debian: apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri for Mesa's llvmpipe, or "
    "the GPU vendor's driver)";

std::string egl_error(const char* what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  return std::string(what) + " failed with EGL error " + code + kInstall;
}

// An initialised display with no window system: Mesa's surfaceless platform (llvmpipe, Mesa's
// GPU drivers), else the first EGL device that initialises (EGL_EXT_platform_device: NVIDIA's
// driver, which offers no surfaceless platform). EGL_NO_DISPLAY, with `why`, where neither does.
// SHADOWVOL_EGL_PLATFORM=surfaceless or device takes that one alone (a machine whose first
// platform fails, or a check of the second).
EGLDisplay headless_display(std::string& why) {
  const auto initialised = [](EGLDisplay d) {
    EGLint major = 0, minor = 0;
    return d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor) == EGL_TRUE;
  };
  const char* chosen = std::getenv("SHADOWVOL_EGL_PLATFORM");
  const std::string only = chosen ? chosen : "";
  if (!only.empty() && only != "surfaceless" && only != "device") {
    why = "SHADOWVOL_EGL_PLATFORM=" + only + ": expected surfaceless or device";
    return EGL_NO_DISPLAY;
  }
  why = "no headless EGL platform is available" +
        (only.empty() ? std::string() : " (SHADOWVOL_EGL_PLATFORM=" + only + ")") + kInstall;
  if (only != "device" &&
      epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (initialised(d)) return d;
    why = egl_error("eglInitialize");
  }
  if (only != "surfaceless" &&
      epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") &&
      epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count) == EGL_TRUE)
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (initialised(d)) return d;
      }
    if (only == "device") why = egl_error("eglInitialize (an EGL device)");
  }
  return EGL_NO_DISPLAY;
}

}  // namespace

Expected<Context> Context::create_headless() {
  std::string why;
  EGLDisplay display = headless_display(why);
  if (display == EGL_NO_DISPLAY) return make_error(why);
  Context ctx;
  ctx.display_ = display;
  if (!eglBindAPI(EGL_OPENGL_API)) return make_error(egl_error("eglBindAPI(OpenGL)"));
  // Surfaceless displays offer no window configs: the default EGL_WINDOW_BIT would find none.
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, config_attributes, &config, 1, &configs) || configs == 0)
    return make_error(egl_error("eglChooseConfig (an OpenGL config)"));
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                       4,
                                       EGL_CONTEXT_MINOR_VERSION,
                                       5,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
  if (context == EGL_NO_CONTEXT)
    return make_error(egl_error("creating an OpenGL 4.5 core context"));
  ctx.context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
    return make_error(egl_error("eglMakeCurrent without a surface"));
  return ctx;
}

Context::Context(Context&& other) noexcept
    : display_(std::exchange(other.display_, nullptr)),
      context_(std::exchange(other.context_, nullptr)) {}

Context& Context::operator=(Context&& other) noexcept {
  if (this != &other) {
    release();
    display_ = std::exchange(other.display_, nullptr);
    context_ = std::exchange(other.context_, nullptr);
  }
  return *this;
}

Context::~Context() { release(); }

void Context::release() {
  if (display_ == nullptr) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_ != nullptr) eglDestroyContext(display_, context_);
  eglTerminate(display_);
  eglReleaseThread();
  display_ = context_ = nullptr;
}

Info Context::info() const { return query_info(); }

Info query_info() {
  Info info;
  auto text = [](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s != nullptr ? s : "?");
  };
  info.vendor = text(GL_VENDOR);
  info.renderer = text(GL_RENDERER);
  info.version = text(GL_VERSION);
  const int version = epoxy_gl_version();  // 45 for 4.5
  Features& f = info.features;
  f.depth_clamp = version >= 32 || epoxy_has_gl_extension("GL_ARB_depth_clamp");
  f.two_sided_stencil = version >= 20;
  f.stencil_wrap = version >= 14;
  f.geometry_shaders = version >= 32;
  f.occlusion_queries = version >= 15;
  f.depth_bounds = epoxy_has_gl_extension("GL_EXT_depth_bounds_test");
  f.integer_targets = version >= 30;
  f.clip_control = version >= 45 || epoxy_has_gl_extension("GL_ARB_clip_control");
  if (!f.depth_clamp)
    f.fallbacks.push_back("no depth clamp: an infinite projection keeps w = 0 vertices at depth 0");
  if (!f.two_sided_stencil)
    f.fallbacks.push_back("no two-sided stencil: volumes are drawn twice, once per facing");
  if (!f.geometry_shaders)
    f.fallbacks.push_back("no geometry shaders: volumes are built on the CPU only");
  if (!f.depth_bounds)
    f.fallbacks.push_back(
        "no depth bounds test: tiles are not bounded by the volumes' depth range");
  if (!f.occlusion_queries) f.fallbacks.push_back("no occlusion queries: no occlusion culling");
  return info;
}

}  // namespace shadowvol::gl
