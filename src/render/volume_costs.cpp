#include "render/volume_costs.h"

#include <algorithm>

#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "core/projection.h"
#include "core/shapes.h"
#include "core/topology.h"
#include "core/volume.h"

namespace shadowvol {

const TypicalVolumes& typical_volumes() {
  static const TypicalVolumes volumes = [] {
    TypicalVolumes out;
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 6, 9), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
    const glm::mat4 view_proj =
        infinite_reversed_perspective(glm::radians(60.0f), 1.0f, 0.1f) * view;
    const glm::vec4 light(-6.0f, 5.0f, -2.0f, 1.0f);
    const Topology torus = build_topology(make_bumpy_torus(48, 24, 0.8f, 0.3f));
    VolumeScratch scratch;
    VolumeBuffer volume;
    for (int i = 0; i < 4; ++i) {
      const glm::mat4 model =
          glm::translate(glm::mat4(1.0f),
                         glm::vec3(2.2f * float(i % 2) - 1.1f, 0.8f, 2.2f * float(i / 2) - 1.1f)) *
          glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));
      build_volume(torus, glm::inverse(model) * light, {Generator::automatic, true}, scratch,
                   volume);
      const glm::mat4 mvp = view_proj * model;
      auto add = [&](const PrimitiveList& list, int corners) {
        for (std::size_t p = 0; p < list.size(); ++p) {
          const glm::vec4* v = &list.vertices[p * static_cast<std::size_t>(corners)];
          for (int t = 0; t < (corners == kQuadCorners ? 2 : 1); ++t) {
            for (int k = 0; k < 3; ++k) out.triangles.push_back(mvp * v[kQuadTriangles[3 * t + k]]);
            out.weights.push_back(list.weights[p]);
          }
        }
      };
      add(volume.sides, kQuadCorners);
      add(volume.light_caps, kTriangleCorners);
      add(volume.dark_caps, kTriangleCorners);
    }
    return out;
  }();
  return volumes;
}

VolumeCosts volume_costs(double ms_small, double ms_large, std::size_t vertices,
                         std::uint64_t large_fill) {
  VolumeCosts costs;
  costs.ms_per_vertex = vertices > 0 ? ms_small / static_cast<double>(vertices) : 0.0;
  costs.ms_per_pixel =
      large_fill > 0 ? std::max(ms_large - ms_small, 0.0) / static_cast<double>(large_fill) : 0.0;
  // Neither may be 0: a measured cost of 0 would read as "not measured".
  costs.ms_per_vertex = std::max(costs.ms_per_vertex, 1e-12);
  costs.ms_per_pixel = std::max(costs.ms_per_pixel, 1e-12);
  return costs;
}

}  // namespace shadowvol
