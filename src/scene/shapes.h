// shadowvol scene: procedural shapes, so that tests, benchmarks and built-in scenes need no files.
//
// Owns: meshes generated from a few parameters, deterministic for the same parameters.
#pragma once

#include <cstddef>

#include <glm/vec3.hpp>

#include "core/mesh.h"

namespace shadowvol {

// A closed, consistently oriented torus around the z axis whose tube radius ripples with
// `bumps` waves in each direction: non-convex, so its silhouette against most lights has many
// nested loops, like a detailed character rather than a sphere. `rings` x `segments` quads,
// 2 * rings * segments triangles, vertices in ring order (neighbouring triangles share
// vertices that sit close in memory, as in a mesh optimised for a vertex cache).
Mesh make_bumpy_torus(int rings, int segments, float major_radius = 1.0f,
                      float minor_radius = 0.35f, int bumps = 7);

// A torus with about `triangles` triangles (rings:segments about 2:1).
Mesh make_bumpy_torus_with(std::size_t triangles);

// The axis-aligned box [lo, hi], 12 outward-facing triangles on 8 shared vertices; without its
// top (+z) face when `with_top` is false: an open box with four boundary edges.
Mesh make_box(glm::vec3 lo, glm::vec3 hi, bool with_top = true);

// A square of side 2 * half_size in the y = 0 plane, centred on the origin, facing +y: two
// triangles, four boundary edges (a ground plane).
Mesh make_ground(float half_size);

}  // namespace shadowvol
