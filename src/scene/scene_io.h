// shadowvol scene: scene files (JSON), read into a Scene. Format: docs/scenes.md.
//
// Owns: parsing and checking a scene file. Every bad or missing value is refused with the file
// and the key path (`scene.json: objects[2].transform.scale: ...`); mesh files named in it are
// loaded relative to the scene file's folder.
#pragma once

#include <filesystem>

#include "core/expected.h"
#include "scene/scene.h"

namespace shadowvol {

Expected<Scene> load_scene_file(const std::filesystem::path& path);

}  // namespace shadowvol
