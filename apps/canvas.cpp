#include "canvas.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "output_file.h"

namespace shadowvol {

struct Canvas::State {
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;
  std::string path;  // an SVG's
  std::string svg;   // its bytes, written to `path` whole by finish()
  int width = 0, height = 0;
  ~State() {
    if (cr != nullptr) cairo_destroy(cr);
    if (surface != nullptr) cairo_surface_destroy(surface);
  }
};

namespace {

constexpr const char* kFont = "DejaVu Sans";

void set_colour(cairo_t* cr, const glm::vec3& c, float alpha = 1.0f) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

void set_font(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

}  // namespace

Canvas::Canvas(std::unique_ptr<State> state) : state_(std::move(state)) {}
Canvas::Canvas(Canvas&&) noexcept = default;
Canvas& Canvas::operator=(Canvas&&) noexcept = default;
Canvas::~Canvas() = default;

Canvas Canvas::image(int w, int h, const glm::vec3& background, float alpha) {
  auto s = std::make_unique<State>();
  s->width = w, s->height = h;
  s->surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
  s->cr = cairo_create(s->surface);
  set_colour(s->cr, background, alpha);
  cairo_set_operator(s->cr, CAIRO_OPERATOR_SOURCE);
  cairo_paint(s->cr);
  cairo_set_operator(s->cr, CAIRO_OPERATOR_OVER);
  return Canvas(std::move(s));
}

Canvas Canvas::svg(const std::string& path, int w, int h) {
  auto s = std::make_unique<State>();
  s->width = w, s->height = h;
  s->path = path;
  s->surface = cairo_svg_surface_create_for_stream(
      [](void* to, const unsigned char* data, unsigned int size) {
        static_cast<std::string*>(to)->append(reinterpret_cast<const char*>(data), size);
        return CAIRO_STATUS_SUCCESS;
      },
      &s->svg, w, h);
  s->cr = cairo_create(s->surface);
  set_colour(s->cr, glm::vec3(1.0f));
  cairo_paint(s->cr);
  return Canvas(std::move(s));
}

void Canvas::fill_rect(double x0, double y0, double x1, double y1, const glm::vec3& color,
                       float alpha) {
  set_colour(state_->cr, color, alpha);
  cairo_rectangle(state_->cr, x0, y0, x1 - x0, y1 - y0);
  cairo_fill(state_->cr);
}

void Canvas::polyline(std::span<const glm::dvec2> points, const glm::vec3& color, double width) {
  if (points.size() < 2) return;
  cairo_t* cr = state_->cr;
  cairo_move_to(cr, points[0].x, points[0].y);
  for (std::size_t i = 1; i < points.size(); ++i) cairo_line_to(cr, points[i].x, points[i].y);
  set_colour(cr, color);
  cairo_set_line_width(cr, width);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_stroke(cr);
}

void Canvas::dot(const glm::dvec2& at, double radius, const glm::vec3& color) {
  cairo_new_sub_path(state_->cr);
  cairo_arc(state_->cr, at.x, at.y, radius, 0.0, 6.283185307179586);
  set_colour(state_->cr, color);
  cairo_fill(state_->cr);
}

double Canvas::text_width(std::string_view text, double size, bool bold) {
  set_font(state_->cr, size, bold);
  const std::string s(text);
  cairo_text_extents_t e;
  cairo_text_extents(state_->cr, s.c_str(), &e);
  return e.x_advance;
}

void Canvas::text(double x, double y, std::string_view text, double size, const glm::vec3& color,
                  Align align, bool bold) {
  cairo_t* cr = state_->cr;
  set_font(cr, size, bold);
  const std::string s(text);
  cairo_font_extents_t font;
  cairo_font_extents(cr, &font);
  const double width = text_width(text, size, bold);
  const double left = align == Align::left ? x : align == Align::centre ? x - width / 2 : x - width;
  cairo_move_to(cr, left, y + font.ascent);
  set_colour(cr, color);
  cairo_show_text(cr, s.c_str());
}

void Canvas::draw_image(const Image& image, double x, double y) {
  cairo_surface_t* src = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, image.width, image.height);
  cairo_surface_flush(src);
  unsigned char* data = cairo_image_surface_get_data(src);
  const int stride = cairo_image_surface_get_stride(src);
  for (int row = 0; row < image.height; ++row)
    for (int col = 0; col < image.width; ++col) {
      const std::uint8_t* p = &image.rgba[4 * (std::size_t(row) * image.width + col)];
      const std::uint32_t a = p[3];
      // Premultiplied, native-endian 0xAARRGGBB.
      const std::uint32_t argb =
          a << 24 | (p[0] * a / 255) << 16 | (p[1] * a / 255) << 8 | (p[2] * a / 255);
      std::memcpy(data + std::size_t(row) * stride + 4 * std::size_t(col), &argb, 4);
    }
  cairo_surface_mark_dirty(src);
  cairo_set_source_surface(state_->cr, src, x, y);
  cairo_paint(state_->cr);
  cairo_surface_destroy(src);
}

Image Canvas::pixels() {
  cairo_surface_flush(state_->surface);
  Image out{state_->width, state_->height, {}};
  out.rgba.resize(std::size_t(out.width) * out.height * 4);
  const unsigned char* data = cairo_image_surface_get_data(state_->surface);
  const int stride = cairo_image_surface_get_stride(state_->surface);
  for (int row = 0; row < out.height; ++row)
    for (int col = 0; col < out.width; ++col) {
      std::uint32_t argb;
      std::memcpy(&argb, data + std::size_t(row) * stride + 4 * std::size_t(col), 4);
      const std::uint32_t a = argb >> 24;
      std::uint8_t* p = &out.rgba[4 * (std::size_t(row) * out.width + col)];
      const auto straight = [a](std::uint32_t c) {
        return static_cast<std::uint8_t>(
            a == 0 ? 0 : std::min<std::uint32_t>(255, (c * 255 + a / 2) / a));
      };
      p[0] = straight((argb >> 16) & 0xff);
      p[1] = straight((argb >> 8) & 0xff);
      p[2] = straight(argb & 0xff);
      p[3] = static_cast<std::uint8_t>(a);
    }
  return out;
}

Expected<void> Canvas::finish() {
  cairo_surface_finish(state_->surface);
  const cairo_status_t status = cairo_surface_status(state_->surface);
  if (status != CAIRO_STATUS_SUCCESS)
    return make_error((state_->path.empty() ? std::string("the picture") : state_->path) +
                      ": cannot be drawn (" + cairo_status_to_string(status) + ")");
  if (!state_->path.empty()) return write_file(state_->path, state_->svg);
  return {};
}

}  // namespace shadowvol
