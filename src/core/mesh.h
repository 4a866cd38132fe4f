// shadowvol core: Mesh, an indexed triangle list, and its validation.
//
// Owns: the in-memory form of a caster mesh as it arrives from a loader or a generator,
// before any welding. Pure: no I/O, no threads, no globals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "core/expected.h"

namespace shadowvol {

// A triangle soup with shared vertices: triangle t uses positions[indices[3t + k]], k = 0..2,
// counter-clockwise seen from the side its normal points to. Positions are in the mesh's own
// (object) space; any unit.
struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;

  std::size_t triangle_count() const { return indices.size() / 3; }
};

// Hard limits that keep every index and count of the later stages inside 32 bits with room for
// the flag bits they pack (topology stores a face index and its orientation in one uint32).
inline constexpr std::size_t kMaxTriangles = std::size_t{1} << 28;  // 268M triangles
inline constexpr std::size_t kMaxVertices = std::size_t{1} << 30;
// Face planes are stored in float: |coordinate| * |normal| must stay far below float's 3.4e38.
inline constexpr float kMaxCoordinate = 1e18f;

// Checks that a mesh can be used by every later stage. Returns an error naming `source` (a file
// name or object name, for the message) and the first problem found: no triangles, an index
// count that is not a multiple of 3, an index outside the position array, a NaN or infinite
// coordinate, a coordinate beyond +-kMaxCoordinate, or a size above kMaxTriangles / kMaxVertices.
// Degenerate triangles are not errors: the topology counts them and the volume generators handle
// them.
Expected<void> validate_mesh(const Mesh& mesh, std::string_view source);

}  // namespace shadowvol
