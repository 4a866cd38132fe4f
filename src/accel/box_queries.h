// shadowvol accel: the geometry of hierarchical occlusion culling's queries (Bittner, Wimmer,
// Piringer and Purgathofer 2004, "CHC"; GPU Gems 3 ch. 11 §11.3.3), eye-relative.
//
// Owns: the triangles a query draws for a box seen from the eye, and for the box's shadow volume
// (the box extruded away from a light to infinity), and when such a query cannot answer and the
// node must be taken as visible. A query passes where a fragment lies at or in front of the stored
// depth (raster::query), so its triangles must over-cover: every pixel centre whose ray meets the
// region before (or at) its stored surface must be covered by a fragment at that depth or nearer.
// The region is closed and convex, so every triangle of its boundary is drawn (both facings), and
// the box is grown by query_margin() first, which outweighs the rasterizer's snapping of vertices
// to 1/256 pixel for boxes up to a few thousand pixels across at any distance. Where the region
// meets the near plane's rectangle, the rays start inside it and cross no boundary on their way to
// a surface inside it, so no query can answer (box_meets_near, shadow_meets_near): the node is
// taken as visible.
#pragma once

#include <array>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace shadowvol {

// How much a box is grown before its query: 1e-4 of the farthest corner's distance from the eye
// (the origin), and of the box's diagonal.
float query_margin(const glm::vec3& lo, const glm::vec3& hi);

// The box [lo, hi], grown by query_margin: 12 triangles, 3 vertices each (w = 1).
void box_query_triangles(const glm::vec3& lo, const glm::vec3& hi, std::vector<glm::vec4>& out);
// The shadow volume of the box [lo, hi], grown by query_margin, from `light` (homogeneous; w = 0
// directional): the box's faces toward the light (or edge-on to it) and, for each edge between
// such a face and one away from it (the silhouette), the quad from the edge to its image at
// infinity away from the light (w = 0). They bound the region of every point whose segment to
// the light meets the box (the far cap lies at infinity, depth 0, where no stored surface is).
void shadow_query_triangles(const glm::vec3& lo, const glm::vec3& hi, const glm::vec4& light,
                            std::vector<glm::vec4>& out);

// Whether the box lies wholly outside one plane of the view frustum (x, y within w; in front of
// the near plane): nothing in it can be drawn.
bool box_outside_frustum(const glm::vec3& lo, const glm::vec3& hi, const glm::mat4& view_proj);
// Whether the box may meet the near plane's rectangle (its grown box meets the rectangle's box).
bool box_meets_near(const glm::vec3& lo, const glm::vec3& hi,
                    const std::array<glm::vec3, 4>& near_rect);
// Whether the box's shadow volume may meet the near rectangle (near_plane.h's sphere test), or a
// point light lies in the box (its shadow volume is then all of space): no query can answer.
bool shadow_meets_near(const glm::vec3& lo, const glm::vec3& hi, const glm::vec4& light,
                       const std::array<glm::vec3, 4>& near_rect);

}  // namespace shadowvol
