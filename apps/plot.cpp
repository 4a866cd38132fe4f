#include "plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bitmap_font.h"

namespace shadowvol {
namespace {

constexpr int kScale = 2;  // text scale: 10x14 pixel glyphs
constexpr int kLine = kGlyphHeight * kScale;
constexpr int kPanelWidth = 480, kPanelHeight = 300;
constexpr int kLeft = 84, kRight = 16, kTop = 34, kBottom = 56;  // plot area within a panel
constexpr int kHeader = 3 * kLine + 40;                          // title and legend
const glm::vec3 kInk{0.15f, 0.15f, 0.15f}, kGrid{0.88f, 0.88f, 0.88f};

// A line `width` pixels thick, stepped pixel by pixel along its longer axis.
void line(Image& image, double x0, double y0, double x1, double y1, const glm::vec3& color,
          int width) {
  const int steps = static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0))));
  for (int i = 0; i <= steps; ++i) {
    const double t = steps == 0 ? 0.0 : double(i) / steps;
    const int x = static_cast<int>(std::lround(x0 + (x1 - x0) * t)) - width / 2;
    const int y = static_cast<int>(std::lround(y0 + (y1 - y0) * t)) - width / 2;
    fill_rect(image, x, y, x + width, y + width, color);
  }
}

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

void draw_panel(Image& image, int left, int top, const PlotPanel& panel,
                const std::string& x_label) {
  const int x0 = left + kLeft, x1 = left + kPanelWidth - kRight;
  const int y0 = top + kTop, y1 = top + kPanelHeight - kBottom;  // y0 top, y1 the axis
  draw_text(image, x0, top + 8, panel.title, kInk, kScale);
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
    const int y = static_cast<int>(std::lround(py(v)));
    fill_rect(image, x0, y, x1, y + 1, kGrid);
    const std::string label = short_count(v);
    draw_text(image, x0 - 8 - text_width(label, kScale), y - kLine / 2, label, kInk, kScale);
  }
  const double x_step = std::max(1.0, nice_step(x_max, 5));
  for (double f = 0.0; f <= x_max + 1e-9; f += x_step) {
    const int x = static_cast<int>(std::lround(px(f)));
    fill_rect(image, x, y1, x + 1, y1 + 5, kInk);
    const std::string label = short_count(f);
    draw_text(image, x - text_width(label, kScale) / 2, y1 + 9, label, kInk, kScale);
  }
  draw_text(image, (x0 + x1 - text_width(x_label, kScale)) / 2, y1 + 14 + kLine, x_label, kInk,
            kScale);
  fill_rect(image, x0, y0, x0 + 1, y1 + 1, kInk);  // axes
  fill_rect(image, x0, y1, x1 + 1, y1 + 1, kInk);
  for (const PlotSeries& s : panel.series)
    for (std::size_t f = 0; f < s.values.size(); ++f) {
      const double x = px(double(f)), y = py(s.values[f]);
      if (f > 0) line(image, px(double(f - 1)), py(s.values[f - 1]), x, y, s.color, 2);
      line(image, x, y, x, y, s.color, 5);  // a dot per frame: one frame still shows
    }
}

}  // namespace

Image draw_chart(const Chart& chart) {
  const int columns = std::max(1, chart.columns);
  const int rows = (static_cast<int>(chart.panels.size()) + columns - 1) / columns;
  Image image{columns * kPanelWidth + 20, kHeader + rows * kPanelHeight + 10, {}};
  image.rgba.assign(static_cast<std::size_t>(image.width) * image.height * 4, 255);  // white
  draw_text(image, 20, 16, chart.title, kInk, kScale);
  // The legend: every series name once, in order of first appearance.
  int x = 20;
  std::vector<std::string> named;
  for (const PlotPanel& panel : chart.panels)
    for (const PlotSeries& s : panel.series) {
      if (std::find(named.begin(), named.end(), s.name) != named.end()) continue;
      named.push_back(s.name);
      const int y = 24 + 2 * kLine;
      fill_rect(image, x, y + kLine / 2 - 2, x + 36, y + kLine / 2 + 2, s.color);
      draw_text(image, x + 46, y, s.name, kInk, kScale);
      x += 46 + text_width(s.name, kScale) + 40;
    }
  for (std::size_t i = 0; i < chart.panels.size(); ++i) {
    const int col = static_cast<int>(i) % columns, row = static_cast<int>(i) / columns;
    draw_panel(image, 10 + col * kPanelWidth, kHeader + row * kPanelHeight, chart.panels[i],
               chart.panels[i].x_label.empty() ? chart.x_label : chart.panels[i].x_label);
  }
  return image;
}

}  // namespace shadowvol
