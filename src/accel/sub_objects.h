// shadowvol accel: sub-objects, the cells of a k-D tree over a spatially large mesh (Lloyd,
// Wendt, Govindaraju and Manocha 2004, "CC Shadow Volumes", §3: "We decompose spatially large
// objects into smaller sub-objects using a k-D tree to provide better localization").
//
// Owns: the split of one mesh, in its own space, built once per mesh and cell size. The cells
// partition the mesh's box; each is a leaf with two boxes:
//   - caster: the bounds of the faces it owns (each face belongs to the cell that holds its
//     centroid), whose volumes it casts; empty (lo > hi) where it owns none;
//   - receiver: the bounds of the mesh's surface within the cell (every face clipped to it), so
//     that a large face (a floor of two triangles) receives, per cell, only where it lies.
// Every point of the mesh lies in some leaf's receiver box, and every face in one leaf's caster
// box; the edges between faces of two leaves are merged when volumes are built (core/volume.h,
// VolumeClamp), so that no side is drawn twice.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/topology.h"
#include "core/volume.h"

namespace shadowvol {

struct SubObjects {
  struct Leaf {
    glm::vec3 caster_lo{INFINITY}, caster_hi{-INFINITY};
    glm::vec3 receiver_lo{INFINITY}, receiver_hi{-INFINITY};
    std::size_t faces = 0;  // how many it owns
    bool casts() const { return faces > 0; }
  };
  std::vector<std::uint32_t> face_leaf;  // per face
  // Per vertex, the leaves of the faces around it (core/volume.h, build_vertex_leaves).
  std::vector<std::uint32_t> vertex_leaf_offsets, vertex_leaves;
  std::vector<Leaf> leaves;  // cells with some of the mesh in them
  float cell = 0.0f;         // the cell size it was split for
};

// Splits the mesh's box at the middle of its longest side, the largest cell first, until every
// cell's longest side is at most `cell` or there are `max_leaves` cells; cells the surface misses
// are dropped. A mesh no longer than `cell` is one leaf. Deterministic.
SubObjects split_sub_objects(const Topology& topo, float cell, std::size_t max_leaves);

}  // namespace shadowvol
