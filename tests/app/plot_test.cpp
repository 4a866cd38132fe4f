// The app's charts: text drawn where it is placed, in a real font; a chart draws its series where
// their values put them, as a PNG or an SVG.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "canvas.h"
#include "plot.h"

namespace shadowvol {
namespace {

// The columns and rows that hold ink (any channel below 128 on white).
struct Ink {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1, pixels = 0;
};
Ink ink_of(const Image& image) {
  Ink ink;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = &image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)];
      if (p[0] >= 128 && p[1] >= 128 && p[2] >= 128) continue;
      ++ink.pixels;
      ink.x0 = std::min(ink.x0, x), ink.x1 = std::max(ink.x1, x);
      ink.y0 = std::min(ink.y0, y), ink.y1 = std::max(ink.y1, y);
    }
  return ink;
}

TEST(Canvas, TextLandsWhereItIsPlacedAtItsSize) {
  Canvas left = Canvas::image(200, 40, glm::vec3(1.0f));
  left.text(10, 5, "Frame 42", 20, glm::vec3(0.0f));
  const Ink a = ink_of(left.pixels());
  ASSERT_GT(a.pixels, 50);
  EXPECT_GE(a.x0, 10);
  EXPECT_LE(a.x0, 13);
  EXPECT_GE(a.y0, 5);
  EXPECT_LE(a.y1, 5 + 24);     // within its line
  EXPECT_GT(a.y1 - a.y0, 10);  // capitals of a 20-pixel font
  const double width = left.text_width("Frame 42", 20);
  EXPECT_NEAR(a.x1 - a.x0, width, 8.0);  // the ink spans the advance, less the bearings
  EXPECT_GT(left.text_width("Frame 4242", 20), width);
  // Right-aligned at x: the ink ends there.
  Canvas right = Canvas::image(200, 40, glm::vec3(1.0f));
  right.text(190, 5, "Frame 42", 20, glm::vec3(0.0f), Canvas::Align::right);
  const Ink b = ink_of(right.pixels());
  EXPECT_LE(b.x1, 190);
  EXPECT_GE(b.x1, 186);
  // A transparent canvas keeps its alpha: only the text is opaque.
  Canvas clear = Canvas::image(40, 20, glm::vec3(0.0f), 0.0f);
  clear.fill_rect(0, 0, 10, 10, glm::vec3(1.0f, 0.0f, 0.0f));
  const Image px = clear.pixels();
  EXPECT_EQ(px.rgba[0], 255);
  EXPECT_EQ(px.rgba[3], 255);
  EXPECT_EQ(px.rgba[4 * (15 * 40 + 30) + 3], 0);
}

TEST(Chart, WritesAnSvgOrSaysWhyNot) {
  const Chart chart{"title", "frame", 1, {{"panel", {{"a", {1, 0, 0}, {1.0, 2.0}}}, {}}}};
  const auto path = std::filesystem::temp_directory_path() / "shadowvol_chart.svg";
  ASSERT_TRUE(write_chart(path.string(), chart).ok());
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  EXPECT_NE(text.str().find("<svg"), std::string::npos);
  EXPECT_NE(text.str().find("<path"), std::string::npos);  // lines and glyph outlines
  const auto bad = write_chart("/nonexistent/chart.svg", chart);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message.rfind("/nonexistent/chart.svg: cannot be written", 0), 0u)
      << bad.error().message;
}

// A series that rises puts its last point higher on the image than its first, in its colour,
// two panels side by side make the chart about twice as wide as one, and a panel may have an x
// label of its own.
TEST(Chart, DrawsEachSeriesInItsColourWhereItsValuesFall) {
  const glm::vec3 red{1.0f, 0.0f, 0.0f};
  Chart one{"title", "frame", 1, {{"panel", {{"rising", red, {0.0, 10.0, 20.0, 40.0}}}, {}}}};
  const Image image = draw_chart(one);
  int first_y = -1, last_y = -1, lo_x = image.width, hi_x = -1;
  for (int y = image.height / 4; y < image.height; ++y)  // below the title and the legend
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = &image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)];
      if (p[0] < 230 || p[1] > 40 || p[2] > 40) continue;  // red, antialiased edges aside
      if (x < lo_x) lo_x = x, first_y = y;
      if (x > hi_x) hi_x = x, last_y = y;
    }
  ASSERT_GE(hi_x, 0) << "no pixel in the series' colour";
  EXPECT_LT(last_y, first_y) << "the last value, the largest, is drawn higher";
  EXPECT_GT(hi_x - lo_x, image.width / 2);  // the series spans the plot's width
  Chart two = one;
  two.columns = 2;
  two.panels.push_back(two.panels[0]);
  EXPECT_NEAR(draw_chart(two).width, 2 * image.width, 40);
  EXPECT_EQ(draw_chart(two).height, image.height);
  // A panel's own x label replaces the chart's under it: another label changes the image, the
  // chart's own label given to the panel draws the same image.
  Chart relabelled = one;
  relabelled.panels[0].x_label = "slices";
  const Image other = draw_chart(relabelled);
  ASSERT_EQ(other.rgba.size(), image.rgba.size());
  EXPECT_NE(other.rgba, image.rgba);
  relabelled.panels[0].x_label = "frame";
  EXPECT_EQ(draw_chart(relabelled).rgba, image.rgba);
  // Labels per point (lamps, buildings) replace the indices under the ticks: the indices' own
  // text draws the same image, other text another.
  Chart ticked = one;
  ticked.panels[0].x_ticks = {"0", "1", "2", "3"};
  EXPECT_EQ(draw_chart(ticked).rgba, image.rgba);
  ticked.panels[0].x_ticks = {"1", "2", "4", "8"};
  EXPECT_NE(draw_chart(ticked).rgba, image.rgba);
}

}  // namespace
}  // namespace shadowvol
