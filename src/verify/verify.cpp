#include "verify/verify.h"

#include <algorithm>
#include <cassert>

namespace shadowvol {
namespace {

// Whether the reference changes, for light l, anywhere in the square between the centres of the
// neighbours of pixel (x, y): it is sampled every 1 / kSteps pixel.
bool boundary_between_centres(const ReferenceTracer& tracer, int x, int y, std::size_t l) {
  constexpr int kSteps = 4;
  const auto at = [&](int i, int j) {
    return tracer.sample(x + 0.5 + double(i) / kSteps, y + 0.5 + double(j) / kSteps);
  };
  const ReferenceSample first = at(-kSteps, -kSteps);
  for (int j = -kSteps; j <= kSteps; ++j)
    for (int i = -kSteps; i <= kSteps; ++i) {
      const ReferenceSample s = at(i, j);
      if (s.object != first.object || s.shadowed[l] != first.shadowed[l] ||
          s.faces_light[l] != first.faces_light[l])
        return true;
    }
  return false;
}

}  // namespace

Comparison compare(const Frame& frame, const ReferenceFrame& ref) {
  const int w = ref.width, h = ref.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  assert(frame.object.size() == pixels && frame.shadowed.size() == ref.shadowed.size());
  Comparison c;
  c.verdict.assign(pixels, 0);
  for (std::size_t l = 0; l < ref.shadowed.size(); ++l) {
    const std::vector<std::uint8_t>& shadow = ref.shadowed[l];
    const std::vector<std::uint8_t>& facing = ref.faces_light[l];
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p = static_cast<std::size_t>(y) * w + x;
        if (ref.object[p] < 0 || !facing[p]) continue;
        ++c.pixels_compared;
        const bool same = frame.object[p] == ref.object[p] && frame.shadowed[l][p] == shadow[p];
        if (same) continue;
        ++c.mismatched;
        // Within one pixel of a boundary of the reference: of its shadow, of the surfaces it
        // sees (silhouettes), or of the part that faces the light.
        bool band = false;
        for (int dy = -1; dy <= 1 && !band; ++dy)
          for (int dx = -1; dx <= 1 && !band; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const std::size_t q = static_cast<std::size_t>(qy) * w + qx;
            band =
                ref.object[q] != ref.object[p] || shadow[q] != shadow[p] || facing[q] != facing[p];
          }
        if (!band && ref.tracer) band = boundary_between_centres(*ref.tracer, x, y, l);
        c.mismatched_outside_band += !band;
        c.verdict[p] = std::max<std::uint8_t>(c.verdict[p], band ? 1 : 2);
      }
  }
  return c;
}

Image diff_image(const Frame& frame, const Comparison& comparison) {
  Image out = frame.image;
  for (std::size_t p = 0; p < comparison.verdict.size(); ++p) {
    std::uint8_t* px = &out.rgba[4 * p];
    const int grey = (px[0] * 3 + px[1] * 6 + px[2]) / 10 / 2 + 40;
    px[0] = px[1] = px[2] = static_cast<std::uint8_t>(grey);
    if (comparison.verdict[p] == 1) px[0] = 255, px[1] = 210, px[2] = 0;  // within the band
    if (comparison.verdict[p] == 2) px[0] = 255, px[1] = 0, px[2] = 0;    // outside it
  }
  return out;
}

}  // namespace shadowvol
