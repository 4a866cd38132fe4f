// shadowvol render: pictures of where the count passes work (Laine 2005 Fig. 1), so that a
// person can see where a method saves.
#pragma once

#include <cstdint>

#include "render/renderer.h"

namespace shadowvol {

struct Heatmap {
  Image image;
  // The scale: the brightest colour means this many passes per pixel of a tile (at least 1).
  double passes_at_top = 1.0;
};

// Two panels side by side over a dimmed grey copy of the frame: on the left, how many times the
// count passes processed each pixel of a tile (pixels processed / pixels of the tile); on the
// right, how many times they changed its count (pixels updated / pixels). Black is none, then
// through purple and orange to pale yellow at `passes_at_top`, the larger panel's maximum, which
// both panels share; a bar along the bottom shows the scale. The frame must carry tile_work
// (RenderOptions::tile_work).
Heatmap tile_work_heatmap(const Frame& frame);

}  // namespace shadowvol
