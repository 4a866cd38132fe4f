// shadowvol core: Topology, built once per mesh and read by every frame.
//
// Owns: welding vertices by position, the edge table (every undirected edge with every face
// that uses it and the direction in which it does), and the manifold report. The per-frame
// silhouette and volume code (core/volume.h) reads only the flat arrays here: CSR adjacency,
// no per-edge allocation (STYLE §2: the build form and the query form are different types).
// Pure: no I/O, no threads, no globals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

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
  std::size_t vertices = 0;              // after welding
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
};

// Edge face reference: face index in the upper 31 bits, and in bit 0 whether the face traverses
// the edge against its canonical direction (edge_vertices[2e] -> edge_vertices[2e+1]).
inline constexpr std::uint32_t kReversedBit = 1u;
inline std::uint32_t face_of(std::uint32_t ref) { return ref >> 1; }
inline bool is_reversed(std::uint32_t ref) { return (ref & kReversedBit) != 0; }

struct Topology {
  // --- query form: what the per-frame pass reads ---
  std::vector<glm::vec3> positions;           // welded, in the mesh's space
  std::vector<std::uint32_t> face_vertices;   // 3 per input triangle, same order as the input
  std::vector<std::uint32_t> edge_vertices;   // 2 per edge, canonical direction: first < second
  std::vector<std::uint32_t> edge_face_offsets;  // edges + 1 entries; CSR into edge_faces
  std::vector<std::uint32_t> edge_faces;         // face references, see face_of / is_reversed

  // --- build products kept for callers ---
  std::vector<std::uint32_t> vertex_remap;  // input vertex index -> welded vertex index
  TopologyReport report;

  std::size_t face_count() const { return face_vertices.size() / 3; }
  std::size_t edge_count() const { return edge_vertices.size() / 2; }

  // Bytes of the flat arrays one volume-generation pass reads (positions, faces, edge table).
  std::size_t frame_bytes() const;
};

// Builds the topology of a mesh that passed validate_mesh (asserted in debug). Collapsed
// triangles (two corners welded together) keep their face index but add no edges.
Topology build_topology(const Mesh& mesh, const WeldOptions& options = {});

}  // namespace shadowvol
