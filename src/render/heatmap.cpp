#include "render/heatmap.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace shadowvol {
namespace {

constexpr int kGap = 4;           // between the panels
constexpr int kScaleHeight = 12;  // the bar along the bottom, under a gap

// Black, purple, red, orange, pale yellow: dark where little happens, light where much does.
glm::vec3 colour_of(double t) {
  static constexpr std::array<glm::vec3, 5> kStops = {
      glm::vec3(0, 0, 0), glm::vec3(60, 15, 110), glm::vec3(180, 40, 90), glm::vec3(245, 130, 30),
      glm::vec3(252, 240, 170)};
  const double x = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(x), kStops.size() - 2);
  return glm::mix(kStops[i], kStops[i + 1], static_cast<float>(x - double(i)));
}

void put(Image& image, int x, int y, const glm::vec3& rgb) {
  std::uint8_t* p = &image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)];
  p[0] = static_cast<std::uint8_t>(rgb.r + 0.5f);
  p[1] = static_cast<std::uint8_t>(rgb.g + 0.5f);
  p[2] = static_cast<std::uint8_t>(rgb.b + 0.5f);
  p[3] = 255;
}

}  // namespace

Heatmap tile_work_heatmap(const Frame& frame) {
  const int w = frame.image.width, h = frame.image.height;
  const int tiles_x = (w + raster::kTileSize - 1) / raster::kTileSize;
  assert(frame.tile_work.size() ==
         static_cast<std::size_t>(tiles_x) * ((h + raster::kTileSize - 1) / raster::kTileSize));
  const auto tile_pixels = [&](std::size_t t) {
    const int x0 = static_cast<int>(t % tiles_x) * raster::kTileSize;
    const int y0 = static_cast<int>(t / tiles_x) * raster::kTileSize;
    return double(std::min(raster::kTileSize, w - x0) * std::min(raster::kTileSize, h - y0));
  };
  Heatmap out;
  for (std::size_t t = 0; t < frame.tile_work.size(); ++t)
    out.passes_at_top =
        std::max(out.passes_at_top, frame.tile_work[t].pixels_processed / tile_pixels(t));
  out.image = {2 * w + kGap, h + kGap + kScaleHeight,
               std::vector<std::uint8_t>(
                   static_cast<std::size_t>(2 * w + kGap) * (h + kGap + kScaleHeight) * 4, 255)};
  for (int panel = 0; panel < 2; ++panel)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::uint8_t* src = &frame.image.rgba[4 * (static_cast<std::size_t>(y) * w + x)];
        const float grey = 0.35f * (0.3f * src[0] + 0.59f * src[1] + 0.11f * src[2]);
        const std::size_t t =
            static_cast<std::size_t>(y / raster::kTileSize) * tiles_x + x / raster::kTileSize;
        const raster::TileWork& work = frame.tile_work[t];
        const double passes =
            (panel == 0 ? work.pixels_processed : work.pixels_updated) / tile_pixels(t);
        const glm::vec3 rgb =
            passes > 0.0 ? glm::mix(glm::vec3(grey), colour_of(passes / out.passes_at_top), 0.85f)
                         : glm::vec3(grey);
        put(out.image, panel * (w + kGap) + x, y, rgb);
      }
  for (int x = 0; x < out.image.width; ++x)
    for (int y = h + kGap; y < out.image.height; ++y)
      put(out.image, x, y, colour_of(double(x) / (out.image.width - 1)));
  return out;
}

}  // namespace shadowvol
