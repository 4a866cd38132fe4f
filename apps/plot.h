// shadowvol app: line charts, for `bench --plot` and the suites' (Laine 2005 Fig. 6).
//
// Owns the layout of a grid of panels, each a set of series over frames with its own y scale
// (from 0, in round steps, labelled in K and M), a shared legend and a title, drawn with cairo
// (canvas.h) as an image or straight to an SVG.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/expected.h"
#include "render/heatmap.h"
#include "render/renderer.h"

namespace shadowvol {

struct PlotSeries {
  std::string name;            // in the legend; series of the same name share it
  glm::vec3 color;             // sRGB, 0..1
  std::vector<double> values;  // one per frame, >= 0
};

struct PlotPanel {
  std::string title;
  std::vector<PlotSeries> series;
  std::string x_label;  // under this panel; empty: the chart's
  // A label per point (x = 0, 1, ...: lamps, buildings, slices), each shown; empty: the points'
  // indices (frames), in round steps.
  std::vector<std::string> x_ticks = {};
};

struct Chart {
  std::string title;
  std::string x_label;  // under every panel
  int columns = 1;      // panels per row, filled row by row
  std::vector<PlotPanel> panels;
};

Image draw_chart(const Chart& chart);
// An SVG where `path` ends in .svg, else a PNG; the error names the path.
Expected<void> write_chart(const std::string& path, const Chart& chart);

// The heatmap (render/heatmap.h) with its words: each panel's title above it and the scale's
// ends under its bar ("0" and the passes per pixel its brightest colour means).
Image labelled_heatmap(const Heatmap& map);

}  // namespace shadowvol
