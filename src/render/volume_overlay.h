// shadowvol render: the shadow volumes drawn over a frame, so that a person can see them.
#pragma once

#include "render/frame.h"
#include "render/frame_plan.h"
#include "render/volume_cache.h"
#include "scene/scene.h"

namespace shadowvol {

// Draws the edges of every side quad of the cached volumes over the image (the silhouette edge
// and its two rays to infinity, clipped at the near plane), one colour per light.
void overlay_volumes(Image& image, const Scene& scene, const FramePlan& plan,
                     const VolumeCache& volumes);

}  // namespace shadowvol
