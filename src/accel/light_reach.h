// shadowvol accel: where a point light of limited range can change a pixel (Lengyel 2002,
// "The Mechanics of Robust Stencil Shadows"; McGuire et al. 2003; GPU Gems 3 §11.2.3).
//
// Owns: the screen rectangle (the scissor) and the window depths (the depth bounds) of a light's
// sphere of range, and whether a box meets that sphere. A surface within the range lies inside
// both, so a count or lit pass limited to them loses nothing; and the segment from such a
// surface to the light lies inside the sphere (it is convex), so a caster wholly outside it
// shadows nothing there. Eye-relative space; depths are core/projection.h's (1 near, 0 at
// infinity); pixels as the rasterizer's (row 0 at the top, centres at + 0.5).
#pragma once

#include <cstdint>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "raster/raster.h"

namespace shadowvol {

struct LightReach {
  bool limited = false;  // a point light with a range; else the rest is the whole image
  raster::PixelRect scissor;
  raster::DepthBounds depth;
  bool empty() const { return scissor.empty() || depth.zmin > depth.zmax; }
};

// The reach of a point light at `light` (eye-relative, w = 1) with radius `range`, seen through
// a camera of view `view` (eye-relative to eye space, a rotation), projection `proj`
// (core/projection.h) and near distance `near`, on a width x height image. Where the sphere lies
// wholly in front of the near plane, the rectangle is the one its tangent planes through the eye
// bound (Lengyel); else that of the view-aligned cube around it, cut by the near plane.
// Conservative by a pixel and a hair of depth, for rounding.
LightReach light_reach(const glm::vec4& light, float range, const glm::mat4& view,
                       const glm::mat4& proj, float near, int width, int height);

// Sets mask[p] = 1 (the light does not arrive) at every pixel of a width x height image, row 0
// at the top, whose surface lies beyond the light's range: outside the scissor, or at distance
// range or more from `light` (eye-relative, w = 1), its point taken from its window depth
// (depth[p]) through inv_view_proj. A light without a range leaves the mask alone.
void mark_beyond_reach(std::span<std::uint8_t> mask, std::span<const float> depth,
                       const glm::mat4& inv_view_proj, const glm::vec4& light, float range,
                       const LightReach& reach, int width, int height);

// Whether the box [lo, hi] comes within `range` of the point `centre`.
bool box_meets_sphere(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& centre,
                      float range);

}  // namespace shadowvol
