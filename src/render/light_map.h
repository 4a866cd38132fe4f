// shadowvol render: a picture of the light intensity map (Kim, Kim & Turk 2008 §2), the light
// that reaches each visible surface through the casters, so that a person can see what the
// shadow passes computed apart from the surfaces' own colours.
#pragma once

#include "render/renderer.h"
#include "scene/scene.h"

namespace shadowvol {

// Per pixel of the frame's opaque layer, the sum over the lights of each light's colour times
// its intensity times the fraction that arrives (Frame::transmitted; 0 or 1 by the shadow mask
// in a scene without transparent casters), scaled so that the sum of every light at full is
// white, in sRGB. Where no surface is seen, black. The frame must carry masks for the scene's
// lights (any backend's render does).
Image light_map_image(const Scene& scene, const Frame& frame);

}  // namespace shadowvol
