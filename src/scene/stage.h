// shadowvol scene: the benchmark stage (`bench --stage`), one mesh on one ground under one light,
// set out from the mesh's bounds alone so that figures compare across runs and tools, and the
// meshes it is named for besides files: UV spheres and a CAD-like assembly.
//
// The stage, for a mesh of bounds centre c and half-diagonal r: a ground quad just under the
// bounds (y = min y - 0.001 r), half-size 4 r, centred under c; one point light at
// c + r (1.5, 3, 1); the eye at c + r (0, 1.2, 3) looking at c, up +y, vertical field of view
// 50 degrees, near plane 0.05 r. Animated (scene_at_frame, `bench --animate`), the mesh slides
// along +x by kStageStepPerFrame r a frame over the still ground: its volume, and any ray
// tracer's acceleration structure, must be rebuilt every frame.
#pragma once

#include <string>
#include <string_view>

#include "core/expected.h"
#include "core/mesh.h"
#include "scene/scene.h"

namespace shadowvol {

inline constexpr float kStageStepPerFrame = 0.01f;

// The stage around `mesh` (named `name`). The mesh must have a vertex (asserted).
Scene stage_scene(std::string name, Mesh mesh);

// `sphere:N`: a UV sphere of 2 N^2 triangles (N + 1 rings of N segments, N in 3 .. 4096),
// radius 1, centred at (0, 1.2, 0).
Mesh stage_sphere(int n);

// A CAD-like assembly of 152,892 triangles in over a thousand parts, deterministic: a cast base
// (its top a grid of quads), brackets of two boxes sharing part of a face (coincident faces),
// panels standing on the base with their edges across its grid (T-junctions), heat sinks of fins,
// open pipes bent along arcs (no end caps), open domes, and hundreds of bolts (hex heads on
// shafts) — the open, self-touching parts of a CAD export.
Mesh make_cad_assembly();

// The stage for a name: `sphere:N`, `cad` (make_cad_assembly), or a mesh file any format
// mesh_io reads. Errors name the problem.
Expected<Scene> load_stage(const std::string& name);

}  // namespace shadowvol
