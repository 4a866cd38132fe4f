// shadowvol core: procedural shapes, so that tests, benchmarks and built-in scenes need no files.
//
// Owns: meshes generated from a few parameters, deterministic for the same parameters.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

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

// A closed tube from a to b: `sides` sides, radius ra at a and rb at b, each end closed by a fan
// around a centre vertex (the centres are vertices 0 and 1), outward-facing.
Mesh make_tube(glm::vec3 a, glm::vec3 b, float ra, float rb, int sides);

// A closed sphere of `rings` bands and `segments` slices, outward-facing.
Mesh make_sphere(glm::vec3 centre, float radius, int rings, int segments);

// Appends `part` to `mesh`, its indices moved past mesh's vertices.
void append_mesh(Mesh& mesh, const Mesh& part);

// The connected components of a mesh (triangles that share a vertex index, transitively; with
// `join_equal_positions`, also vertices at exactly the same position, for files that repeat a
// vertex per face), each as a mesh of its own, in the order of their first triangles.
std::vector<Mesh> connected_parts(const Mesh& mesh, bool join_equal_positions = false);

// A standing armoured figure about 2 units tall, feet on y = 0, facing +z: legs, torso, arms,
// shoulders, head and crest, a sword and a shield, each a closed part (some overlapping), about
// 900 triangles. Dense and self-shadowing, in the spirit of Laine 2005's KNIGHT.
Mesh make_knight();

// A robot about 2 units tall, feet on y = 0, facing +z: box feet, tube legs, a box torso with a
// chest plate, tube arms ending in sphere hands, a sphere head with an antenna, each a closed
// part, about 1000 triangles. The crowd of CC shadow volumes' robot scene (Lloyd et al. 2004
// Fig. 6) is made of it.
Mesh make_robot();

// A roof truss across x in [-half_span, half_span], its bottom chord along the x axis: a Warren
// truss of triangular section, two top chords `depth` apart (z = +-depth / 2) at y = `height`
// over one bottom chord (each chord a tube per panel), diagonals zig-zagging on both slanted
// faces between its `panels` panel points, and ties across the top at every top panel point;
// every member a closed tube of
// radius `radius` and `sides` sides (4 sides triangles each). The members cross at the nodes (a
// closed mesh, self-intersecting), as CC shadow volumes' corridor trusses (Fig. 1) do.
Mesh make_truss(float half_span, float height, float depth, int panels, float radius, int sides);

// A tree about 4 units tall, its root at the origin: a trunk and three levels of branches, each
// a closed tapered tube, and open leaves (single quads) fanned out at the tips of the last
// level, sharing the tip's centre vertex so that a branch and its leaves form one connected
// part. The same seed gives the same tree. In the spirit of Laine 2005's TREE: a large caster
// whose volumes cover much of the screen.
Mesh make_tree(std::uint32_t seed = 7);

}  // namespace shadowvol
