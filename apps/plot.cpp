#include "plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <glm/vec2.hpp>

#include "canvas.h"
#include "image_file.h"

namespace shadowvol {
namespace {

constexpr double kText = 14.0, kTitle = 17.0;  // pixels
constexpr int kPanelWidth = 480, kPanelHeight = 300;
constexpr int kLeft = 70, kRight = 16, kTop = 34, kBottom = 56;  // plot area within a panel
constexpr int kHeader = 76;                                      // title and legend
const glm::vec3 kInk{0.15f, 0.15f, 0.15f}, kGrid{0.88f, 0.88f, 0.88f};

// The round step (1, 2 or 5 times a power of ten) that cuts `span` into about `parts` parts.
double nice_step(double span, int parts) {
  if (!(span > 0.0)) return 1.0;
  const double raw = span / parts, power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * power >= raw) return m * power;
  return 10.0 * power;
}

// 1500 -> "1.5K", 2000000 -> "2M": the tick labels of a count.
std::string short_count(double v) {
  const char* suffix = "";
  if (v >= 1e6) {
    v /= 1e6;
    suffix = "M";
  } else if (v >= 1e3) {
    v /= 1e3;
    suffix = "K";
  }
  char text[32];
  std::snprintf(text, sizeof text, v == std::floor(v) ? "%.0f%s" : "%.1f%s", v, suffix);
  return text;
}

void draw_panel(Canvas& canvas, int left, int top, const PlotPanel& panel,
                const std::string& x_label) {
  const double x0 = left + kLeft, x1 = left + kPanelWidth - kRight;
  const double y0 = top + kTop, y1 = top + kPanelHeight - kBottom;  // y0 top, y1 the axis
  canvas.text(x0, top + 8, panel.title, kText, kInk, Canvas::Align::left, true);
  std::size_t frames = 0;
  double highest = 0.0;
  for (const PlotSeries& s : panel.series) {
    frames = std::max(frames, s.values.size());
    for (double v : s.values) highest = std::max(highest, v);
  }
  const double y_step = nice_step(highest, 4);
  const double y_max = std::max(1.0, std::ceil(highest / y_step)) * y_step;
  const double x_max = frames > 1 ? double(frames - 1) : 1.0;
  auto px = [&](double frame) { return x0 + (x1 - x0) * frame / x_max; };
  auto py = [&](double value) { return y1 - (y1 - y0) * value / y_max; };
  for (double v = 0.0; v <= y_max * (1.0 + 1e-9); v += y_step) {
    const double y = std::round(py(v));
    canvas.fill_rect(x0, y, x1, y + 1, kGrid);
    canvas.text(x0 - 8, y - kText * 0.6, short_count(v), kText, kInk, Canvas::Align::right);
  }
  const bool labelled = !panel.x_ticks.empty();
  const double x_step = labelled ? 1.0 : std::max(1.0, nice_step(x_max, 5));
  for (double f = 0.0; f <= x_max + 1e-9; f += x_step) {
    const double x = std::round(px(f));
    const std::size_t i = static_cast<std::size_t>(f);
    canvas.fill_rect(x, y1, x + 1, y1 + 5, kInk);
    canvas.text(x, y1 + 8,
                labelled ? (i < panel.x_ticks.size() ? panel.x_ticks[i] : "") : short_count(f),
                kText, kInk, Canvas::Align::centre);
  }
  canvas.text((x0 + x1) / 2, y1 + 30, x_label, kText, kInk, Canvas::Align::centre);
  canvas.fill_rect(x0, y0, x0 + 1, y1 + 1, kInk);  // axes
  canvas.fill_rect(x0, y1, x1 + 1, y1 + 1, kInk);
  for (const PlotSeries& s : panel.series) {
    std::vector<glm::dvec2> points;
    for (std::size_t f = 0; f < s.values.size(); ++f)
      points.emplace_back(px(double(f)), py(s.values[f]));
    canvas.polyline(points, s.color, 2.5);
    for (const glm::dvec2& p : points) canvas.dot(p, 3.0, s.color);  // one frame still shows
  }
}

glm::ivec2 chart_size(const Chart& chart) {
  const int columns = std::max(1, chart.columns);
  const int rows = (static_cast<int>(chart.panels.size()) + columns - 1) / columns;
  return {columns * kPanelWidth + 20, kHeader + rows * kPanelHeight + 10};
}

void paint_chart(Canvas& canvas, const Chart& chart) {
  const int columns = std::max(1, chart.columns);
  canvas.text(20, 12, chart.title, kTitle, kInk, Canvas::Align::left, true);
  // The legend: every series name once, in order of first appearance.
  double x = 20;
  std::vector<std::string> named;
  for (const PlotPanel& panel : chart.panels)
    for (const PlotSeries& s : panel.series) {
      if (std::find(named.begin(), named.end(), s.name) != named.end()) continue;
      named.push_back(s.name);
      const double y = 44;
      canvas.fill_rect(x, y + kText / 2 - 2, x + 30, y + kText / 2 + 2, s.color);
      canvas.text(x + 38, y, s.name, kText, kInk);
      x += 38 + canvas.text_width(s.name, kText) + 28;
    }
  for (std::size_t i = 0; i < chart.panels.size(); ++i) {
    const int col = static_cast<int>(i) % columns, row = static_cast<int>(i) / columns;
    draw_panel(canvas, 10 + col * kPanelWidth, kHeader + row * kPanelHeight, chart.panels[i],
               chart.panels[i].x_label.empty() ? chart.x_label : chart.panels[i].x_label);
  }
}

}  // namespace

Image draw_chart(const Chart& chart) {
  const glm::ivec2 size = chart_size(chart);
  Canvas canvas = Canvas::image(size.x, size.y, glm::vec3(1.0f));
  paint_chart(canvas, chart);
  return canvas.pixels();
}

Expected<void> write_chart(const std::string& path, const Chart& chart) {
  if (!std::filesystem::path(path).extension().string().ends_with(".svg"))
    return write_png(path, draw_chart(chart));
  const glm::ivec2 size = chart_size(chart);
  Canvas canvas = Canvas::svg(path, size.x, size.y);
  paint_chart(canvas, chart);
  return canvas.finish();
}

Image labelled_heatmap(const Heatmap& map) {
  // The heatmap's own layout: two panels a gap of 4 apart, the scale's bar along the bottom.
  constexpr int kGap = 4, kAbove = 24, kBelow = 22;
  const int panel = (map.image.width - kGap) / 2;
  Canvas canvas =
      Canvas::image(map.image.width, map.image.height + kAbove + kBelow, glm::vec3(1.0f));
  canvas.draw_image(map.image, 0, kAbove);
  canvas.text(panel / 2.0, 4, "pixels processed per pixel", kText, kInk, Canvas::Align::centre);
  canvas.text(panel + kGap + panel / 2.0, 4, "pixels updated per pixel", kText, kInk,
              Canvas::Align::centre);
  const double below = kAbove + map.image.height + 3.0;
  char top[48];
  std::snprintf(top, sizeof top, "%.1f passes", map.passes_at_top);
  canvas.text(2, below, "0", kText, kInk);
  canvas.text(map.image.width / 2.0, below, "count-pass work per pixel of a tile", kText, kInk,
              Canvas::Align::centre);
  canvas.text(map.image.width - 2, below, top, kText, kInk, Canvas::Align::right);
  return canvas.pixels();
}

}  // namespace shadowvol
