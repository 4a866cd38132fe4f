// shadowvol scene: loading meshes from files (assimp).
//
// Owns: turning any file assimp reads (OBJ, PLY, glTF/GLB, COLLADA, FBX, 3DS, STL, IFC, ...)
// into one Mesh, with every node's transform applied, polygons triangulated, and every problem
// reported as a message that names the file. Never throws, never aborts on a bad file.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "core/mesh.h"

namespace shadowvol {

struct LoadedMesh {
  Mesh mesh;
  std::size_t points_ignored = 0;     // point primitives in the file (not casters)
  std::size_t lines_ignored = 0;      // line primitives in the file (not casters)
  std::vector<std::string> warnings;  // for the caller to show; loading went on regardless
};

// Loads every triangle of every mesh instance in the file's node hierarchy, each transformed by
// the product of its node's transforms (so instanced meshes appear once per instance), into one
// Mesh in the file's root space as assimp presents it (assimp turns Z-up COLLADA files to Y up).
// Points and lines are counted and left out with a warning. Errors (each names the file): missing
// or unreadable file, a file assimp cannot parse, a file with no triangles, and anything
// validate_mesh refuses (NaN/Inf coordinates, out-of-range indices, sizes past the limits).
//
// `progress`, if set, is called now and then with a fraction in [0, 1] while the file is read
// (as often as assimp reports, which for some formats is only at the start and the end).
using LoadProgress = std::function<void(float fraction)>;
Expected<LoadedMesh> load_mesh(const std::filesystem::path& path,
                               const LoadProgress& progress = {});

}  // namespace shadowvol
