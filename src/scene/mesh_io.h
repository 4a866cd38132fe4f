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
#include "scene/node_animation.h"
#include "scene/scene.h"

#include <glm/vec2.hpp>

namespace shadowvol {

// What a file says besides its triangles, by the names it gives them.
struct FileMaterial {
  std::string name;
  Material material;  // base colour (glTF base colour factor, else diffuse) and opacity
};
struct FileCamera {
  std::string name;
  Camera camera;  // in the file's root space, as its node hierarchy places it
};
struct FileLight {
  std::string name;
  SceneLight light;
};

struct LoadedMesh {
  Mesh mesh;
  // Per triangle of `mesh`, its material: an index into `materials`. Both empty where the file
  // gives no material of its own (only assimp's default).
  std::vector<std::uint32_t> triangle_material;
  std::vector<FileMaterial> materials;
  // Per corner of `mesh` (as mesh.indices), the shading normal: the file's vertex normal where
  // it gives one, else crease_normals' at kDefaultCreaseDegrees (core/shading_normals.h).
  std::vector<glm::vec3> corner_normals;
  // Per corner, the texture coordinates of the file's first set (v up), NaN where its mesh has
  // none; empty where no material has a texture.
  std::vector<glm::vec2> corner_uvs;
  // Where the file has animations: its node hierarchy with them as clips (in the file's order),
  // and per triangle of `mesh` the node whose instance of a mesh it belongs to. Null and empty
  // where the file has none.
  std::shared_ptr<const NodeHierarchy> hierarchy;
  std::vector<std::uint32_t> triangle_node;
  std::vector<FileCamera> cameras;    // perspective cameras, in the file's order
  std::vector<FileLight> lights;      // point, spot (as points) and directional lights
  std::size_t points_ignored = 0;     // point primitives in the file (not casters)
  std::size_t lines_ignored = 0;      // line primitives in the file (not casters)
  std::vector<std::string> warnings;  // for the caller to show; loading went on regardless
};

// Loads every triangle of every mesh instance in the file's node hierarchy, each transformed by
// the product of its node's transforms (so instanced meshes appear once per instance), into one
// Mesh in the file's root space as assimp presents it (assimp turns Z-up COLLADA files to Y up).
// Points and lines are counted and left out with a warning. Materials: the base colour (glTF's
// base colour factor; else the diffuse colour: OBJ/MTL Kd, COLLADA, FBX) and opacity (the
// material's opacity, MTL d; glTF's base colour alpha where its alpha mode is BLEND; 1 - glTF's
// transmission factor), linear RGB. Normals: the file's, turned by the inverse transpose of
// their node's transform, a crease angle's where it has none. Textures: the base colour map
// (glTF's base colour texture, else the diffuse one: MTL map_Kd, COLLADA, FBX), from a file
// beside the mesh or embedded in it; one that cannot be read is left out with a warning, the
// material keeping its colour. Cameras: placed by their nodes, the
// vertical field of view from assimp's horizontal one and the aspect. Lights (glTF
// KHR_lights_punctual, COLLADA, FBX): their colour, normalised to a largest channel of 1, at
// intensity 1 (files give intensities in units of their own); spot lights cast as point lights.
// Animations: each a clip of its channels' keys in seconds (sorted; a key of a non-finite value
// or time is an error), for nodes named in the hierarchy (channels for others are left out with
// a warning); the mesh stays at rest, and cameras and lights where the rest pose puts them.
// Skinning (bone weights) is not applied: skinned meshes stay in their bind pose.
// Errors (each names the file): missing or unreadable file, a file assimp cannot parse, a file with
// no triangles, and anything validate_mesh refuses (NaN/Inf coordinates, out-of-range indices,
// sizes past the limits).
//
// `progress`, if set, is called now and then with a fraction in [0, 1] while the file is read
// (as often as assimp reports, which for some formats is only at the start and the end).
using LoadProgress = std::function<void(float fraction)>;
Expected<LoadedMesh> load_mesh(const std::filesystem::path& path,
                               const LoadProgress& progress = {});

}  // namespace shadowvol
