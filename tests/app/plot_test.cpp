// The app's charts: the font draws what its glyphs say, and a chart draws its series where
// their values put them.
#include <gtest/gtest.h>

#include <cstdint>

#include "bitmap_font.h"
#include "plot.h"

namespace shadowvol {
namespace {

Image blank(int w, int h) {
  return {w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h * 4, 0)};
}
bool lit(const Image& image, int x, int y) {
  return image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)] != 0;
}
int lit_count(const Image& image) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += lit(image, x, y);
  return n;
}

TEST(BitmapFont, DrawsTheGlyphsPixelsAtScale) {
  Image image = blank(12, 14);
  draw_text(image, 0, 0, "1", glm::vec3(1.0f), 2);
  // "1": row 0 is "..#..", so at scale 2 only columns 4-5 of rows 0-1 are lit there.
  for (int x = 0; x < 10; ++x) EXPECT_EQ(lit(image, x, 0), x == 4 || x == 5) << x;
  // Its bottom row ".###." is three glyph pixels wide: six pixels at scale 2.
  int bottom = 0;
  for (int x = 0; x < 10; ++x) bottom += lit(image, x, 13);
  EXPECT_EQ(bottom, 6);
  // Ten glyph pixels (the flag, the stem, the foot), each 2x2.
  EXPECT_EQ(lit_count(image), 4 * 10);
}

TEST(BitmapFont, LettersOfEitherCaseAreOneGlyphAndUnknownOnesABox) {
  Image lower = blank(6, 7), upper = blank(6, 7), unknown = blank(6, 7), space = blank(6, 7);
  draw_text(lower, 0, 0, "k", glm::vec3(1.0f), 1);
  draw_text(upper, 0, 0, "K", glm::vec3(1.0f), 1);
  EXPECT_EQ(lower.rgba, upper.rgba);
  EXPECT_GT(lit_count(lower), 0);
  draw_text(unknown, 0, 0, "~", glm::vec3(1.0f), 1);
  EXPECT_EQ(lit_count(unknown), 2 * 5 + 2 * 5);  // the outline of 5x7: nothing dropped silently
  draw_text(space, 0, 0, " ", glm::vec3(1.0f), 1);
  EXPECT_EQ(lit_count(space), 0);
  EXPECT_EQ(text_width("abc", 2), (3 * 6 - 1) * 2);
  EXPECT_EQ(text_width("", 2), 0);
}

TEST(BitmapFont, ClipsAtTheImageEdges) {
  Image image = blank(4, 4);
  draw_text(image, -2, -2, "8888", glm::vec3(1.0f), 1);  // partly outside: must not write there
  // The visible part of the first "8": glyph rows 2-5, columns 2-4 (one, two, one, one lit).
  EXPECT_EQ(lit_count(image), 5);
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
      if (p[0] != 255 || p[1] != 0 || p[2] != 0) continue;
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
}

}  // namespace
}  // namespace shadowvol
