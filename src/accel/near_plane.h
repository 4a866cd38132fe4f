// shadowvol accel: where shadow volumes meet the camera's near plane (GPU Gems 3 ch. 11 §11.2.3;
// Hornus, Hoberock, Lefebvre and Hart 2005, "ZP+").
//
// Z-pass counts the volume faces between the near plane and the surface, so it is right only
// where the near-plane point of the pixel lies outside every volume. GPU Gems 3 §11.2.3 tests
// each caster's bounds against the near-plane rectangle and takes z-fail where it may shadow it
// (may_shadow_near_plane). ZP+ instead gives each pixel the count of the volume at that point
// first, and the z-pass draw of the sides adds the rest; Laine 2005 §3.3 applies it in the pixels
// that use z-pass only. Hornus et al. project the caster's light caps from the light onto the near
// plane; here the pre-fill is drawn from the volume's own cut by the near plane instead, made of
// the very edges the clipper gives the sides, so that it agrees with their draw on every pixel.
// Drawn with raster::CountRule::prefill (no depth test: front faces add their weight, back faces
// subtract it), it leaves that count in every pixel.
#pragma once

#include <array>
#include <cstdint>
#include <span>
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

// The pre-fill of one closed volume, from its own clip-space triangles (3 corners each): every
// triangle of it, drawn by the count pass or not, with its weight as drawn and, where `parts` is
// not empty, its part (each part of a volume counted by its own split plane is closed and needs
// its own pre-fill). A near-plane point's count in the volume is the winding number around it of
// the volume's cut by the near plane, and that cut is made of the edges the rasterizer's clipper
// adds to the triangles it cuts (raster::near_plane_cut); a fan of triangles from one point of the
// cut to each edge, weighted by minus its triangle's weight, winds that number. The apex is a point
// the eye sees (w > 0), so that the fan winds 0 behind the eye, where no volume reaches. Since its
// edges are the clipper's own, bit for bit, a pixel that a side's draw loses to the near plane the
// pre-fill counts, and the reverse: z-pass from the pre-fill counts exactly what the whole volume
// drawn without a depth test would (float planes of two computations of one line would disagree
// on the pixels they pass between). Appends the fan (depths kept inside the range: it carries
// counts), its weights and, where `out_parts` is not null, their parts; `apexes` is scratch.
void append_near_plane_prefill(std::span<const glm::vec4> triangles,
                               std::span<const std::int32_t> weights,
                               std::span<const std::uint32_t> parts, std::vector<glm::vec4>& out,
                               std::vector<std::int32_t>& out_weights,
                               std::vector<std::uint32_t>* out_parts,
                               std::vector<glm::vec4>& apexes);

}  // namespace shadowvol
