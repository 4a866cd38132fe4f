#include "verify/verify.h"

#include <algorithm>
#include <cassert>
#include <string>

#include "brute/brute_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/common.hpp>

namespace shadowvol {
namespace {

// How a layer's light differs from the reference's at pixel p for light l: the largest channel
// difference (0 without transparent casters).
float light_error(const std::vector<std::vector<glm::vec3>>& a,
                  const std::vector<std::vector<glm::vec3>>& b, std::size_t l, std::size_t p) {
  if (a.empty() || b.empty()) return 0.0f;
  const glm::vec3 d = glm::abs(a[l][p] - b[l][p]);
  return std::max({d.x, d.y, d.z});
}

// Whether the reference's layer changes, for light l, anywhere in the square between the
// centres of the neighbours of pixel (x, y): it is sampled every 1 / kSteps pixel. A sixteenth,
// as a quarter missed a lit gap three sixteenths wide between two leaves' shadows (`tree`, frame
// 50, 480 x 270); the cost falls only on the rare mismatches with no boundary at a neighbour.
//
// Or, where the frame sees at (x, y) another face of the object the reference sees, whether that
// face lies there in front of the reference's surface at (x, y), or is seen there at all: a
// silhouette of one object over itself (the inner rim of a torus) passes within the pixel, where
// a face turned from the eye ends at its neighbour's edge and a rasterizer's vertices, snapped
// to its subpixel grid, may leave a hair of it over the centre. (Between objects, the change of
// object is the boundary.)
//
// Or, where another face of the reference's object stands on its surface within the square (a
// car's cabin on its body: a concave crease), whether the shadow on that surface's plane,
// continued under the other face, changes: the shadow's edge is the crease, hidden but within
// the pixel, and a volume's side through it meets the surface there at the depth of its own
// rounding.
template <class Pick>
bool boundary_between_centres(const ReferenceSampler& tracer, const Mismatch& m, Pick pick) {
  const int x = m.x, y = m.y;
  const std::size_t l = m.light;
  const bool other_face = m.object == m.reference_object && m.face != m.reference_face;
  constexpr int kSteps = 16;
  const auto at = [&](int i, int j) {
    return tracer.sample(x + 0.5 + double(i) / kSteps, y + 0.5 + double(j) / kSteps);
  };
  if (other_face) {
    const ReferenceSample centre = at(0, 0);
    if (tracer.face_nearer_within(x + 0.5, y + 0.5, m.object, m.face, pick(centre).distance))
      return true;
  }
  const bool shadow = m.difference == Difference::shadow;
  const auto shadow_changes_beyond_crease = [&](int i, int j) {
    const ReferenceSurface continued =
        tracer.on_face_plane(x + 0.5 + double(i) / kSteps, y + 0.5 + double(j) / kSteps,
                             m.reference_object, m.reference_face);
    return continued.object >= 0 && continued.faces_light[l] &&
           bool(continued.shadowed[l]) != m.reference_shadowed;
  };
  const ReferenceSample first_sample = at(-kSteps, -kSteps);
  const ReferenceSurface& first = pick(first_sample);
  for (int j = -kSteps; j <= kSteps; ++j)
    for (int i = -kSteps; i <= kSteps; ++i) {
      const ReferenceSample sample = at(i, j);
      const ReferenceSurface& s = pick(sample);
      if (other_face && s.object == m.object && s.face == m.face) return true;
      if (shadow && s.object == m.reference_object && s.face != m.reference_face &&
          shadow_changes_beyond_crease(i, j))
        return true;
      if (s.object != first.object || s.shadowed[l] != first.shadowed[l] ||
          s.faces_light[l] != first.faces_light[l] ||
          (!s.transmitted.empty() && s.transmitted[l] != first.transmitted[l]))
        return true;
    }
  return false;
}

// One layer of the frame against the same layer of the reference; `pick` takes that layer's
// surface out of a reference sample.
// A mismatch counted: within the band or outside it.
void settle(Comparison& c, std::size_t p, bool band, float error, const Mismatch& m) {
  c.mismatched_outside_band += !band;
  c.outside_band_near_plane_shadowed += !band && m.near_plane_shadowed;
  if (!band) c.max_light_error_outside_band = std::max(c.max_light_error_outside_band, error);
  if (!band && c.outside_band.size() < kListedMismatches) c.outside_band.push_back(m);
  c.verdict[p] = std::max<std::uint8_t>(c.verdict[p], band ? 1 : 2);
}

// Whether the near-plane point of pixel (x, y), or of a neighbour, lies in a shadow of light l:
// plain z-pass is wrong where the near plane is in a shadow, and that region's edge is sampled
// at the centres as any other boundary is, so a pixel beside it is within its band.
bool near_plane_shadowed_around(const std::vector<std::vector<std::uint8_t>>& near,
                                std::size_t l, int x, int y, int w, int h) {
  if (near.empty()) return false;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int qx = x + dx, qy = y + dy;
      if (qx >= 0 && qy >= 0 && qx < w && qy < h && near[l][std::size_t(qy) * w + qx]) return true;
    }
  return false;
}

struct Suspect {
  Mismatch what;
  float error;
};

template <class Pick>
void compare_layer(const SurfaceLayer& frame, const ReferenceLayer& ref, bool glass,
                   const std::vector<std::vector<std::uint8_t>>& near_plane_shadowed, int w, int h,
                   const ReferenceSampler* tracer, Pick pick, const Progress& progress,
                   Comparison& c) {
  std::vector<Suspect> suspects;
  const bool sides = !frame.faces_light.empty();  // the frame says which surfaces face the light
  for (std::size_t l = 0; l < ref.shadowed.size(); ++l) {
    const std::vector<std::uint8_t>& shadow = ref.shadowed[l];
    const std::vector<std::uint8_t>& facing = ref.faces_light[l];
    const std::vector<std::uint8_t>* grazing = ref.grazing.empty() ? nullptr : &ref.grazing[l];
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p = static_cast<std::size_t>(y) * w + x;
        if (ref.object[p] < 0) continue;
        // The frame's side of the light, where the reference's is not a matter of rounding.
        const bool side = sides && !(grazing && (*grazing)[p]);
        if (!facing[p] && !side) continue;
        ++c.pixels_compared;
        const bool same_surface = frame.object[p] == ref.object[p];
        const float error = same_surface && facing[p]
                                ? light_error(frame.transmitted, ref.transmitted, l, p)
                                : 0.0f;
        c.max_light_error = std::max(c.max_light_error, error);
        // Within one pixel of a boundary of the reference: of its shadow or the light that
        // reaches it, of the surfaces it sees (silhouettes), or of the part that faces the light.
        // Or of the face the frame sees, another of the same object (boundary_between_centres).
        const bool other_face = frame.object[p] == ref.object[p] && frame.face[p] != ref.face[p];
        bool band = false;
        for (int dy = -1; dy <= 1 && !band; ++dy)
          for (int dx = -1; dx <= 1 && !band; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const std::size_t q = static_cast<std::size_t>(qy) * w + qx;
            band = ref.object[q] != ref.object[p] || shadow[q] != shadow[p] ||
                   (other_face && ref.object[q] == frame.object[p] &&
                    ref.face[q] == frame.face[p]) ||
                   facing[q] != facing[p] ||
                   (!ref.transmitted.empty() && ref.transmitted[l][q] != ref.transmitted[l][p]);
          }
        const bool same =
            same_surface && (!side || frame.faces_light[l][p] == facing[p]) &&
            (!facing[p] || (frame.shadowed[l][p] == shadow[p] && error <= kLightTolerance));
        if (same) {
          if (!band)
            c.max_light_error_outside_band = std::max(c.max_light_error_outside_band, error);
          continue;
        }
        ++c.mismatched;
        const Difference difference =
            !same_surface                                          ? Difference::surface
            : side && frame.faces_light[l][p] != facing[p]         ? Difference::side
            : frame.shadowed[l][p] != shadow[p]                    ? Difference::shadow
                                                                   : Difference::light;
        const Mismatch what{x,
                            y,
                            l,
                            glass,
                            near_plane_shadowed_around(near_plane_shadowed, l, x, y, w, h),
                            difference,
                            frame.object[p],
                            ref.object[p],
                            frame.face[p],
                            ref.face[p],
                            frame.shadowed[l][p] != 0,
                            shadow[p] != 0};
        if (!band && tracer != nullptr) {
          suspects.push_back({what, error});  // looked at between centres below
          continue;
        }
        settle(c, p, band, error, what);
      }
  }
  // Mismatches with no boundary among their neighbours: the reference traced between the
  // centres, a thousand samples each, in parallel.
  std::vector<std::uint8_t> bands(suspects.size(), 0);
  const std::size_t step = std::max<std::size_t>(1, suspects.size() / 64);
  for (std::size_t s0 = 0; s0 < suspects.size(); s0 += step) {
    if (progress)
      progress("tracing between the centres of " + std::to_string(suspects.size()) + " mismatches",
               float(s0) / float(suspects.size()));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(s0, std::min(suspects.size(), s0 + step)),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i < range.end(); ++i) {
                          const Suspect& m = suspects[i];
                          bands[i] = boundary_between_centres(*tracer, m.what, pick);
                        }
                      });
  }
  for (std::size_t i = 0; i < suspects.size(); ++i) {
    const Suspect& m = suspects[i];
    settle(c, static_cast<std::size_t>(m.what.y) * w + m.what.x, bands[i] != 0, m.error, m.what);
  }
}

}  // namespace

