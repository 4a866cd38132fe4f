// shadowvol render: the typical volumes a backend times for CC shadow volumes' V > R heuristic
// (Lloyd et al. 2004 §3.2.1: "The values of v and r can be determined empirically by rendering a
// 'typical' set of shadow volumes at different resolutions. Rendering at a low resolution, e.g.
// 10 x 10, gives an estimate of v. Rendering at high resolution and subtracting v gives an
// estimate of r.").
//
// Owns: that set (the same on every backend) and the arithmetic from timings to VolumeCosts; the
// backends own the timing (FrameBackend::measure_volume_costs).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "render/frame.h"

namespace shadowvol {

// The volumes of a ring of bumpy tori (about 9,000 caster triangles) under a point light beside
// them, seen from a camera that frames them and much of their shadows: clip-space triangles
// (aspect 1) and one signed weight each, as a count pass draws them.
struct TypicalVolumes {
  std::vector<glm::vec4> triangles;
  std::vector<std::int32_t> weights;
  std::size_t vertices() const { return triangles.size(); }
};
const TypicalVolumes& typical_volumes();

// The small and the large image's sides in pixels.
inline constexpr int kSmallSide = 10, kLargeSide = 512;

// v = the small draw's time per vertex; r = the rest of the large draw's time per pixel it
// covered (its fill). Times in milliseconds.
VolumeCosts volume_costs(double ms_small, double ms_large, std::size_t vertices,
                         std::uint64_t large_fill);

}  // namespace shadowvol
