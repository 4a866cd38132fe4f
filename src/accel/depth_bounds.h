// shadowvol accel: how far a shadow volume reaches, in space and in depth (Laine 2005 §7).
//
// Owns: the far plane that ends a bounded volume just beyond the scene, and the depth bounds of
// a volume (EXT_depth_bounds_test; McGuire et al. 2003) as Laine makes them for his comparison
// methods: the window depths of the shadow volume of the caster's bounding box where it meets
// the view frustum. Eye-relative space; depths are core/projection.h's (1 near, 0 at infinity).
#pragma once

#include <array>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "raster/raster.h"

namespace shadowvol {

// The far plane that ends an object's bounded volume (core/volume.h, Extrusion::bounded),
// eye-relative: facing away from the light along the line from the light through the object's
// box centre (along a directional light's rays), a little beyond the farthest corner of `reach`
// (the scene's box and the near-plane rectangle, so that every receiver and the pre-fill's near
// plane lie on its kept side). The plane at infinity where a point light sits on one of the
// object's box corners or sees one more than 84 degrees from that line: rays that graze the
// plane would be extruded to huge coordinates.
glm::vec4 bounded_far_plane(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& reach_lo,
                            const glm::vec3& reach_hi, const glm::vec4& light);

// Laine 2005 §7's depth bounds (FramePlan::depth_bounds). The box's volume, cut by the far plane,
// is convex (the hull of the box and its shadow on the plane), so where it meets the frustum its
// depths reach their extremes on its boundary, cut by the frustum's planes, or at a corner of
// the near rectangle inside it (depth 1); the far end of the frustum is at infinity (depth 0).
// Its boundary is the box's own volume, built by core like any other. Widened by a hair, as the
// rasterizer's depths may round past a vertex's.
raster::DepthBounds box_volume_depth_bounds(const glm::vec3& lo, const glm::vec3& hi,
                                            const glm::vec4& light, const glm::vec4& far_plane,
                                            const glm::mat4& view_proj,
                                            const std::array<glm::vec3, 4>& near_rect);

}  // namespace shadowvol
