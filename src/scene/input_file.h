// The files a scene is read from (scene files, meshes, textures): whether one can be read, and if
// not, why, in the user's terms (no such file, a folder, a link loop, a path too long, no
// permission, not a regular file), before any reader opens it.
#pragma once

#include <filesystem>
#include <string_view>

#include "core/expected.h"

namespace shadowvol {

// The error names the path and says what it is not, `kind` being what was wanted ("mesh file").
Expected<void> check_input_file(const std::filesystem::path& path, std::string_view kind);

// Whether `name` is meant as a path rather than a built-in scene's name: it has a folder or an
// extension, or something by that name exists (however broken: a link loop, a path too long).
bool names_a_path(const std::filesystem::path& name);

// The extension in lower case, with its dot (".json"), so that X.JSON is read as x.json.
std::string lower_extension(const std::filesystem::path& path);

}  // namespace shadowvol
