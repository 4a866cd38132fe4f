// shadowvol view: an interactive window on the OpenGL backend (GLFW).
//
// Mouse: left drag orbits the camera, right (or middle) drag pans, the wheel zooms; with Shift
// (or L held) a left drag moves the first light around the target instead. Keys: M cycles the
// method (auto, z-pass, z-fail), V toggles the volumes' edges, G switches CPU and geometry-shader
// volumes, Space pauses the animation, F12 writes a screenshot, Esc or Q quits. The frame time
// and each object's method are drawn in the corner.
#pragma once

#include <string>

#include "gl/gl_backend.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace shadowvol {

struct ViewArgs {
  Scene scene;
  RenderOptions options;  // width and height: the window's initial size
  gl::GlSettings gl;
  int frames = 0;          // > 0: close after this many frames (tests, screenshots)
  std::string screenshot;  // written after the last frame, when given
};

// Runs until the window closes; 0 on success, else prints the problem and returns 1.
int run_viewer(const ViewArgs& args);

}  // namespace shadowvol
