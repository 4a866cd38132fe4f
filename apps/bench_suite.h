// shadowvol app: `bench --suite spsv`, Laine 2005's measurement (Table 1) on our scenes.
//
// Every scene of the suite (knight, knights16, tree, tree-decomposed) with each method (zp+db,
// zf+db, spsv) over frames 0 .. N-1 of its animation, in the software rasterizer: per frame,
// the tiles processed (touched by a volume primitive), the tiles not culled, the pixels
// processed and the pixels updated (count changes), and the count passes' time.
#pragma once

#include <string>

#include "render/renderer.h"

namespace shadowvol {

struct SuiteOptions {
  int frames = 10;
  int width = 1024, height = 768;  // the paper's resolution
  std::string json;  // a file for the totals and per-frame series as JSON; "-" for stdout
  std::string csv;   // a file for one row per scene, method and frame
  std::string plot;  // a PNG of every counter's per-frame series, per scene and method
  // Laine 2005 §7 extrudes every volume to the scene's extent, for all three methods alike.
  Extrusion extrusion = Extrusion::bounded;
};

// Runs the suite, prints a table of totals and ratios against the goals, writes the files.
// Returns the process's exit status.
int run_spsv_suite(const SuiteOptions& options);

}  // namespace shadowvol
