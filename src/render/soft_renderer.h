// shadowvol render: SoftRenderer, the software backend.
//
// Owns: the passes on src/soft's rasterizer (depth with face ids, then per light: volumes from
// the cache, counts by z-pass or z-fail, and shading where the count is 0), threads from oneTBB.
// Deterministic: the same frame at any thread count.
#pragma once

#include "render/frame_plan.h"
#include "render/renderer.h"
#include "soft/raster.h"

namespace shadowvol {

// The software backend: src/soft's rasterizer, threads from oneTBB.
class SoftRenderer final : public Renderer {
 public:
  Frame render(const Scene& scene, const RenderOptions& options) override;
  std::string_view backend() const override { return "soft"; }

 private:
  VolumeCache volumes_;
  soft::Target target_;
};

}  // namespace shadowvol
