// shadowvol render: the buffers of a frame that compositing tools and other renderers compare
// against, besides its picture: per light a shadow mask, the depth, the object ids; and the
// picture supersampled.
//
// Owns: turning a Frame (what each pixel shows, per light whether it is lit) into those buffers,
// at the pixel centres `verify` compares; and the box filter that resolves a supersampled picture.
// No I/O: the command line writes them (PNG, PFM).
#pragma once

#include <cstdint>
#include <vector>

#include "core/expected.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace shadowvol {

struct GreyImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> value;  // row 0 at the top
};

// `render --mask`'s values.
inline constexpr std::uint8_t kMaskLit = 255, kMaskShadowed = 0, kMaskNotFacing = 128;

// Light `light`'s mask over the frame's opaque layer: kMaskLit where the light arrives,
// kMaskShadowed where an opaque caster blocks it or the surface lies beyond its range (the
// distance from the point the pixel's centre shows, on any object), and
// kMaskNotFacing where no surface is seen or the surface faces away from the light (the eye and
// the light on opposite sides of its face's plane, as the reference decides). Transparent
// casters' partial light is not in the mask (light_map.h shows it). `scene` as at the frame.
GreyImage shadow_mask(const Scene& scene, const Frame& frame, std::size_t light);

struct DepthImage {
  int width = 0, height = 0;
  std::vector<float> depth;  // row 0 at the top
};
// Per pixel, the distance in scene units along the camera's view axis to the surface the frame
// shows there (the ray through the pixel's centre meets its face's plane); +infinity where no
// surface is seen. `scene` as at the frame.
DepthImage view_depth(const Scene& scene, const Frame& frame);

// Per pixel, the index of the object seen plus one, in 24 bits (red the low byte, then green,
// then blue), 0 where none; alpha 255. Exact values for ID mattes, not a picture.
Image object_ids(const Frame& frame);

// Supersampling (`render --samples N`): N samples per pixel on a k x k grid, N = k^2 in 1 .. 64.
inline constexpr int kMaxSamples = 64;
// The grid's side k for N samples, refused where N is not a square in range or the picture at
// k times the size would pass the rasterizer's limit.
Expected<int> samples_side(int samples, int width, int height);
// The picture of k x k samples per pixel, each pixel the mean of its samples in linear light.
Image resolve_samples(const Image& samples, int side);

}  // namespace shadowvol
