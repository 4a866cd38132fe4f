// shadowvol soft: which of several split planes (Laine 2005 §4) suits one shadow volume best,
// judged from a sample of the frame's tiles before the volume is counted.
//
// Laine constructs one plane per object by a rule of thumb and leaves better construction open
// (§8: "more sophisticated split plane construction methods could certainly be developed"). This
// picks from candidates instead: at the centre of one tile in every kSampleStride x
// kSampleStride block, at the tile's middle stored depth (where split_rule tests it), it counts
// the volume's layers that z-pass would count there (the sides in front) and those z-fail would
// (sides and caps behind), and charges each plane what its split test would make the sampled
// tiles cost. The samples are drawn by the rasterizer itself (CountRule::cover and
// CountRule::behind) on a target of one pixel per sampled tile, and their work is added to the
// caller's counters: the choice is not free, and the figures say so.
//
// Not thread-safe: one sampler per renderer, like its target.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "raster/raster.h"

namespace shadowvol::soft {

// The rasterizer this backend is built on.
using raster::Counters;
using raster::CountRule;
using raster::DepthBounds;
using raster::kTileSize;
using raster::Target;
using raster::TileDepth;

// One sampled tile in every 4 x 4 (a 32 x 32 pixel block): at 1024 x 768, 768 samples. Finer
// sampling chooses a little better and costs more than it saves (README, issue 6).
inline constexpr int kSampleStride = 4;

class SplitPlaneSampler {
 public:
  // The index in `planes` (clip space, as SplitPlane::plane) of the one under which the volume
  // would cost least, as the samples estimate it; the first of equals, 0 when nothing is
  // sampled. `always` are the triangles counted in every tile (the sides), `zfail_only` those
  // counted only in z-fail tiles (the caps), both clip-space, 3 vertices each. `target` holds
  // the frame's depth and up-to-date tile depths; tiles outside `bounds` are free under either
  // rule, as draw_counts skips them. The samples' work is added to `counters`.
  std::size_t cheapest(const Target& target, std::span<const glm::vec4> always,
                       std::span<const glm::vec4> zfail_only, DepthBounds bounds,
                       std::span<const glm::vec4> planes, Counters& counters);

 private:
  // Per sample, the triangles that `rule` counts against its tile's middle depth, into `layers`;
  // samples set aside get the depth `set_aside`, where the rule counts nothing.
  void count_layers(std::span<const glm::vec4> triangles, CountRule rule, float set_aside,
                    std::vector<std::int32_t>& layers, Counters& counters);

  Target samples_;                    // one pixel per sampled tile
  std::vector<std::int64_t> tile_;    // per sample: its tile's index in the frame, or -1
  std::vector<float> middle_;         // per sample: its tile's middle stored depth
  std::vector<glm::vec4> triangles_;  // always then zfail_only, mapped onto samples_
  std::vector<std::int32_t> ones_;    // their weights
  std::vector<std::int32_t> zpass_layers_, zfail_layers_;  // per sample
  std::vector<std::size_t> telling_;                       // the samples whose two counts differ
};

}  // namespace shadowvol::soft
