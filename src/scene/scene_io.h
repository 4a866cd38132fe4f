// shadowvol scene: scenes by what a person names them, and scene files (JSON), read into a Scene.
// Format: docs/scenes.md.
//
// Owns: finding a scene by name, file or mesh; parsing and checking a scene file. Every bad or
// missing value is refused with the file and the key path (`scene.json: objects[2].transform.scale:
// ...`); mesh files named in it are loaded relative to the scene file's folder.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "scene/mesh_io.h"
#include "scene/scene.h"

namespace shadowvol {

// `warnings`, if given, receives what reading the scene's mesh files passed over (mesh_io.h).
Expected<Scene> load_scene_file(const std::filesystem::path& path,
                                std::vector<std::string>* warnings = nullptr);

// What went wrong in a JSON file, for a person: the key path where it did, then nlohmann's
// detail without its "[json.exception...]" prefix. A number beyond a double (`1e400`) is named
// with its text; every other kind (syntax, type, range, iterator, other) says which it is.
std::string describe_json_error(const nlohmann::json::exception& e, const std::string& path);

struct LoadedScene {
  Scene scene;
  std::vector<std::string> warnings;  // what reading a mesh file passed over (mesh_io.h)
  std::vector<FileCamera> cameras;    // a mesh file's own cameras, by name (mesh_io.h)
};
// `stage:NAME`: the benchmark stage of NAME (scene/stage.h: sphere:N, cad or a mesh file); else
// a built-in scene by name (builtin_scene), else a scene file (.json) or a mesh file that exists
// (any format mesh_io reads), as file_scene makes it. An unknown name that names no file is
// refused with the built-in names listed.
Expected<LoadedScene> load_scene(const std::string& name);

// How file_objects makes a mesh file's objects.
struct FileObjectOptions {
  Material fallback;                 // for a file that gives no materials of its own
  std::optional<Material> material;  // given: every object takes it, not the file's
  int clip = 0;                      // the animation that moves the nodes; -1: none, all still
  double frames_per_second = kDefaultFramesPerSecond;
  glm::dmat4 placement{1.0};  // the file's root space -> world
};
// A mesh file's objects: an object per material its triangles use (named PREFIX/MATERIAL, with
// its base colour, opacity, texture where every corner has coordinates, and the file's normals),
// PREFIX alone where the file gives no materials or `material` replaces them. Where the clip moves
// nodes, the triangles of each moving node are objects of their own (PREFIX/NODE,
// PREFIX/NODE/MATERIAL) bound to it (node_animation.h), so that scene_at_frame moves them; a node
// flat at rest (scale 0) is drawn still, with a warning in `warnings`.
std::vector<SceneObject> file_objects(const std::string& prefix, const LoadedMesh& loaded,
                                      const FileObjectOptions& options,
                                      std::vector<std::string>& warnings);
// The index of the file's animation of that name; an unknown one is refused with the names.
Expected<int> find_clip(const LoadedMesh& loaded, const std::string& name);

// A mesh file as a scene: file_objects (the file's first animation moving its nodes) on
// default_stage's ground, the file's first camera and its lights where it has them, and
// default_stage's for what it lacks.
Scene file_scene(const std::string& name, const LoadedMesh& loaded,
                 std::vector<std::string>& warnings);

// Looks through the camera of that name among the file's (`render --camera NAME`); an unknown
// name is refused with the names there are.
Expected<void> use_camera(LoadedScene& loaded, const std::string& name);

}  // namespace shadowvol
