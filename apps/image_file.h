// The command line's image writers, shared by its subcommands and the viewer.
#pragma once

#include <string>

#include "core/expected.h"
#include "render/frame_outputs.h"
#include "render/renderer.h"

namespace shadowvol {

// Each writes row 0 at the top of the picture; the error names the path.
Expected<void> write_png(const std::string& path, const Image& image);      // 8-bit RGBA
Expected<void> write_png(const std::string& path, const GreyImage& image);  // 8-bit grey
// Portable float map, one channel ("Pf", little-endian, rows bottom to top as the format has it).
Expected<void> write_pfm(const std::string& path, const DepthImage& image);

}  // namespace shadowvol
