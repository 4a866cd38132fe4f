#include "render/light_map.h"

#include <cassert>
#include <cmath>
#include <cstddef>

#include "render/shading.h"

namespace shadowvol {

Image light_map_image(const Scene& scene, const Frame& frame) {
  assert(frame.shadowed.size() == scene.lights.size());
  const std::size_t pixels = frame.object.size();
  Image out{frame.image.width, frame.image.height, std::vector<std::uint8_t>(4 * pixels, 0)};
  glm::vec3 full(0.0f);
  for (const SceneLight& light : scene.lights) full += light.color * light.intensity;
  for (int c = 0; c < 3; ++c) full[c] = full[c] > 0.0f ? full[c] : 1.0f;
  for (std::size_t p = 0; p < pixels; ++p) {
    out.rgba[4 * p + 3] = 255;
    if (frame.object[p] < 0) continue;
    glm::vec3 arriving(0.0f);
    for (std::size_t l = 0; l < scene.lights.size(); ++l) {
      const glm::vec3 fraction = frame.transmitted.empty()
                                     ? glm::vec3(frame.shadowed[l][p] ? 0.0f : 1.0f)
                                     : frame.transmitted[l][p];
      arriving += scene.lights[l].color * scene.lights[l].intensity * fraction;
    }
    for (int c = 0; c < 3; ++c) out.rgba[4 * p + c] = shading::to_srgb8(arriving[c] / full[c]);
  }
  return out;
}

}  // namespace shadowvol
