#include "view.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <epoxy/gl.h>
// GLFW after epoxy, which provides the OpenGL declarations.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/gtc/type_ptr.hpp>
#include <glm/gtx/rotate_vector.hpp>

#include "gl/objects.h"
#include "image_file.h"
#include "window_draw.h"

namespace shadowvol {
namespace {

// What the mouse and keys change, and the frame they change it in.
struct Controls {
  glm::vec3 target{0.0f};
  float distance = 1.0f, yaw = 0.0f, pitch = 0.0f;
  glm::vec4 light{0.0f};  // the first light, dragged about the target
  bool dragging_light = false;
  int button = -1;  // GLFW mouse button held, or -1
  double last_x = 0, last_y = 0;
  Method method = Method::automatic;
  bool show_volumes = false, paused = false, screenshot = false;
  gl::GlSettings gl;
  // Who casts and who receives, per object (SceneObject's flags), toggled on the selected one.
  std::vector<std::uint8_t> casts, receives;
  std::size_t selected = 0;

  void look_from(const Camera& camera) {
    target = camera.target;
    const glm::vec3 d = camera.position - camera.target;
    distance = glm::length(d);
    yaw = std::atan2(d.x, d.z);
    pitch = std::asin(std::clamp(d.y / distance, -1.0f, 1.0f));
  }
  glm::vec3 eye() const {
    return target + distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                         std::cos(pitch) * std::cos(yaw));
  }
};

Controls& controls_of(GLFWwindow* window) {
  return *static_cast<Controls*>(glfwGetWindowUserPointer(window));
}

void on_button(GLFWwindow* window, int button, int action, int mods) {
  Controls& c = controls_of(window);
  if (action == GLFW_RELEASE) {
    c.button = -1;
    return;
  }
  c.button = button;
  c.dragging_light = button == GLFW_MOUSE_BUTTON_LEFT &&
                     ((mods & GLFW_MOD_SHIFT) != 0 || glfwGetKey(window, GLFW_KEY_L) == GLFW_PRESS);
  glfwGetCursorPos(window, &c.last_x, &c.last_y);
}

void on_move(GLFWwindow* window, double x, double y) {
  Controls& c = controls_of(window);
  const auto dx = static_cast<float>(x - c.last_x), dy = static_cast<float>(y - c.last_y);
  c.last_x = x;
  c.last_y = y;
  if (c.button == GLFW_MOUSE_BUTTON_LEFT && c.dragging_light) {
    // Around the vertical axis through the target, and up or down.
    const glm::vec3 centre = c.light.w != 0.0f ? c.target : glm::vec3(0.0f);
    glm::vec3 offset = glm::vec3(c.light) - centre;
    offset = glm::rotateY(offset, -dx * 0.01f);
    offset.y = std::max(offset.y - dy * 0.02f * std::max(1.0f, glm::length(offset) * 0.2f), 0.05f);
    c.light = glm::vec4(centre + offset, c.light.w);
  } else if (c.button == GLFW_MOUSE_BUTTON_LEFT) {
    c.yaw -= dx * 0.01f;
    c.pitch = std::clamp(c.pitch + dy * 0.01f, -1.5f, 1.5f);
  } else if (c.button == GLFW_MOUSE_BUTTON_RIGHT || c.button == GLFW_MOUSE_BUTTON_MIDDLE) {
    const glm::vec3 forward = glm::normalize(c.target - c.eye());
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    c.target += (-dx * right + dy * up) * (c.distance * 0.0015f);
  }
}

void on_scroll(GLFWwindow* window, double, double y) {
  Controls& c = controls_of(window);
  c.distance = std::clamp(c.distance * std::pow(0.9f, static_cast<float>(y)), 1e-3f, 1e6f);
}

void on_key(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  Controls& c = controls_of(window);
  switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
      glfwSetWindowShouldClose(window, GLFW_TRUE);
      break;
    case GLFW_KEY_M:
      c.method = c.method == Method::automatic ? Method::zpass
                 : c.method == Method::zpass   ? Method::zfail
                                               : Method::automatic;
      break;
    case GLFW_KEY_V:
      c.show_volumes = !c.show_volumes;
      break;
    case GLFW_KEY_G:
      c.gl.volumes = c.gl.volumes == gl::VolumePath::cpu   ? gl::VolumePath::gpu
                     : c.gl.volumes == gl::VolumePath::gpu ? gl::VolumePath::vertex
                                                           : gl::VolumePath::cpu;
      break;
    case GLFW_KEY_SPACE:
      c.paused = !c.paused;
      break;
    case GLFW_KEY_F12:
      c.screenshot = true;
      break;
    case GLFW_KEY_TAB:
      if (!c.casts.empty()) c.selected = (c.selected + 1) % c.casts.size();
      break;
    case GLFW_KEY_C:
      if (!c.casts.empty()) c.casts[c.selected] = !c.casts[c.selected];
      break;
    case GLFW_KEY_R:
      if (!c.receives.empty()) c.receives[c.selected] = !c.receives[c.selected];
      break;
    default:
      break;
  }
}

