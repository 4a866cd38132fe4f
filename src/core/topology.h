// shadowvol core: Topology, built once per mesh and read by every frame.
//
// Owns: welding vertices by position, the edge table (every undirected edge with every face
// that uses it and the direction in which it does), and the manifold report. The per-frame
// silhouette and volume code (core/volume.h) reads only the flat arrays here: face planes, the
// face pair of every regular edge, a CSR list for the rare irregular ones, no per-edge
// allocation (STYLE §2: the build form and the query form are different types).
// Pure: no I/O, no threads, no globals.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/mesh.h"

namespace shadowvol {

struct WeldOptions {
  // 0 welds vertices whose positions are bit-for-bit equal (+0 and -0 are equal); a positive
  // value also merges a vertex into the first earlier representative within this Euclidean
  // distance (greedy, in input order, so the result is deterministic).
  float epsilon = 0.0f;
};

// What `shadowvol inspect` prints. Counts are over the welded mesh.
struct TopologyReport {
  std::size_t input_vertices = 0;
  std::size_t vertices = 0;  // after welding
  std::size_t triangles = 0;
  std::size_t edges = 0;                 // undirected edges of non-collapsed triangles
  std::size_t boundary_edges = 0;        // used by exactly one triangle
  std::size_t nonmanifold_edges = 0;     // used by three or more triangles
  std::size_t inconsistent_edges = 0;    // used by two triangles in the same direction
  std::size_t degenerate_triangles = 0;  // zero area: a repeated welded vertex, or collinear
  std::size_t components = 0;            // sets of triangles connected through shared vertices
  // Every edge has exactly two triangles that use it in opposite directions: the mesh bounds a
  // solid and the standard (silhouette) generator is exact on it. Vertex-non-manifold meshes
  // (two solids touching at a vertex) still qualify: the silhouette method only needs edges.
  bool closed_manifold = false;
  // Parts (Topology's) wound outwards: closed (each of their edges has two faces, running it
  // opposite ways) and enclosing a positive volume. Seen from outside their bounds, every ray
  // enters such a part through a front (counter-clockwise) face first, so its back faces are
  // never the nearest surface.
  std::size_t parts_wound_outwards = 0;
};

// Face reference of an irregular edge: face index in the upper bits, and in bit 0 whether the
// face runs the edge against its stored direction (irregular_vertices[e][0] -> [1]).
inline constexpr std::uint32_t kReversedBit = 1u;
inline std::uint32_t face_of(std::uint32_t ref) { return ref >> 1; }
inline bool is_reversed(std::uint32_t ref) { return (ref & kReversedBit) != 0; }

using IndexPair = std::array<std::uint32_t, 2>;

// The plane of each face, (n, -n.a) with n = (b - a) x (c - a) scaled by a power of two into
// [0.5, 1) (an exact scaling), rounded to float: the light L (homogeneous) is in front iff
// dot(plane, L) > 0. Exact for small integer coordinates; elsewhere the sign can differ from the
// exact one only for a light within about 1e-7 of the plane (relative to the distance from the
// origin), where the face's own shadow is a wedge of that angle. Zero for zero-area faces.
// Structure of arrays: the facing pass walks all faces four or eight to a vector register.
struct FacePlanes {
  std::vector<float> x, y, z, w;

  std::size_t size() const { return x.size(); }
  glm::vec4 operator[](std::size_t f) const { return {x[f], y[f], z[f], w[f]}; }
  void push_back(const glm::vec4& p) {
    x.push_back(p.x);
    y.push_back(p.y);
    z.push_back(p.z);
    w.push_back(p.w);
  }
  void reserve(std::size_t n) {
    for (auto* v : {&x, &y, &z, &w}) v->reserve(n);
  }
};

struct Topology {
  // --- query form: what the per-frame pass reads ---
  std::vector<glm::vec3> positions;          // welded, in the mesh's space
  std::vector<std::uint32_t> face_vertices;  // 3 per input triangle, same order as the input
  FacePlanes face_planes;

  // Regular edges: one face, or two faces running the edge in opposite directions (every edge of
  // a consistently wound manifold, open or closed). Stored so that the per-frame test is one
  // comparison: edge_vertices[e] runs in the direction edge_faces[e][0] uses the edge;
  // edge_faces[e][1] runs it the other way, or is face_count() for a boundary edge (the facing
  // buffer's extra slot, always 0). edge_vertices is read only for edges that cast a quad.
  std::vector<IndexPair> edge_faces;
  std::vector<IndexPair> edge_vertices;

  // Irregular edges: two faces running the edge the same way, or three or more faces. Their
  // face references (face_of / is_reversed) are in CSR form.
  std::vector<IndexPair> irregular_vertices;     // lower vertex index first
  std::vector<std::uint32_t> irregular_offsets;  // irregular edges + 1 entries
  std::vector<std::uint32_t> irregular_faces;

  // Parts: the sets of faces joined through shared (welded) vertices, numbered 0 .. part_count()
  // - 1 in order of each one's first face. The part of every vertex a face uses, kNoPart for a
  // vertex no face uses. Every edge lies in one part, so each part's volume is a whole volume of
  // its own (core/volume.h: VolumeOptions::parts), and Laine 2005 §6's decomposition of a caster
  // into sub-objects can give each part its own split plane at no cost in side quads.
  static constexpr std::uint32_t kNoPart = 0xffffffffu;
  std::vector<std::uint32_t> vertex_part;
  std::size_t part_count() const { return report.components; }
  // Per part: 1 where it is wound outwards (TopologyReport::parts_wound_outwards).
  std::vector<std::uint8_t> part_wound_outwards;
  std::uint32_t part_of_face(std::size_t f) const { return vertex_part[face_vertices[3 * f]]; }

  // --- build products kept for callers ---
  std::vector<std::uint32_t> vertex_remap;  // input vertex index -> welded vertex index
  TopologyReport report;

  std::size_t face_count() const { return face_vertices.size() / 3; }
  std::size_t regular_edge_count() const { return edge_faces.size(); }
  std::size_t irregular_edge_count() const { return irregular_vertices.size(); }
  // Edges are numbered regular first, then irregular.
  std::size_t edge_count() const { return regular_edge_count() + irregular_edge_count(); }

  // Bytes of the flat arrays one side-quad pass reads in full: face planes, regular edge faces,
  // irregular edges. (Positions and edge_vertices are read only for edges that cast a quad.)
  std::size_t frame_bytes() const;
};

// Builds the topology of a mesh that passed validate_mesh (asserted in debug). Collapsed
// triangles (two corners welded together) keep their face index but add no edges.
Topology build_topology(const Mesh& mesh, const WeldOptions& options = {});

}  // namespace shadowvol