Comparison compare(const Frame& frame, const ReferenceFrame& ref, const Progress& progress) {
  const int w = ref.width, h = ref.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  assert(frame.object.size() == pixels && frame.shadowed.size() == ref.shadowed.size());
  assert(frame.glass.object.empty() == ref.glass.object.empty());
  Comparison c;
  c.verdict.assign(pixels, 0);
  const ReferenceSampler* tracer = ref.tracer.get();
  compare_layer(
      frame, ref, false, ref.near_plane_shadowed, w, h, tracer,
      [](const ReferenceSample& s) -> const ReferenceSurface& { return s; }, progress, c);
  if (!ref.glass.object.empty())
    compare_layer(
        frame.glass, ref.glass, true, ref.near_plane_shadowed, w, h, tracer,
        [](const ReferenceSample& s) -> const ReferenceSurface& { return s.glass; }, progress, c);
  return c;
}

const char* to_string(Reference r) { return r == Reference::brute ? "brute" : "embree"; }

Expected<Reference> parse_reference(std::string_view name) {
  if (name == "embree") return Reference::embree;
  if (name == "brute") return Reference::brute;
  return make_error("unknown reference '" + std::string(name) + "' (expected embree or brute)");
}

Expected<ReferenceFrame> reference_frame(const Scene& scene, int width, int height,
                                         Reference reference, const Progress& progress) {
  return reference == Reference::brute ? trace_brute_reference(scene, width, height, progress)
                                       : trace_reference(scene, width, height, progress);
}

Frame as_frame(const ReferenceFrame& reference) {
  Frame f;
  const auto layer = [](const ReferenceLayer& from, SurfaceLayer& to) {
    to.object = from.object;
    to.face = from.face;
    to.shadowed = from.shadowed;
    to.transmitted = from.transmitted;
    to.faces_light = from.faces_light;
  };
  layer(reference, f);
  if (!reference.glass.object.empty()) layer(reference.glass, f.glass);
  f.image.width = reference.width;
  f.image.height = reference.height;
  f.image.rgba.assign(std::size_t{4} * reference.width * reference.height, 128);
  return f;
}

const char* to_string(Difference d) {
  switch (d) {
    case Difference::surface: return "surface";
    case Difference::side: return "side";
    case Difference::shadow: return "shadow";
    case Difference::light: return "light";
  }
  return "?";
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
