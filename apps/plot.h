// shadowvol app: line charts as images, for `bench --suite spsv --plot` (Laine 2005 Fig. 6).
//
// Owns the layout of a grid of panels, each a set of series over frames with its own y scale
// (from 0, in round steps, labelled in K and M), a shared legend and a title. Pure: returns the
// image; apps/image_file.h writes it.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

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
};

struct Chart {
  std::string title;
  std::string x_label;  // under every panel
  int columns = 1;      // panels per row, filled row by row
  std::vector<PlotPanel> panels;
};

Image draw_chart(const Chart& chart);

}  // namespace shadowvol
