#include "soft/split_sampler.h"

#include <gtest/gtest.h>

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "raster/raster.h"

namespace shadowvol::soft {
namespace {

// Clip-space planes whose split test gives every tile one rule (split_rule): z-pass everywhere
// (every point on the camera's side of w = -z) and z-fail everywhere (the zero plane).
const glm::vec4 kZpassEverywhere(0.0f, 0.0f, 1.0f, 1.0f);
const glm::vec4 kZfailEverywhere(0.0f);

// A front and a back face over most of the screen at window depth z: two layers of a volume.
std::vector<glm::vec4> two_layers(float z) {
  const glm::vec2 a(-0.9f, -0.9f), b(0.9f, -0.9f), c(0.0f, 0.9f);
  return {glm::vec4(a, z, 1), glm::vec4(b, z, 1), glm::vec4(c, z, 1),   // CCW: front
          glm::vec4(a, z, 1), glm::vec4(c, z, 1), glm::vec4(b, z, 1)};  // CW: back
}

// Surfaces at depth 0.25 everywhere; the volume's layers in front of them cost z-pass, those
// behind cost z-fail, and caps cost z-fail only (in front of the surfaces or behind them). The
// sampler picks the plane whose rule pays nothing, whichever place in the list it has, and its
// samples' work is counted.
TEST(SplitPlaneSampler, PicksTheRuleThatPaysNothing) {
  Target target(96, 64);
  target.clear_depth(0.25f);
  target.update_tile_depth();
  SplitPlaneSampler sampler;
  const std::vector<glm::vec4> none;
  const std::vector<glm::vec4> in_front = two_layers(0.5f), behind = two_layers(0.1f);
  const std::span<const glm::vec4> one_behind = std::span(behind).first(3);
  struct Case {
    std::span<const glm::vec4> sides, caps;
    bool zfail_is_free;
  };
  for (const Case& c :
       {Case{in_front, none, true}, Case{behind, none, false}, Case{none, behind, false},
        Case{in_front, one_behind, true}, Case{one_behind, in_front, false}}) {
    for (const bool zfail_first : {false, true}) {
      const std::vector<glm::vec4> planes = zfail_first
                                                ? std::vector{kZfailEverywhere, kZpassEverywhere}
                                                : std::vector{kZpassEverywhere, kZfailEverywhere};
      Counters counters;
      const std::size_t picked = sampler.cheapest(target, c.sides, c.caps, {}, planes, counters);
      EXPECT_EQ(planes[picked], c.zfail_is_free ? kZfailEverywhere : kZpassEverywhere)
          << "zfail_first " << zfail_first;
      EXPECT_GT(counters.pixels_processed, 0u);  // the samples are not free
    }
  }
}

// Ties go to the first plane (the caller's own), and so does a single plane or a volume outside
// the depth bounds, which no sample tests.
TEST(SplitPlaneSampler, KeepsTheFirstPlaneWhenNothingTellsThemApart) {
  Target target(96, 64);
  target.clear_depth(0.25f);
  target.update_tile_depth();
  SplitPlaneSampler sampler;
  const std::vector<glm::vec4> none, in_front = two_layers(0.5f);
  const std::vector<glm::vec4> both{kZpassEverywhere, kZfailEverywhere};
  Counters counters;
  EXPECT_EQ(sampler.cheapest(target, none, none, {}, both, counters), 0u);
  const std::vector<glm::vec4> one{kZpassEverywhere};
  EXPECT_EQ(sampler.cheapest(target, in_front, none, {}, one, counters), 0u);
  EXPECT_EQ(sampler.cheapest(target, in_front, none, {0.3f, 0.9f}, both, counters), 0u);
  EXPECT_EQ(counters.pixels_processed, 0u);
}

}  // namespace
}  // namespace shadowvol::soft