// Ends GLFW however run_viewer returns.
struct GlfwSession {
  bool ok = glfwInit() == GLFW_TRUE;
  ~GlfwSession() {
    if (ok) glfwTerminate();
  }
};

int fail(const std::string& message) {
  std::cerr << "shadowvol: error: " << message << "\n";
  return 1;
}

}  // namespace

int run_viewer(const ViewArgs& args) {
  glfwSetErrorCallback(
      [](int, const char* text) { std::cerr << "shadowvol: glfw: " << text << "\n"; });
  GlfwSession session;
  if (!session.ok)
    return fail(
        "cannot open a window: GLFW did not start (is there a display? Without one, use render "
        "--backend gl, or run under xvfb-run)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window =
      glfwCreateWindow(args.options.width, args.options.height,
                       ("shadowvol view: " + args.scene.name).c_str(), nullptr, nullptr);
  if (window == nullptr)
    return fail(
        "cannot open a window with an OpenGL 4.5 core context (on Debian: apt-get install "
        "libgl1 libglx-mesa0 libgl1-mesa-dri, or the GPU vendor's driver)");
  glfwMakeContextCurrent(window);
  glfwSwapInterval(args.frames > 0 ? 0 : 1);
  int status = 0;
  {
    auto made = gl::GlBackend::create(args.gl);
    if (!made) {
      glfwDestroyWindow(window);
      return fail(made.error().message);
    }
    gl::GlBackend& backend = **made;
    Renderer renderer(std::move(*made));
    Frame frame;
    auto text = TextOverlay::create();
    if (!text) {
      glfwDestroyWindow(window);
      return fail(text.error().message);
    }
    Controls controls;
    controls.look_from(args.scene.camera);
    if (!args.scene.lights.empty()) controls.light = args.scene.lights[0].position;
    controls.method = args.options.method;
    controls.gl = args.gl;
    for (const SceneObject& object : args.scene.objects) {
      controls.casts.push_back(object.casts_shadows);
      controls.receives.push_back(object.receives_shadows);
    }
    glfwSetWindowUserPointer(window, &controls);
    glfwSetMouseButtonCallback(window, on_button);
    glfwSetCursorPosCallback(window, on_move);
    glfwSetScrollCallback(window, on_scroll);
    glfwSetKeyCallback(window, on_key);

    int animation_frame = 0, shown = 0, screenshots = 0;
    double smoothed_ms = 0.0;
    while (!glfwWindowShouldClose(window)) {
      glfwPollEvents();
      int width = 0, height = 0;
      glfwGetFramebufferSize(window, &width, &height);
      if (width < 1 || height < 1) continue;  // minimised
      Scene scene = scene_at_frame(args.scene, animation_frame);
      if (!controls.paused) ++animation_frame;
      scene.camera.target = controls.target;
      scene.camera.position = controls.eye();
      if (!scene.lights.empty()) scene.lights[0].position = controls.light;
      for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        scene.objects[o].casts_shadows = controls.casts[o] != 0;
        scene.objects[o].receives_shadows = controls.receives[o] != 0;
      }
      RenderOptions options = args.options;
      options.width = std::min(width, 16384);
      options.height = std::min(height, 16384);
      options.method = controls.method;
      options.show_volumes = controls.show_volumes;
      gl::GlSettings settings = controls.gl;
      if (!gl::check_settings(settings, options.generator).ok())
        settings.volumes = gl::VolumePath::cpu;
      backend.set_settings(settings);

      const auto start = std::chrono::steady_clock::now();
      if (options.show_volumes) {  // the edges are drawn over a read-back image
        renderer.render(scene, options, frame);
        show_image(frame.image);
      } else {
        renderer.present(scene, options, frame);
      }
      const FrameStats& stats = frame.stats;
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      smoothed_ms = shown == 0 ? ms : 0.9 * smoothed_ms + 0.1 * ms;

      char line[256];
      std::vector<std::string> lines;
      std::snprintf(line, sizeof line, "%.1f ms a frame (depth %.1f, counts %.1f, shade %.1f)  %s",
                    smoothed_ms, stats.ms_depth, stats.ms_counts, stats.ms_shade,
                    backend.info().renderer.c_str());
      lines.push_back(line);
      std::snprintf(line, sizeof line, "method %s [M]  volumes %s [G]  edges %s [V]  %s",
                    std::string(to_string(options.method)).c_str(),
                    std::string(gl::to_string(settings.volumes)).c_str(),
                    options.show_volumes ? "on" : "off", controls.paused ? "paused [Space]" : "");
      lines.push_back(line);
      // Twelve objects about the selected one.
      const std::size_t first =
          std::min(controls.selected - std::min<std::size_t>(controls.selected, 5),
                   scene.objects.size() - std::min<std::size_t>(scene.objects.size(), 12));
      for (std::size_t o = first; o < scene.objects.size() && o < first + 12; ++o) {
        const int zfail = o < stats.zfail_lights.size() ? stats.zfail_lights[o] : 0;
        const int lights = static_cast<int>(scene.lights.size());
        const SceneObject& object = scene.objects[o];
        char glass[48] = "";
        if (object.material.transparent())
          std::snprintf(glass, sizeof glass, ", transparent (opacity %.2f)",
                        object.material.opacity);
        std::snprintf(line, sizeof line, "%s %s: %s%s%s%s", o == controls.selected ? ">" : " ",
                      object.name.c_str(),
                      zfail == 0        ? "z-pass"
                      : zfail == lights ? "z-fail"
                                        : "z-fail for some lights",
                      glass, object.casts_shadows ? "" : ", casts no shadows",
                      object.receives_shadows ? "" : ", receives none");
        lines.push_back(line);
      }
      lines.push_back(
          "drag: orbit  right drag: pan  wheel: zoom  shift+drag: light  F12: screenshot  Tab: "
          "select  C: casts  R: receives");
      text->draw(lines, width, height);

      ++shown;
      const bool last = args.frames > 0 && shown >= args.frames;
      if (controls.screenshot || (last && !args.screenshot.empty())) {
        const std::string path = last && !args.screenshot.empty()
                                     ? args.screenshot
                                     : "shadowvol-view-" + std::to_string(++screenshots) + ".png";
        const Image image = read_window(width, height);
        if (auto ok = write_png(path, image); !ok) {
          status = fail(ok.error().message);
          break;
        }
        std::cout << "wrote screenshot " << path << " (" << width << "x" << height << ", "
                  << distinct_colours(image) << " distinct colours)\n";
        controls.screenshot = false;
      }
      glfwSwapBuffers(window);
      if (last) break;
    }
    if (const std::string error = gl::take_error(); !error.empty())
      status = fail("OpenGL reported " + error);
  }  // the renderer and the text overlay go while the context is still current
  glfwDestroyWindow(window);
  return status;
}

}  // namespace shadowvol
