// The command line's PNG writer, shared by its subcommands and the viewer.
#pragma once

#include <string>

#include "core/expected.h"
#include "render/renderer.h"

namespace shadowvol {

// Writes 8-bit RGBA, row 0 at the top; the error names the path.
Expected<void> write_png(const std::string& path, const Image& image);

}  // namespace shadowvol
