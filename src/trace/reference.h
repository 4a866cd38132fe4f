// shadowvol trace: the ray-traced reference (Embree 3). Independent of all shadow-volume code:
// it shares only the scene description and the camera with the renderer.
//
// Owns: an Embree device and scene built from the world-space triangles of a Scene, primary
// rays through the same pixel centres the rasterizer samples, and one shadow ray per visible
// point and light. Errors from Embree come back as values.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/expected.h"
#include "scene/scene.h"

namespace shadowvol {

struct ReferenceFrame {
  int width = 0, height = 0;
  std::vector<std::int32_t> object;  // per pixel: scene object index, -1 for background
  std::vector<std::uint32_t> face;   // per pixel: face of that object
  // Per light, per pixel: 1 if the visible surface faces the light (its normal, turned towards
  // the eye, points to the light's side), and 1 if the segment to the light crosses a surface.
  std::vector<std::vector<std::uint8_t>> faces_light;
  std::vector<std::vector<std::uint8_t>> shadowed;
};

// Traces the scene at width x height through scene.camera. Fails if Embree cannot be set up.
Expected<ReferenceFrame> trace_reference(const Scene& scene, int width, int height);

}  // namespace shadowvol
