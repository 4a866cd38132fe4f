// Per-frame silhouette and volume generation. Hot path: reads the topology's flat arrays once
// and writes only to the caller's buffers. See volume.h for the papers and the conventions.
#include "core/volume.h"

#include <cassert>
#include <string>

#include <glm/geometric.hpp>

namespace shadowvol {
namespace {

// How much a face of the given facing contributes to the edges and caps around it. standard
// counts only light-facing faces (Intel; GPU Gems 3 §11.2.2); robust and multiplicity count
// every face with its sign (GPU Gems 3 §11.3.1; Kim et al. §1.2).
template <Generator G>
inline int face_weight(std::int8_t facing) {
  if constexpr (G == Generator::standard) return facing > 0 ? 1 : 0;
  else return facing;
}

inline glm::vec4 at_infinity(const glm::vec3& p, const glm::vec4& light) {
  return glm::vec4(light.w * p - glm::vec3(light), 0.0f);
}

inline void push_quad(const glm::vec3& u, const glm::vec3& v, const glm::vec4& light, int weight,
                      PrimitiveList& sides) {
  sides.vertices.push_back(glm::vec4(u, 1.0f));
  sides.vertices.push_back(at_infinity(u, light));
  sides.vertices.push_back(at_infinity(v, light));
  sides.vertices.push_back(glm::vec4(v, 1.0f));
  sides.weights.push_back(weight);
}

template <Generator G>
void append_sides_for(const Topology& topo, const glm::vec4& light,
                      std::span<const std::int8_t> facing, IndexRange edges, PrimitiveList& sides) {
  const std::uint32_t* offsets = topo.edge_face_offsets.data();
  const std::uint32_t* refs = topo.edge_faces.data();
  for (std::size_t e = edges.begin; e < edges.end; ++e) {
    const std::uint32_t first = offsets[e], last = offsets[e + 1];
    const glm::vec3& u = topo.positions[topo.edge_vertices[2 * e]];
    const glm::vec3& v = topo.positions[topo.edge_vertices[2 * e + 1]];
    if constexpr (G == Generator::robust) {
      // A consistent manifold pair of equal facing is interior to one part: nothing to extrude.
      if (last - first == 2 && is_reversed(refs[first]) != is_reversed(refs[first + 1]) &&
          facing[face_of(refs[first])] == facing[face_of(refs[first + 1])])
        continue;
      for (std::uint32_t i = first; i < last; ++i) {
        const int w = face_weight<G>(facing[face_of(refs[i])]);
        if (w != 0) push_quad(u, v, light, is_reversed(refs[i]) ? -w : w, sides);
      }
    } else {
      int multiplicity = 0;
      for (std::uint32_t i = first; i < last; ++i) {
        const int w = face_weight<G>(facing[face_of(refs[i])]);
        multiplicity += is_reversed(refs[i]) ? -w : w;
      }
      if (multiplicity != 0) push_quad(u, v, light, multiplicity, sides);
    }
  }
}

void push_triangle(const glm::vec4& a, const glm::vec4& b, const glm::vec4& c, int weight,
                   PrimitiveList& list) {
  list.vertices.push_back(a);
  list.vertices.push_back(b);
  list.vertices.push_back(c);
  list.weights.push_back(weight);
}

}  // namespace

std::string_view to_string(Generator generator) {
  switch (generator) {
    case Generator::standard: return "standard";
    case Generator::robust: return "robust";
    case Generator::multiplicity: return "multiplicity";
    case Generator::automatic: return "auto";
  }
  return "unknown";
}

Expected<Generator> parse_generator(std::string_view name) {
  for (Generator g : {Generator::standard, Generator::robust, Generator::multiplicity,
                      Generator::automatic})
    if (name == to_string(g)) return g;
  return make_error("unknown generator '" + std::string(name) +
                    "': expected standard, robust, multiplicity or auto");
}

Generator resolve_generator(Generator requested, const TopologyReport& report) {
  if (requested != Generator::automatic) return requested;
  return report.closed_manifold ? Generator::standard : Generator::multiplicity;
}

Expected<void> check_generator(Generator requested, const TopologyReport& report,
                               std::string_view source) {
  if (requested != Generator::standard || report.closed_manifold) return {};
  return make_error(std::string(source) +
                    ": the standard generator needs a closed 2-manifold, but this mesh has " +
                    std::to_string(report.boundary_edges) + " boundary, " +
                    std::to_string(report.nonmanifold_edges) + " non-manifold and " +
                    std::to_string(report.inconsistent_edges) +
                    " inconsistently oriented edges; use robust, multiplicity or auto");
}

void VolumeBuffer::append(const VolumeBuffer& other) {
  for (auto [to, from] : {std::pair{&sides, &other.sides},
                          std::pair{&light_caps, &other.light_caps},
                          std::pair{&dark_caps, &other.dark_caps}}) {
    to->vertices.insert(to->vertices.end(), from->vertices.begin(), from->vertices.end());
    to->weights.insert(to->weights.end(), from->weights.begin(), from->weights.end());
  }
}

void compute_facing(const Topology& topo, const glm::vec4& light, IndexRange faces,
                    std::span<std::int8_t> facing) {
  assert(facing.size() >= faces.end - faces.begin);
  const glm::dvec3 light_xyz(light);
  const double light_w = light.w;
  const std::uint32_t* fv = topo.face_vertices.data();
  for (std::size_t f = faces.begin; f < faces.end; ++f) {
    const glm::dvec3 a(topo.positions[fv[3 * f]]);
    const glm::dvec3 b(topo.positions[fv[3 * f + 1]]);
    const glm::dvec3 c(topo.positions[fv[3 * f + 2]]);
    const double side = glm::dot(glm::cross(b - a, c - a), light_xyz - light_w * a);
    facing[f - faces.begin] = static_cast<std::int8_t>((side > 0.0) - (side < 0.0));
  }
}

void append_sides(const Topology& topo, const glm::vec4& light, Generator generator,
                  std::span<const std::int8_t> facing, IndexRange edges, VolumeBuffer& out) {
  assert(facing.size() == topo.face_count());
  switch (generator) {
    case Generator::standard:
      return append_sides_for<Generator::standard>(topo, light, facing, edges, out.sides);
    case Generator::robust:
      return append_sides_for<Generator::robust>(topo, light, facing, edges, out.sides);
    case Generator::multiplicity:
      return append_sides_for<Generator::multiplicity>(topo, light, facing, edges, out.sides);
    case Generator::automatic: assert(!"resolve the generator first"); return;
  }
}

void append_caps(const Topology& topo, const glm::vec4& light, Generator generator,
                 std::span<const std::int8_t> facing, IndexRange faces, VolumeBuffer& out) {
  assert(generator != Generator::automatic && facing.size() == topo.face_count());
  const bool standard = generator == Generator::standard;
  const bool dark_caps = light.w != 0.0f;
  const std::uint32_t* fv = topo.face_vertices.data();
  for (std::size_t f = faces.begin; f < faces.end; ++f) {
    const int s = facing[f];
    if (s == 0) continue;  // zero area or edge-on to the light: an empty volume
    const glm::vec3& a = topo.positions[fv[3 * f]];
    const glm::vec3& b = topo.positions[fv[3 * f + 1]];
    const glm::vec3& c = topo.positions[fv[3 * f + 2]];
    // standard: front faces cap the light side, back faces the dark side (closed meshes only).
    const int light_weight = standard ? (s > 0 ? 1 : 0) : s;
    const int dark_weight = standard ? (s < 0 ? 1 : 0) : -s;
    if (light_weight != 0)
      push_triangle(glm::vec4(a, 1.0f), glm::vec4(b, 1.0f), glm::vec4(c, 1.0f), light_weight,
                    out.light_caps);
    if (dark_caps && dark_weight != 0)
      push_triangle(at_infinity(a, light), at_infinity(b, light), at_infinity(c, light),
                    dark_weight, out.dark_caps);
  }
}

void build_volume(const Topology& topo, const glm::vec4& light, const VolumeOptions& options,
                  std::vector<std::int8_t>& facing, VolumeBuffer& out) {
  const Generator generator = resolve_generator(options.generator, topo.report);
  out.clear();
  facing.resize(topo.face_count());
  compute_facing(topo, light, {0, topo.face_count()}, facing);
  append_sides(topo, light, generator, facing, {0, topo.edge_count()}, out);
  if (options.caps) append_caps(topo, light, generator, facing, {0, topo.face_count()}, out);
}

}  // namespace shadowvol
