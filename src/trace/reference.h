// shadowvol trace: the ray-traced reference (Embree 3). Independent of all shadow-volume code:
// it shares only the scene description and the camera with the renderer.
//
// Owns: an Embree device and scene built from the world-space triangles of a Scene, primary
// rays through the same pixel centres the rasterizer samples (or any other point of the window),
// and one shadow ray per visible point and light. Errors from Embree come back as values.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/expected.h"
#include "scene/scene.h"

namespace shadowvol {

// What the reference sees along one primary ray.
struct ReferenceSample {
  std::int32_t object = -1;  // scene object index, -1 for background
  std::uint32_t face = 0;    // face of that object
  // Per light: whether the surface faces the light (its normal, turned towards the eye, points
  // to the light's side), and whether the segment to the light crosses a surface.
  std::vector<std::uint8_t> faces_light, shadowed;
};

// The scene built once for Embree, traced through a width x height window of scene.camera.
class ReferenceTracer {
 public:
  // Fails if Embree cannot be set up or cannot build the scene.
  static Expected<std::shared_ptr<const ReferenceTracer>> create(const Scene& scene, int width,
                                                                 int height);
  ~ReferenceTracer();
  // The ray through window point (x, y), in pixels from the top-left corner: pixel (i, j) is
  // sampled at (i + 0.5, j + 0.5), as the rasterizer samples it.
  ReferenceSample sample(double x, double y) const;
  // Empty, or the error Embree has reported while tracing.
  std::string error() const;

 private:
  struct State;
  explicit ReferenceTracer(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

struct ReferenceFrame {
  int width = 0, height = 0;
  std::vector<std::int32_t> object;  // per pixel: scene object index, -1 for background
  std::vector<std::uint32_t> face;   // per pixel: face of that object
  // Per light, per pixel: 1 if the visible surface faces the light (its normal, turned towards
  // the eye, points to the light's side), and 1 if the segment to the light crosses a surface.
  std::vector<std::vector<std::uint8_t>> faces_light;
  std::vector<std::vector<std::uint8_t>> shadowed;
  // The tracer that made the frame, for samples between pixel centres.
  std::shared_ptr<const ReferenceTracer> tracer;
};

// Traces the scene at width x height through scene.camera, at every pixel centre. Fails if
// Embree cannot be set up.
Expected<ReferenceFrame> trace_reference(const Scene& scene, int width, int height);

}  // namespace shadowvol
