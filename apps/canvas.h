// The command line's 2D drawing: charts, the heatmap's labels and the viewer's text, through
// cairo with a real font (DejaVu Sans, through fontconfig), antialiased, into an image or an SVG.
//
// Owns a cairo surface and context for one picture; coordinates in pixels (or SVG points), y
// down, colours sRGB in 0..1. Errors (an SVG file that cannot be written) come back from finish.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/expected.h"
#include "render/renderer.h"

namespace shadowvol {

class Canvas {
 public:
  enum class Align { left, centre, right };

  // A w x h picture in memory, filled with `background` (alpha 0: transparent).
  static Canvas image(int w, int h, const glm::vec3& background, float alpha = 1.0f);
  // A w x h SVG document written to `path` by finish().
  static Canvas svg(const std::string& path, int w, int h);
  Canvas(Canvas&&) noexcept;
  Canvas& operator=(Canvas&&) noexcept;
  ~Canvas();

  void fill_rect(double x0, double y0, double x1, double y1, const glm::vec3& color,
                 float alpha = 1.0f);
  void polyline(std::span<const glm::dvec2> points, const glm::vec3& color, double width);
  void dot(const glm::dvec2& at, double radius, const glm::vec3& color);
  // Text of `size` pixels (the em), its top at y and its left, centre or right at x.
  void text(double x, double y, std::string_view text, double size, const glm::vec3& color,
            Align align = Align::left, bool bold = false);
  double text_width(std::string_view text, double size, bool bold = false);
  // An image (row 0 at the top) with its top-left corner at (x, y).
  void draw_image(const Image& image, double x, double y);

  // An image canvas's pixels (8-bit RGBA, not premultiplied).
  Image pixels();
  // Ends the picture: an SVG is written out; any cairo error is reported with the path.
  Expected<void> finish();

 private:
  struct State;
  explicit Canvas(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace shadowvol
