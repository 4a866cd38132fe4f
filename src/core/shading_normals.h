// shadowvol core: the normals the lit pass shades with, one per triangle corner.
//
// Smooth shading changes only how a surface is lit, never where shadows fall: the shadow masks
// stay exactly the geometry's (every method's and the reference's). A corner normal is in the
// mesh's own space, unit length, or zero where the corner has no direction (a face of no area).
// Pure: no I/O, no threads, no globals.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "core/mesh.h"

namespace shadowvol {

inline constexpr float kDefaultCreaseDegrees = 30.0f;

// Per corner (3 per triangle, in the order of mesh.indices): the mean of the normals of the faces
// around its point (its vertex, and every vertex at the same position) that reach its face across
// edges where neighbours meet at less than `crease_degrees`, each weighted by its angle at the
// point (Thürmer and Wüthrich 1998: a polygon weighs the same however it was cut into
// triangles). A surface is smooth across edges flatter than the crease and keeps its edges where
// it folds more (a cube stays a cube), however far the faces around a point turn in all. Faces
// wound against their neighbours (open or non-manifold meshes) meet them at more than any crease
// under 90 degrees and keep their own side. Degenerate faces give zero normals and join nothing.
// Work: a sort of the positions, then a sort of each point's edges. crease_degrees in [0, 180].
std::vector<glm::vec3> crease_normals(const Mesh& mesh, float crease_degrees);

// The shadow terminator of smooth shading. A face turned from a light lies in its own shadow
// (every method's and the reference's: shadows are the geometry's), yet the normals of its
// corners may lean towards the light, by up to the sine of their angle to the faces around them.
// On a coarse mesh the light would then stop in a step, zigzagging along the triangles. The lit
// pass shades with (cos(normal, light) - offset) / (1 - offset), the offset interpolated like
// the normal, so that the light fades to nothing where a face's neighbour turns away.
// A corner's offset: the largest sine of the angle between its normal and a face around its
// point on the same side, at most kMaxTerminatorOffset. Flat shading has offset 0 (unchanged).
inline constexpr float kMaxTerminatorOffset = 0.9f;
struct ShadingNormals {
  std::vector<glm::vec3> normals;  // per corner, unit length (or zero: no direction)
  std::vector<float> offsets;      // per corner, in [0, kMaxTerminatorOffset]
};
// Pairs per-corner normals with their terminator offsets (all 0 where normals has not one per
// corner of mesh, whose shading the backends then take as flat).
ShadingNormals make_shading_normals(const Mesh& mesh, std::vector<glm::vec3> normals);

}  // namespace shadowvol
