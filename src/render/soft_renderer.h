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

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

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

  // Triangles (3 clip-space vertices each) and their weights, grouped by a key per triangle:
  // those of keys [first, last) are together, in order. Triangles whose keys already run in
  // order (a volume counted whole: its sides, then its caps) are viewed where they lie, which
  // must outlive the view; others are copied into order, stably.
  struct Grouped {
    std::span<const glm::vec4> tris;
    std::span<const std::int32_t> weights;
    std::vector<std::size_t> offsets;    // key k's are [offsets[k], offsets[k + 1])
    std::vector<glm::vec4> sorted_tris;  // the copies, kept between frames
    std::vector<std::int32_t> sorted_weights;
    std::vector<std::size_t> cursor;  // where the next of key k goes, while copying

    void group(std::span<const glm::vec4> triangles, std::span<const std::int32_t> triangle_weights,
               std::span<const std::uint32_t> keys, std::size_t key_count);
    std::span<const glm::vec4> triangles_of(std::size_t first, std::size_t last) const {
      return tris.subspan(3 * offsets[first], 3 * (offsets[last] - offsets[first]));
    }
    std::span<const std::int32_t> weights_of(std::size_t first, std::size_t last) const {
      return weights.subspan(offsets[first], offsets[last] - offsets[first]);
    }
  };

  VolumeCache volumes_;
  soft::Target target_;
  soft::SplitPlaneSampler split_sampler_;
  // Kept between frames: no reallocation. Under a split plane, a key per triangle (its part and
  // whether only z-fail counts it) and the triangles grouped by it.
  std::vector<glm::vec4> tris_, prefill_tris_;
  std::vector<std::int32_t> weights_, prefill_weights_;
  std::vector<std::uint32_t> keys_, prefill_keys_;
  Grouped volume_groups_, prefill_groups_;
  std::vector<glm::vec3> log_light_, eye_log_;
  std::vector<float> opaque_depth_;  // with transparent casters: the opaque layer's depths
};

}  // namespace shadowvol
