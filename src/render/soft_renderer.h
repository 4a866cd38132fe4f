// shadowvol render: SoftRenderer, the software backend.
//
// Owns: the passes on src/soft's rasterizer (depth with face ids, then per light: volumes from
// the cache, counts by z-pass or z-fail, and shading where the count is 0), threads from oneTBB.
// Deterministic: the same frame at any thread count.
//
// Transparent casters (Kim, Kim & Turk 2008): the opaque surfaces make the first layer; per
// light, the opaque casters' counts give its shadow mask, and each group of transparent casters
// of one material is counted on its own (exact integer surface counts, light caps included) and
// added into a float32 log light intensity map as count * log(transmittance); the light that
// arrives is exp of the map. The nearest transparent surface in front makes a second layer, lit
// the same way (partial self-shadowing). The picture is the first layer seen through every
// transparent surface in front of it (counted per group the same way, along the eye's rays),
// plus the nearest one's own reflection.
#pragma once

#include "render/frame_plan.h"
#include "render/renderer.h"
#include "soft/raster.h"
#include "soft/split_sampler.h"

namespace shadowvol {

// The software backend: src/soft's rasterizer, threads from oneTBB.
class SoftRenderer final : public Renderer {
 public:
  Frame render(const Scene& scene, const RenderOptions& options) override;
  std::string_view backend() const override { return "soft"; }

 private:
  struct Pass;
  // Per light, the layer's shadow mask (and, with transparent casters, its transmitted light)
  // against the depth buffer as it stands.
  void light_layer(const Pass& pass, std::size_t light, SurfaceLayer& layer);
  // Adds the counts of object o's volume for this light into the target.
  void count_volume(const Pass& pass, std::size_t light, std::size_t o);
  // With transparent casters: per pixel, the log of the fraction of what lies behind that the
  // transparent surfaces in front of the opaque one let through to the eye (each surface once,
  // whichever way it faces; against the opaque layer's depths), into eye_log_.
  void filter_through_glass(const Pass& pass);

  VolumeCache volumes_;
  soft::Target target_;
  soft::SplitPlaneSampler split_sampler_;
  std::vector<glm::vec4> tris_, prefill_tris_;  // kept between frames: no reallocation
  std::vector<std::int32_t> weights_, prefill_weights_;
  std::vector<glm::vec3> log_light_, eye_log_;
  std::vector<float> opaque_depth_;  // with transparent casters: the opaque layer's depths
};

}  // namespace shadowvol
