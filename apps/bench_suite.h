// shadowvol app: the measurement suites of `bench --suite`.
//
// spsv: Laine 2005's measurement (Table 1) on our scenes. Every scene of the suite (knight,
// knights16, tree, tree-decomposed) with each method (zp+db, zf+db, spsv) over frames 0 .. N-1
// of its animation, in the software rasterizer: per frame, the tiles processed (touched by a
// volume primitive), the tiles not culled, the pixels processed and the pixels updated (count
// changes), and the count passes' time.
//
// city: hierarchical occlusion culling (GPU Gems 3 ch. 11 §11.3.3) on the built-in city at four
// sizes, its street and above paths, without culling and with --occlusion both.
//
// cc: CC shadow volumes' measurement (Lloyd et al. 2004 §4, Fig. 7 to 9). The corridor and the
// robots over their paths with standard volumes (sv), culling only (cull), and culling with
// continuous (ccc), discrete (ccd) and both clampings (cc): per frame the fill (pixels the
// volumes touch with the depth test off), the stencil writes and the shadow-volume time
// (building and counting the volumes), with culling's and clamping's own times beside; then the
// slice sweep of discrete clamping on the corridor (Fig. 9).
#pragma once

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "backend/backend.h"
#include "output_file.h"
#include "plot.h"
#include "render/renderer.h"

namespace shadowvol {

// Writes text to a file whole (write_file), or to standard output for "-".
inline Expected<void> write_text(const std::string& path, const std::string& text) {
  if (path != "-") return write_file(path, text);
  std::cout << text << std::flush;
  if (!std::cout) return make_error("standard output: cannot be written");
  return {};
}

// A suite's renderer of `backend` (and its gl settings) for frames of `options`, or null with the
// error on stderr.
std::unique_ptr<Renderer> suite_renderer(Backend backend, const gl::GlSettings& gl,
                                         const RenderOptions& options);

// Writes a suite's JSON, CSV and plot (`what` it shows, said on `table`) where their paths are
// not empty; false, with the error on stderr, when one cannot be written.
bool write_suite_outputs(const std::string& json_path, const std::string& json,
                         const std::string& csv_path, const std::string& csv,
                         const std::string& plot_path, const Chart& chart, const char* what,
                         std::FILE* table);

template <class T>
T total(const std::vector<T>& v) {
  T sum{};
  for (const T& x : v) sum += x;
  return sum;
}

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

struct CcSuiteOptions {
  int frames = 48;                  // the corridor's walk end to end
  int width = 1280, height = 1024;  // the paper's resolution
  Method method = Method::automatic;
  Backend backend = Backend::soft;
  gl::GlSettings gl;
  int slices = kDefaultSlices;  // ccd's and cc's (the slice sweep sets its own)
  int light_view_size = 512;
  std::string json, csv, plot;  // as SuiteOptions's
};

struct CitySuiteOptions {
  int frames = 8;
  int width = 1280, height = 720;
  Method method = Method::automatic;
  Backend backend = Backend::soft;
  gl::GlSettings gl;
  std::vector<int> sizes = {1000, 2500, 5000, 10000};  // buildings, smallest first
  std::string json, csv, plot;                         // as SuiteOptions's
};

// Runs `bench --suite city`: per city size and path (street, above), without and with occlusion
// culling (both): fill, frame time, shadow-volume time, objects and volumes drawn; the goals and
// the scaling. Returns the process's exit status.
int run_city_suite(const CitySuiteOptions& options);

struct LightsSuiteOptions {
  int frames = 5;
  int width = 1920, height = 1080;
  Method method = Method::automatic;
  Backend backend = Backend::soft;
  gl::GlSettings gl;
  std::vector<int> lamps = {1, 2, 4, 8, 16, 24, 32, 48};
  std::string json, csv, plot;  // as SuiteOptions's (no csv is written)
};

// Runs `bench --suite lights`: per lamp count, the night street's frame time with its lamps'
// ranges and with them lifted, in turn; a table, and JSON and a plot where asked. Returns the
// process's exit status.
int run_lights_suite(const LightsSuiteOptions& options);

// Runs `bench --suite cc`: prints the table of totals, the ratios against the goals and the slice
// sweep, writes the files. Returns the process's exit status.
int run_cc_suite(const CcSuiteOptions& options);

}  // namespace shadowvol
