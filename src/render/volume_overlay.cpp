#include "render/volume_overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/vec2.hpp>

namespace shadowvol {
namespace {

// Draws the segment a-b (clip space, w >= 0 allowed at one end) over the image, blended: clipped
// to the near plane (z <= w) in homogeneous space, so that a ray to infinity ends at its
// vanishing point, then stepped pixel by pixel within the viewport.
void overlay_segment(Image& img, glm::vec4 a, glm::vec4 b, const glm::vec3& color) {
  const float da = a.w - a.z, db = b.w - b.z;
  if (da < 0.0f && db < 0.0f) return;
  if (da < 0.0f) a = a + (b - a) * (da / (da - db));
  if (db < 0.0f) b = b + (a - b) * (db / (db - da));
  if (a.w <= 0.0f || b.w <= 0.0f) return;  // on the eye's plane: nothing to see
  const glm::vec2 pa((a.x / a.w + 1.0f) * 0.5f * img.width, (1.0f - a.y / a.w) * 0.5f * img.height);
  const glm::vec2 pb((b.x / b.w + 1.0f) * 0.5f * img.width, (1.0f - b.y / b.w) * 0.5f * img.height);
  const float length = std::max(std::abs(pb.x - pa.x), std::abs(pb.y - pa.y));
  const int steps = static_cast<int>(std::min(length, 8.0f * (img.width + img.height)));
  for (int i = 0; i <= steps; ++i) {
    const glm::vec2 p = steps == 0 ? pa : pa + (pb - pa) * (float(i) / float(steps));
    const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
    std::uint8_t* px = &img.rgba[4 * (static_cast<std::size_t>(y) * img.width + x)];
    for (int k = 0; k < 3; ++k)
      px[k] = static_cast<std::uint8_t>(0.4f * px[k] + 0.6f * 255.0f * color[k]);
  }
}

}  // namespace

void overlay_volumes(Image& image, const Scene& scene, const FramePlan& plan,
                     const VolumeCache& volumes) {
  const glm::vec3 colors[] = {{1.0f, 0.9f, 0.1f}, {0.2f, 0.9f, 1.0f}, {1.0f, 0.3f, 0.8f}};
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      if (plan.volume(l, o).culled) continue;
      const glm::mat4 mvp = plan.view_proj * plan.objects[o].model;
      const PrimitiveList& sides = volumes.volume(l, o).sides;
      for (std::size_t q = 0; q < sides.size(); ++q) {
        const glm::vec4* v = &sides.vertices[q * kQuadCorners];  // u, u_inf, v_inf, v
        const glm::vec4 u = mvp * v[0], u_inf = mvp * v[1], v_inf = mvp * v[2], w = mvp * v[3];
        const glm::vec3& c = colors[l % 3];
        overlay_segment(image, u, w, c);
        overlay_segment(image, u, u_inf, c);
        overlay_segment(image, w, v_inf, c);
      }
    }
}

}  // namespace shadowvol
