// Per-frame silhouette and volume generation. Hot path: reads the topology's flat arrays once
// and writes only to the caller's buffers. See volume.h for the papers and the conventions.
#include "core/volume.h"

#include <algorithm>
#include <cassert>
#include <string>

#include <glm/geometric.hpp>

namespace shadowvol {
namespace {

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

// The signed contribution of one face to an irregular edge's multiplicity (Kim et al. §1.2).
inline int edge_term(const std::int8_t* weights, std::uint32_t ref) {
  const int w = weights[face_of(ref)];
  return is_reversed(ref) ? -w : w;
}

template <bool kRobust>
void append_sides_for(const Topology& topo, const glm::vec4& light, const std::int8_t* weights,
                      IndexRange range, PrimitiveList& sides) {
  const glm::vec3* positions = topo.positions.data();
  // Regular edges, the hot loop: the first face runs the edge along its stored direction and the
  // second against it (or is the always-0 extra slot), so the multiplicity is w(first) -
  // w(second), and almost every edge costs two byte loads and one comparison. Casting edges are
  // rare and scattered, and each needs its vertex pair and two positions from memory: collected
  // first, a block at a time without branches, their loads then overlap instead of each costing
  // a branch miss followed by a chain of cache misses.
  constexpr std::size_t kBlock = 512;
  std::uint32_t casting[kBlock];
  const std::size_t regular_end = std::min(range.end, topo.regular_edge_count());
  const IndexPair* faces = topo.edge_faces.data();
  const IndexPair* vertices = topo.edge_vertices.data();
  for (std::size_t block = range.begin; block < regular_end; block += kBlock) {
    const std::size_t block_end = std::min(block + kBlock, regular_end);
    std::size_t count = 0;
    for (std::size_t e = block; e < block_end; ++e) {
      casting[count] = static_cast<std::uint32_t>(e);
      count += weights[faces[e][0]] != weights[faces[e][1]];
    }
    // Prefetch in two steps: the vertex pair kAhead edges ahead, the positions of the pair
    // kAhead / 2 ahead (whose vertex pair was asked for kAhead / 2 iterations ago).
    constexpr std::size_t kAhead = 16;
    for (std::size_t k = 0; k < count; ++k) {
      if (k + kAhead < count) __builtin_prefetch(&vertices[casting[k + kAhead]]);
      if (k + kAhead / 2 < count) {
        const IndexPair& ahead = vertices[casting[k + kAhead / 2]];
        __builtin_prefetch(&positions[ahead[0]]);
        __builtin_prefetch(&positions[ahead[1]]);
      }
      const std::uint32_t e = casting[k];
      const int w0 = weights[faces[e][0]], w1 = weights[faces[e][1]];
      const glm::vec3& u = positions[vertices[e][0]];
      const glm::vec3& v = positions[vertices[e][1]];
      if constexpr (kRobust) {  // each face closes its own part: one quad each
        if (w0 != 0) push_quad(u, v, light, w0, sides);
        if (w1 != 0) push_quad(u, v, light, -w1, sides);
      } else {
        push_quad(u, v, light, w0 - w1, sides);
      }
    }
  }
  const std::size_t regular = topo.regular_edge_count();
  for (std::size_t e = std::max(range.begin, regular); e < range.end; ++e) {
    const std::size_t i = e - regular;
    const glm::vec3& u = positions[topo.irregular_vertices[i][0]];
    const glm::vec3& v = positions[topo.irregular_vertices[i][1]];
    int multiplicity = 0;
    for (std::uint32_t k = topo.irregular_offsets[i]; k < topo.irregular_offsets[i + 1]; ++k) {
      const int term = edge_term(weights, topo.irregular_faces[k]);
      if constexpr (kRobust) {
        if (term != 0) push_quad(u, v, light, term, sides);
      } else {
        multiplicity += term;
      }
    }
    if (multiplicity != 0) push_quad(u, v, light, multiplicity, sides);
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

namespace {

// The facing of a plane towards a light, in double: float x float products are exact in double,
// so for small integer coordinates the sign is exact.
inline int facing_in_double(const glm::vec4& plane, const glm::vec4& light) {
  const glm::dvec4 p(plane), l(light);
  const double side = (p.x * l.x + p.y * l.y) + (p.z * l.z + p.w * l.w);
  return (side > 0.0) - (side < 0.0);
}

// A face-weight value that no generator produces: "the float test could not decide".
constexpr std::int8_t kUndecided = 2;

}  // namespace

void compute_face_weights(const Topology& topo, const glm::vec4& light, Generator generator,
                          IndexRange faces, std::span<std::int8_t> weights) {
  assert(generator != Generator::automatic && weights.size() >= faces.end - faces.begin);
  // standard counts only light-facing faces (Intel; GPU Gems 3 §11.2.2); robust and
  // multiplicity count every face with its sign (GPU Gems 3 §11.3.1; Kim et al. §1.2).
  const int lowest = generator == Generator::standard ? 0 : -1;
  const std::size_t n = faces.end - faces.begin;
  const float* __restrict px = topo.face_planes.x.data() + faces.begin;
  const float* __restrict py = topo.face_planes.y.data() + faces.begin;
  const float* __restrict pz = topo.face_planes.z.data() + faces.begin;
  const float* __restrict pw = topo.face_planes.w.data() + faces.begin;
  std::int8_t* __restrict out = weights.data();
  // A float dot product with a certified error bound decides almost every face, several to a
  // vector register (the loop has no branches, so it vectorises); the few it cannot (a light
  // within rounding of the plane) are decided again in double. Bound: each of the four terms goes
  // through at most three roundings (one product, two sums), so |error| <= 3u * sum |terms| with
  // u = 2^-24; 8u leaves room for the rounding of the bound itself, and FLT_MIN for underflow.
  // A NaN (from a light so far away that a product overflows) is undecided too.
  constexpr float kRelative = 8.0f * 5.9604645e-8f;
  constexpr float kAbsolute = 1.17549435e-38f;
  const float lx = light.x, ly = light.y, lz = light.z, lw = light.w;
  int undecided = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float tx = px[i] * lx, ty = py[i] * ly, tz = pz[i] * lz, tw = pw[i] * lw;
    const float side = (tx + ty) + (tz + tw);
    const float bound = ((std::abs(tx) + std::abs(ty)) + (std::abs(tz) + std::abs(tw))) * kRelative;
    const bool zero_area = (px[i] == 0.0f) & (py[i] == 0.0f) & (pz[i] == 0.0f);  // exactly 0
    const bool sure = (std::abs(side) > bound + kAbsolute) | zero_area;
    const int facing = (side > 0.0f) - (side < 0.0f);
    const int weight = std::max(facing, lowest);
    const int unsure = !sure;
    out[i] = static_cast<std::int8_t>(weight + unsure * (kUndecided - weight));  // no branch
    undecided |= unsure;
  }
  if (!undecided) return;
  for (std::size_t i = 0; i < n; ++i)
    if (out[i] == kUndecided)
      out[i] = static_cast<std::int8_t>(
          std::max(facing_in_double(topo.face_planes[faces.begin + i], light), lowest));
}

void append_sides(const Topology& topo, const glm::vec4& light, Generator generator,
                  std::span<const std::int8_t> weights, IndexRange edges, VolumeBuffer& out) {
  assert(generator != Generator::automatic);
  assert(weights.size() == weight_buffer_size(topo) && weights.back() == 0);
  if (generator == Generator::robust)
    append_sides_for<true>(topo, light, weights.data(), edges, out.sides);
  else
    append_sides_for<false>(topo, light, weights.data(), edges, out.sides);
}

void append_caps(const Topology& topo, const glm::vec4& light, Generator generator,
                 std::span<const std::int8_t> weights, IndexRange faces, VolumeBuffer& out) {
  assert(generator != Generator::automatic && weights.size() == weight_buffer_size(topo));
  const bool standard = generator == Generator::standard;
  const bool dark_caps = light.w != 0.0f;
  const std::uint32_t* fv = topo.face_vertices.data();
  // At most one cap of each kind per face: reserving that bound spares a growing buffer its
  // repeated reallocation (a no-op once the caller's buffer has grown to size).
  for (PrimitiveList* list : {&out.light_caps, &out.dark_caps}) {
    list->vertices.reserve(list->vertices.size() + kTriangleCorners * (faces.end - faces.begin));
    list->weights.reserve(list->weights.size() + (faces.end - faces.begin));
  }
  for (std::size_t f = faces.begin; f < faces.end; ++f) {
    const int w = weights[f];
    // robust, multiplicity: a face of weight 0 (zero area, or edge-on) has an empty volume.
    // standard: front faces cap the light side, the others the dark side (closed meshes only;
    // the dark cap of an edge-on face is a zero-area triangle at infinity, of a zero-area face
    // nothing at all, so those two are left out).
    const int light_weight = w;
    const int dark_weight =
        standard ? (w == 0 && topo.face_planes[f] != glm::vec4(0.0f) ? 1 : 0) : -w;
    if (light_weight == 0 && dark_weight == 0) continue;
    const glm::vec3& a = topo.positions[fv[3 * f]];
    const glm::vec3& b = topo.positions[fv[3 * f + 1]];
    const glm::vec3& c = topo.positions[fv[3 * f + 2]];
    if (light_weight != 0)
      push_triangle(glm::vec4(a, 1.0f), glm::vec4(b, 1.0f), glm::vec4(c, 1.0f), light_weight,
                    out.light_caps);
    if (dark_caps && dark_weight != 0)
      push_triangle(at_infinity(a, light), at_infinity(b, light), at_infinity(c, light),
                    dark_weight, out.dark_caps);
  }
}

void build_volume(const Topology& topo, const glm::vec4& light, const VolumeOptions& options,
                  std::vector<std::int8_t>& weights, VolumeBuffer& out) {
  const Generator generator = resolve_generator(options.generator, topo.report);
  out.clear();
  weights.assign(weight_buffer_size(topo), 0);
  compute_face_weights(topo, light, generator, {0, topo.face_count()}, weights);
  append_sides(topo, light, generator, weights, {0, topo.edge_count()}, out);
  if (options.caps) append_caps(topo, light, generator, weights, {0, topo.face_count()}, out);
}

}  // namespace shadowvol
