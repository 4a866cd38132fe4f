// shadowvol gl: the OpenGL backend's context. Headless through EGL (Mesa's surfaceless
// platform: llvmpipe without a GPU, Mesa's GPU drivers with one; else an EGL device, as
// NVIDIA's driver offers), GL loaded with libepoxy.
//
// Owns: creating and destroying an OpenGL 4.5 core context with no window, making it current
// on the calling thread, and reporting what the driver offers the shadow-volume passes. Every
// failure comes back as an error saying what to install or check; nothing aborts.
#pragma once

#include <string>
#include <vector>

#include "core/expected.h"

namespace shadowvol::gl {

// What the shadow-volume passes use, and what they fall back to where something is missing.
struct Features {
  bool depth_clamp = false;        // closes volumes extruded to w = 0 (GL 3.2 / ARB_depth_clamp)
  bool two_sided_stencil = false;  // one pass for both facings (GL 2.0)
  bool stencil_wrap = false;       // counts below 0 and above 255 wrap (GL 1.4)
  bool geometry_shaders = false;   // volumes built on the GPU (GL 3.2)
  bool occlusion_queries = false;  // culling (GL 1.5)
  bool depth_bounds = false;       // EXT_depth_bounds_test (vendor drivers; not llvmpipe)
  bool integer_targets = false;    // R32I targets, for weights other than +-1 (GL 3.0)
  bool clip_control = false;       // reversed depth, z / w in [0, 1] (GL 4.5 / ARB_clip_control)
  std::vector<std::string> fallbacks;  // one line per missing feature: what is done instead
};

struct Info {
  std::string vendor, renderer, version;
  Features features;
};

// What the driver of the current context offers.
Info query_info();

class Context {
 public:
  // An OpenGL 4.5 core context with no window, current on the calling thread.
  static Expected<Context> create_headless();

  Context(Context&& other) noexcept;
  Context& operator=(Context&& other) noexcept;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  ~Context();

  Info info() const;

 private:
  Context() = default;
  void release();
  void* display_ = nullptr;
  void* context_ = nullptr;
};

}  // namespace shadowvol::gl
