// shadowvol trace: Embree used as a CPU renderer of hard shadows would use it, timed: the
// baseline `bench --versus embree` measures shadowvol's frame against (issue 22).
//
// Owns: an Embree device and scene of the opaque objects in eye-relative space, built with the
// flags and quality a renderer picks as its documentation advises: for a BVH rebuilt every frame
// a dynamic scene of medium build quality, for one kept from frame to frame (a static scene) high
// quality, the fastest to trace; and the frame: primary rays through every pixel centre in coherent
// 8-wide packets (2 x 4 pixels), then one shadow ray per hit and light, in packets of the same 8,
// occluded-only queries; tiles of 32 x 32 pixels spread over oneTBB's threads. Transparent casters
// are traced as opaque.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/expected.h"
#include "scene/scene.h"

namespace shadowvol {

struct EmbreeFrame {
  double ms_build = 0, ms_primary = 0, ms_shadow = 0;
  std::uint64_t hits = 0, shadowed = 0;  // pixels that see a surface; (pixel, light) in shadow
};

// The hybrid's input from a depth pass: per pixel of a width x height frame of `scene`, given the
// object (-1 for none) and face it shows, the eye-relative point the pixel centre's ray meets the
// face's plane at (w = 1), or w = 0 where no surface is, as a deferred renderer rebuilds
// positions from its depth buffer. Rows in parallel.
void visible_points(const Scene& scene, int width, int height, std::span<const std::int32_t> object,
                    std::span<const std::uint32_t> face, std::vector<glm::vec4>& points);

class EmbreeBaseline {
 public:
  static Expected<std::unique_ptr<EmbreeBaseline>> create();
  ~EmbreeBaseline();
  // How long the BVH is to live: rebuilt every frame, or kept while the scene stands still.
  enum class Bvh { rebuilt, kept };
  // Builds the BVH of the scene's objects as they stand (replacing the last), timed into ms.
  Expected<void> build(const Scene& scene, double& ms, Bvh bvh = Bvh::rebuilt);
  // Primary and shadow rays of a width x height frame of `scene` (the scene built last).
  EmbreeFrame trace(const Scene& scene, int width, int height);
  // The hybrid an engine would write: shadow rays alone, from the points a depth pass left
  // (eye-relative, one per pixel, w = 0 where no surface), to every light. Returns the time.
  double shadow_rays(const Scene& scene, std::span<const glm::vec4> points,
                     std::uint64_t& shadowed);

 private:
  struct State;
  explicit EmbreeBaseline(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace shadowvol
