// shadowvol verify: a rendered frame against the ray-traced reference, per pixel.
//
// Owns: the comparison that DESIGN.md's invariant is stated in. On every pixel whose surface
// faces the light (in the reference), the rendered shadow mask must equal the reference's,
// except within one pixel of a shadow or silhouette boundary of the reference. With transparent
// casters, so must the transmitted light (within kLightTolerance), on both layers: the opaque
// surfaces, and the nearest transparent surface in front of them. Where the frame records which
// surfaces its lit pass takes as facing each light (RenderOptions::record_facing), so must that,
// on every pixel that shows a surface, but where the reference sees it nearly edge-on from the
// light (kGrazingCosine): a shading input no mask shows (a normal lost to overflow leaves a lit
// face dark, in shadow or not).
//
// "Within one pixel" is decided first from the reference at the pixel's eight neighbours. A
// boundary can pass between pixel centres without changing any of them: a sliver of shadow or
// light thinner than a pixel, such as the tip of a self-shadow at a silhouette vertex. So a
// mismatch with no boundary among its neighbours is looked at again: the reference is traced
// every sixteenth of a pixel over the square between the neighbours' centres, and it is outside
// the band only if all those samples agree.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/expected.h"
#include "render/renderer.h"
#include "trace/reference.h"

namespace shadowvol {

// Transparent casters: light that reaches a surface may differ from the reference's by this much
// (any channel, on the 0..1 scale) and still match, one step of an 8-bit image.
inline constexpr float kLightTolerance = 1.0f / 255.0f;

// What differs at a mismatched pixel, the first that does of: the surface seen, the side of the
// light it is taken to be on, the shadow, the light through transparent casters.
enum class Difference : std::uint8_t { surface, side, shadow, light };
const char* to_string(Difference d);

// One mismatch outside the band, where a person (or a bisect script) can look.
struct Mismatch {
  int x = 0, y = 0;       // pixel, from the top-left corner
  std::size_t light = 0;  // scene light index
  bool glass = false;     // on the transparent layer (else the opaque one)
  // The near-plane point of the pixel, or of a neighbour, lies in the light's shadow.
  bool near_plane_shadowed = false;
  Difference difference = Difference::shadow;
  std::int32_t object = -1, reference_object = -1;  // the surfaces each sees
  std::uint32_t face = 0, reference_face = 0;
  bool shadowed = false, reference_shadowed = false;
};
// Comparison::outside_band lists at most this many, in the order found (light, row, column).
inline constexpr std::size_t kListedMismatches = 32;

struct Comparison {
  std::size_t pixels_compared = 0;  // over all lights and layers
  // A different mask, a different surface seen, a different side of the light, or different
  // light through transparent casters.
  std::size_t mismatched = 0;
  std::size_t mismatched_outside_band = 0;  // of those, more than a pixel from any boundary
  // Of those, the ones at pixels whose near-plane point, or a neighbour's, lies in a shadow of
  // the light compared (ReferenceFrame::near_plane_shadowed): where z-pass, counting from the
  // near plane, must be wrong, or is within a pixel of it, and only there, without a pre-fill
  // (zp+db) or z-fail.
  std::size_t outside_band_near_plane_shadowed = 0;
  // Scenes with transparent casters (else 0): the largest difference of transmitted light from
  // the reference's, any channel, over the compared pixels that see the surface the reference
  // sees; over all of them, and over those outside the band (the reference even over the
  // pixel's neighbours, and for a mismatch also between their centres).
  float max_light_error = 0.0f;
  float max_light_error_outside_band = 0.0f;
  // Per pixel, the worst over the lights: 0 agrees or not compared, 1 mismatch within the
  // band, 2 mismatch outside it.
  std::vector<std::uint8_t> verdict;
  // The first kListedMismatches of the mismatches outside the band.
  std::vector<Mismatch> outside_band;
};

// Which reference decides: Embree's (trace/), or the brute-force one written apart from it
// (brute/: every ray against every triangle in double; small scenes), which checks the first.
enum class Reference : std::uint8_t { embree, brute };
const char* to_string(Reference r);
// "embree" or "brute"; an error naming the choices otherwise.
Expected<Reference> parse_reference(std::string_view name);
// The reference frame of the scene at width x height, by `reference`.
Expected<ReferenceFrame> reference_frame(const Scene& scene, int width, int height,
                                         Reference reference, const Progress& progress = {});

// A reference frame as a rendered frame would hold it (object, face, shadowed, transmitted,
// faces_light, and a grey image), so that one reference can be compared with another by
// `compare`, which reads a mask only where the light is faced.
Frame as_frame(const ReferenceFrame& reference);

// Frame and reference must have the same size and the same lights. The samples between pixel
// centres are traced in parallel; `progress` hears of them where there are many.
Comparison compare(const Frame& frame, const ReferenceFrame& reference,
                   const Progress& progress = {});

// The rendered image, greyed, with mismatches outside the band in red and inside it in yellow.
Image diff_image(const Frame& frame, const Comparison& comparison);

}  // namespace shadowvol
