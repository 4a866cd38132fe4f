#include "core/mesh.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace shadowvol {

Expected<void> validate_mesh(const Mesh& mesh, std::string_view source) {
  const std::string where(source);
  if (mesh.indices.size() % 3 != 0)
    return make_error(where + ": index count " + std::to_string(mesh.indices.size()) +
                      " is not a multiple of 3 (a triangle list is expected)");
  if (mesh.triangle_count() == 0) return make_error(where + ": the mesh has no triangles");
  if (mesh.triangle_count() > kMaxTriangles)
    return make_error(where + ": " + std::to_string(mesh.triangle_count()) +
                      " triangles is more than the supported " + std::to_string(kMaxTriangles));
  if (mesh.positions.size() > kMaxVertices)
    return make_error(where + ": " + std::to_string(mesh.positions.size()) +
                      " vertices is more than the supported " + std::to_string(kMaxVertices));
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return make_error(where + ": vertex " + std::to_string(i) +
                        " has a coordinate that is NaN or infinite");
    if (std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxCoordinate)
      return make_error(where + ": vertex " + std::to_string(i) + " lies more than 1e18 from the " +
                        "origin; scale the model down or move it nearer the origin");
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= mesh.positions.size())
      return make_error(where + ": triangle " + std::to_string(i / 3) + " uses vertex " +
                        std::to_string(mesh.indices[i]) + ", but the mesh has only " +
                        std::to_string(mesh.positions.size()) + " vertices");
  }
  return {};
}

}  // namespace shadowvol
