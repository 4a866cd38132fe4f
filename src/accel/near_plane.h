// shadowvol accel: where shadow volumes meet the camera's near plane (GPU Gems 3 ch. 11 §11.2.3;
// Hornus, Hoberock, Lefebvre and Hart 2005, "ZP+").
//
// Z-pass counts the volume faces between the near plane and the surface, so it is right only
// where the near-plane point of the pixel lies outside every volume. GPU Gems 3 §11.2.3 tests
// each caster's bounds against the near-plane rectangle and takes z-fail where it may shadow it
// (may_shadow_near_plane). ZP+ instead gives each pixel the count of the volume at that point
// first: the caster's light caps, projected from the light onto the near plane, cover exactly the
// near-plane points whose segment to the light crosses them. Drawn with raster::CountRule::prefill
// (no depth test: front faces add their weight, back faces subtract it), they leave that count in
// every pixel, and the z-pass draw of the sides adds the rest. Laine 2005 §3.3 applies it in the
// pixels that use z-pass only.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/volume.h"

namespace shadowvol {

// The corners of the near-plane rectangle of a view (eye-relative), counter-clockwise from the
// bottom left.
std::array<glm::vec3, 4> near_rectangle(const glm::mat4& inv_view_proj);

// May any point of the near-plane rectangle lie in the shadow of something inside the sphere?
// The points whose segment to the light meets the sphere form a cone (a cylinder for a
// directional light); its intersection with the near rectangle is non-empty iff the sphere
// meets the convex hull of the rectangle and the light (rectangle swept towards the light).
// Tested plane by plane against that hull: conservative (may say yes when the answer is no).
bool may_shadow_near_plane(const glm::vec3& centre, float radius,
                           const std::array<glm::vec3, 4>& rect, const glm::vec4& light);

// Whether the pre-fill can be made for this light: not when it lies in the near plane itself,
// where the projection degenerates; such a volume is drawn by z-fail.
bool near_plane_prefill_possible(const glm::vec4& light, const glm::mat4& view_proj);

// Appends the pre-fill of one volume: its light caps (object space, homogeneous with w > 0, so
// that a clamped volume's dark caps, which lie among the receivers, may be given too; `model`
// takes them to eye-relative space, `mirror` = -1 where it mirrors), seen from `light`
// (eye-relative) on the near plane of `view_proj` (core/projection.h). The triangles are in clip
// space with their depth set to 1/2 (they carry counts, not depth); the weights are signed so that
// a front face adds what the volume gains along the segment from the light; `parts`, where not
// null, gets the part of each triangle's cap (light_caps.parts must be filled), since each part of
// a volume counted by its own split plane needs its own pre-fill. Each cap is first cut to the
// piece that can cross such a segment: on the light's side of the near plane and, for a point
// light, no farther from it than the light. Needs near_plane_prefill_possible(light, view_proj).
void append_near_plane_prefill(const PrimitiveList& light_caps, const glm::mat4& model, int mirror,
                               const glm::vec4& light, const glm::mat4& view_proj,
                               std::vector<glm::vec4>& triangles,
                               std::vector<std::int32_t>& weights,
                               std::vector<std::uint32_t>* parts = nullptr);

}  // namespace shadowvol
