// shadowvol scene: scenes by what a person names them, and scene files (JSON), read into a Scene.
// Format: docs/scenes.md.
//
// Owns: finding a scene by name, file or mesh; parsing and checking a scene file. Every bad or
// missing value is refused with the file and the key path (`scene.json: objects[2].transform.scale:
// ...`); mesh files named in it are loaded relative to the scene file's folder.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "scene/mesh_io.h"
#include "scene/scene.h"

namespace shadowvol {

Expected<Scene> load_scene_file(const std::filesystem::path& path);

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

// A mesh file as a scene: an object per material the file gives (named FILE/MATERIAL, its base
// colour and opacity: below 1, a transparent caster), else one object in the stage's colour; the
// file's first camera and its lights where it has them, and default_stage's for what it lacks;
// default_stage's ground under it all.
Scene file_scene(const std::string& name, LoadedMesh loaded);

// Looks through the camera of that name among the file's (`render --camera NAME`); an unknown
// name is refused with the names there are.
Expected<void> use_camera(LoadedScene& loaded, const std::string& name);

}  // namespace shadowvol
