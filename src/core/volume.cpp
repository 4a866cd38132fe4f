// Per-frame silhouette and volume generation. Hot path: reads the topology's flat arrays once
// and writes only to the caller's buffers. See volume.h for the papers and the conventions.
#include "core/volume.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "core/names.h"

namespace shadowvol {
namespace {

// The weight, and the part where the span records parts, of one primitive; then past it.
inline void finish_primitive(int corners, int weight, std::uint32_t part, PrimitiveSpan& out) {
  out.weights[0] = weight;
  out.vertices += corners;
  out.weights += 1;
  if (out.parts != nullptr) *out.parts++ = part;
}

inline void write_quad(const glm::vec3& u, const glm::vec3& v, const glm::vec4& light,
                       const glm::vec4& far_plane, int weight, std::uint32_t part,
                       PrimitiveSpan& out) {
  out.vertices[0] = glm::vec4(u, 1.0f);
  out.vertices[1] = extrude(u, light, far_plane);
  out.vertices[2] = extrude(v, light, far_plane);
  out.vertices[3] = glm::vec4(v, 1.0f);
  finish_primitive(kQuadCorners, weight, part, out);
}

inline void write_triangle(const glm::vec4& a, const glm::vec4& b, const glm::vec4& c, int weight,
                           std::uint32_t part, PrimitiveSpan& out) {
  out.vertices[0] = a;
  out.vertices[1] = b;
  out.vertices[2] = c;
  finish_primitive(kTriangleCorners, weight, part, out);
}

// The signed contribution of one face to an irregular edge's multiplicity (Kim et al. §1.2).
inline int edge_term(const std::int8_t* weights, std::uint32_t ref) {
  const int w = weights[face_of(ref)];
  return is_reversed(ref) ? -w : w;
}

// The face references of irregular edge i.
inline std::span<const std::uint32_t> irregular_refs(const Topology& topo, std::size_t i) {
  const std::uint32_t first = topo.irregular_offsets[i], last = topo.irregular_offsets[i + 1];
  return std::span(topo.irregular_faces).subspan(first, last - first);
}

// The weights of a face's light cap and dark cap. robust, multiplicity: a face of weight 0
// (zero area, or edge-on) has an empty volume. standard: front faces cap the light side, the
// others the dark side (closed meshes only; the dark cap of an edge-on face is a zero-area
// triangle at infinity, of a zero-area face nothing, so those are left out). No dark caps for a
// directional light extruded to infinity: every vertex goes to the same point at infinity.
struct CapWeights {
  int light;
  int dark;
};
inline CapWeights cap_weights(const Topology& topo, bool standard, bool dark_caps, std::int8_t w,
                              std::size_t f) {
  if (!standard) return {w, dark_caps ? -w : 0};
  const bool back = w == 0 && topo.face_planes[f] != glm::vec4(0.0f);
  return {w, dark_caps && back ? 1 : 0};
}

// Whether the far end of a volume needs closing: not where it is one point (a directional light
// extruded to infinity).
inline bool has_dark_caps(const glm::vec4& light, const glm::vec4& far_plane) {
  return light.w != 0.0f || far_plane != kPlaneAtInfinity;
}

// --- clamped volumes (VolumeClamp) ---------------------------------------------------------

// One face's term of an edge's multiplicity (Kim et al. §1.2), and the leaf that casts it.
struct LeafTerm {
  std::uint32_t leaf;
  int term;
};
// Distinct leaves one edge's terms are summed over before their pieces are merged; an irregular
// edge whose faces lie in more casts each face's term apart, which sums to the same counts.
constexpr int kMaxEdgeLeaves = 16;

// The stretches of depth over which terms of distinct leaves sum to a non-zero weight: emit(begin,
// end, weight) for each, in order, adjacent stretches of one weight merged (§3.3: an edge shared
// by two sub-objects is drawn only where their intervals differ, or its terms do not cancel).
template <class Emit>
void sweep_pieces(std::span<const LeafTerm> terms, const VolumeClamp& clamp, Emit&& emit) {
  struct Cursor {
    const DepthInterval* at;
    const DepthInterval* end;
    int term;
    bool inside;
  };
  std::array<Cursor, kMaxEdgeLeaves> cursors;
  int n = 0;
  for (const LeafTerm& t : terms) {
    const std::span<const DepthInterval> own = clamp.of_leaf(t.leaf);
    if (t.term != 0 && !own.empty())
      cursors[n++] = {own.data(), own.data() + own.size(), t.term, false};
  }
  int weight = 0;
  float start = -INFINITY;
  for (;;) {
    float x = INFINITY;
    bool any = false;
    for (int i = 0; i < n; ++i)
      if (cursors[i].at != cursors[i].end) {
        x = std::min(x, cursors[i].inside ? cursors[i].at->end : cursors[i].at->begin);
        any = true;
      }
    if (!any) break;
    for (bool changed = true; changed;) {  // every boundary at x: enter, leave, enter the next
      changed = false;
      for (int i = 0; i < n; ++i) {
        Cursor& c = cursors[i];
        if (c.at == c.end) continue;
        if (!c.inside && c.at->begin == x) {
          c.inside = changed = true;
        } else if (c.inside && c.at->end == x) {
          c.inside = false;
          ++c.at;
          changed = true;
        }
      }
    }
    int after = 0;
    for (int i = 0; i < n; ++i) after += cursors[i].inside ? cursors[i].term : 0;
    if (after != weight) {
      if (weight != 0) emit(start, x, weight);
      start = x;
      weight = after;
    }
  }
}

// The pieces edge e casts under `clamp`, emit(begin, end, weight) in a fixed order.
template <class Emit>
void edge_pieces(const Topology& topo, const VolumeClamp& clamp, bool robust, const std::int8_t* w,
                 std::size_t e, Emit&& emit) {
  const std::size_t regular = topo.regular_edge_count(), faces = topo.face_count();
  std::array<LeafTerm, kMaxEdgeLeaves> terms;
  int n = 0;
  // Each face's term alone (robust, or too many leaves), or summed per leaf.
  auto alone = [&](std::uint32_t f, int term) {
    const LeafTerm t{clamp.leaf_of(f), term};
    sweep_pieces(std::span(&t, 1), clamp, emit);
  };
  auto add = [&](std::uint32_t f, int term) {  // false when the leaves overflow
    const std::uint32_t leaf = clamp.leaf_of(f);
    int i = 0;
    while (i < n && terms[i].leaf != leaf) ++i;
    if (i == kMaxEdgeLeaves) return false;
    if (i == n) terms[n++] = {leaf, 0};
    terms[i].term += term;
    return true;
  };
  if (e < regular) {
    const IndexPair& f = topo.edge_faces[e];
    const int t0 = w[f[0]], t1 = f[1] < faces ? -w[f[1]] : 0;
    if (robust) {
      if (t0 != 0) alone(f[0], t0);
      if (t1 != 0) alone(f[1], t1);
      return;
    }
    add(f[0], t0);
    if (f[1] < faces) add(f[1], t1);
  } else {
    const std::span<const std::uint32_t> refs = irregular_refs(topo, e - regular);
    bool fits = !robust;
    for (std::uint32_t ref : refs) fits = fits && add(face_of(ref), edge_term(w, ref));
    if (!fits) {
      for (std::uint32_t ref : refs)
        if (const int term = edge_term(w, ref); term != 0) alone(face_of(ref), term);
      return;
    }
  }
  sweep_pieces(std::span(terms.data(), static_cast<std::size_t>(n)), clamp, emit);
}

// Where the ray from p away from the light meets the plane depth = t (-inf: p itself).
// In double: the plane's offset less t, and its products with p, cancel where the mesh's own
// coordinates lie far from the origin, and float would move the end off its depth.
inline glm::vec4 segment_end(const glm::vec3& p, const glm::vec4& light, const VolumeClamp& clamp,
                             float t, const glm::vec4& far_plane) {
  if (t == -INFINITY) return glm::vec4(p, 1.0f);
  if (t == INFINITY) return extrude(p, light, far_plane);
  const glm::dvec3 at(p), n(clamp.depth);
  const glm::dvec3 r = double(light.w) * at - glm::dvec3(light);
  const double along = glm::dot(n, r), before = glm::dot(n, at) + (double(clamp.depth.w) - t);
  return glm::vec4(glm::dvec4(along * at - before * r, along));
}

// The bounds of the intervals of vertex v's leaves strictly inside (begin, end), sorted, once
// each: where every piece along v's ray is cut.
void ray_cuts(const VolumeClamp& clamp, std::uint32_t v, float begin, float end,
              std::vector<float>& cuts) {
  cuts.clear();
  for (const std::uint32_t leaf : clamp.leaves_around(v))
    for (const DepthInterval& i : clamp.of_leaf(leaf))
      for (const float bound : {i.begin, i.end})
        if (bound > begin && bound < end) cuts.push_back(bound);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
}

// A piece [begin, end] of edge u -> v as a ladder: quads (u_i, u_i+1, v_j+1, v_j) stepping along
// both rays at once where their cuts coincide, else along one, the other corner doubled (a
// triangle). emit(u_near, u_far, v_far, v_near), each corner by its depth (-inf: the vertex).
template <class Emit>
void ladder(float begin, float end, const std::vector<float>& u_cuts,
            const std::vector<float>& v_cuts, Emit&& emit) {
  std::size_t i = 0, j = 0;
  float u_at = begin, v_at = begin;
  while (i < u_cuts.size() || j < v_cuts.size()) {
    const float u_next = i < u_cuts.size() ? u_cuts[i] : end;
    const float v_next = j < v_cuts.size() ? v_cuts[j] : end;
    const float step = std::min(u_next, v_next);
    const float u_to = u_next == step ? u_next : u_at, v_to = v_next == step ? v_next : v_at;
    emit(u_at, u_to, v_to, v_at);
    i += u_next == step;
    j += v_next == step;
    u_at = u_to, v_at = v_to;
  }
  emit(u_at, end, end, v_at);
}

}  // namespace

Expected<void> check_light(const glm::vec4& light) {
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(light[i]))
      return make_error("the light has a coordinate that is not finite");
  if (light.w != 0.0f && light.w != 1.0f)
    return make_error("the light's w is " + std::to_string(light.w) +
                      ": use 1 for a point light (x, y, z is its position) or 0 for a "
                      "directional light (x, y, z is the direction it shines from)");
  if (light.w == 0.0f && light.x == 0.0f && light.y == 0.0f && light.z == 0.0f)
    return make_error("a directional light needs a direction: x, y and z are all 0");
  return {};
}

PrimitiveSpan PrimitiveList::grow(std::size_t primitives, int corners, bool with_parts) {
  const std::size_t vertex_start = vertices.size(), weight_start = weights.size();
  vertices.resize(vertex_start + primitives * static_cast<std::size_t>(corners));
  weights.resize(weight_start + primitives);
  if (with_parts) parts.resize(weight_start + primitives);
  return {vertices.data() + vertex_start, weights.data() + weight_start,
          with_parts ? parts.data() + weight_start : nullptr};
}

std::string_view to_string(Generator generator) {
  switch (generator) {
    case Generator::standard:
      return "standard";
    case Generator::robust:
      return "robust";
    case Generator::multiplicity:
      return "multiplicity";
    case Generator::automatic:
      return "auto";
  }
  return "unknown";
}

Expected<Generator> parse_generator(std::string_view name) {
  return parse_name(
      name, {Generator::standard, Generator::robust, Generator::multiplicity, Generator::automatic},
      "generator");
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

glm::vec4 extrude(const glm::vec3& p, const glm::vec4& light, const glm::vec4& far_plane) {
  // p + t r on the plane: t = -(F . (p, 1)) / (n . r); scaled by n . r to stay homogeneous,
  // which keeps the plane at infinity (n = 0, d = -1) exact: (r, 0).
  const glm::vec3 r = light.w * p - glm::vec3(light);
  const glm::vec3 n(far_plane);
  const float along = glm::dot(n, r), before = glm::dot(n, p) + far_plane.w;
  return glm::vec4(along * p - before * r, along);
}

namespace {

// The facing of a plane towards a light, in double: float x float products are exact in double,
// so for small integer coordinates the sign is exact.
inline int facing_in_double(const glm::vec4& plane, const glm::vec4& light) {
  const glm::dvec4 p(plane), l(light);
  const double side = (p.x * l.x + p.y * l.y) + (p.z * l.z + p.w * l.w);
  return (side > 0.0) - (side < 0.0);
}

// A face's weight from its facing (+1, 0 edge-on, -1) for a face of nonzero area.
inline int facing_weight(int facing, bool standard) { return standard ? facing >= 0 : facing; }

// A face-weight value that no generator produces: "the float test could not decide".
constexpr std::int8_t kUndecided = 2;

}  // namespace

void compute_face_weights(const Topology& topo, const glm::vec4& light, Generator generator,
                          IndexRange faces, std::span<std::int8_t> weights) {
  assert(generator != Generator::automatic && weights.size() >= faces.end - faces.begin);
  // standard counts only light-facing faces (Intel; GPU Gems 3 §11.2.2); robust and
  // multiplicity count every face with its sign (GPU Gems 3 §11.3.1; Kim et al. §1.2).
  // A light in a face's plane (on the surface itself: a lamp on a table) sees it edge-on. The
  // shadow is then what lies beyond the mesh along rays from the light (docs/volumes.md, "A light
  // on a surface"): robust and multiplicity give such a face no volume; standard, which sweeps what
  // the back faces do not face, takes it as facing the light, so that the silhouette runs where the
  // back faces end.
  const bool standard = generator == Generator::standard;
  const int lowest = standard ? 0 : -1;
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
    const int weight = std::max(facing, lowest) + (standard & (facing == 0) & !zero_area);
    const int unsure = !sure;
    out[i] = static_cast<std::int8_t>(weight + unsure * (kUndecided - weight));  // no branch
    undecided |= unsure;
  }
  if (!undecided) return;
  for (std::size_t i = 0; i < n; ++i)
    if (out[i] == kUndecided)
      out[i] = static_cast<std::int8_t>(
          facing_weight(facing_in_double(topo.face_planes[faces.begin + i], light), standard));
}

std::size_t find_casting_edges(const Topology& topo, Generator generator,
                               std::span<const std::int8_t> weights, IndexRange edges,
                               std::vector<std::uint32_t>& casting, const VolumeClamp* clamp) {
  assert(generator != Generator::automatic);
  assert(weights.size() == weight_buffer_size(topo) && weights.back() == 0);
  const bool robust = generator == Generator::robust;
  const std::int8_t* w = weights.data();
  if (clamp != nullptr) {  // every edge with a term may cast pieces: not the vectorised loop
    std::size_t quads = 0;
    std::vector<float> u_cuts, v_cuts;
    const std::size_t regular = topo.regular_edge_count();
    for (std::size_t e = edges.begin; e < edges.end; ++e) {
      const IndexPair& uv =
          e < regular ? topo.edge_vertices[e] : topo.irregular_vertices[e - regular];
      std::size_t steps = 0;
      edge_pieces(topo, *clamp, robust, w, e, [&](float begin, float end, int) {
        ray_cuts(*clamp, uv[0], begin, end, u_cuts);
        ray_cuts(*clamp, uv[1], begin, end, v_cuts);
        ladder(begin, end, u_cuts, v_cuts, [&](float, float, float, float) { ++steps; });
      });
      if (steps > 0) casting.push_back(static_cast<std::uint32_t>(e));
      quads += steps;
    }
    return quads;
  }
  std::size_t quads = 0;
  // Regular edges, the hot loop: the first face runs the edge along its stored direction and the
  // second against it (or is the always-0 extra slot), so the multiplicity is w(first) -
  // w(second) and almost every edge costs two byte loads and one comparison. Collected a block
  // at a time without branches: casting edges are rare and scattered, and a branch per edge
  // would miss at every one of them.
  constexpr std::size_t kBlock = 512;
  std::uint32_t block_casting[kBlock];
  const IndexPair* faces = topo.edge_faces.data();
  const std::size_t regular_end = std::min(edges.end, topo.regular_edge_count());
  for (std::size_t block = edges.begin; block < regular_end; block += kBlock) {
    const std::size_t block_end = std::min(block + kBlock, regular_end);
    std::size_t count = 0;
#pragma GCC unroll 4
    for (std::size_t e = block; e < block_end; ++e) {
      block_casting[count] = static_cast<std::uint32_t>(e);
      count += w[faces[e][0]] != w[faces[e][1]];
    }
    casting.insert(casting.end(), block_casting, block_casting + count);
    quads += count;
    if (robust)  // each face closes its own part: one quad per face with a non-zero weight
      for (std::size_t k = 0; k < count; ++k)
        quads += (w[faces[block_casting[k]][0]] != 0) + (w[faces[block_casting[k]][1]] != 0) - 1;
  }
  // Irregular edges (same-direction pairs, fans): their terms summed, or for robust one quad per
  // face, as if the edge were open (GPU Gems 3 §11.3.1 splits such edges in preprocessing).
  const std::size_t regular = topo.regular_edge_count();
  for (std::size_t e = std::max(edges.begin, regular); e < edges.end; ++e) {
    int multiplicity = 0;
    std::size_t terms = 0;
    for (std::uint32_t ref : irregular_refs(topo, e - regular)) {
      const int term = edge_term(w, ref);
      multiplicity += term;
      terms += term != 0;
    }
    const std::size_t edge_quads = robust ? terms : (multiplicity != 0 ? 1 : 0);
    if (edge_quads > 0) casting.push_back(static_cast<std::uint32_t>(e));
    quads += edge_quads;
  }
  return quads;
}

void write_sides(const Topology& topo, const glm::vec4& light, const glm::vec4& far_plane,
                 Generator generator, std::span<const std::int8_t> weights,
                 std::span<const std::uint32_t> casting, PrimitiveSpan out,
                 const VolumeClamp* clamp) {
  assert(generator != Generator::automatic && weights.size() == weight_buffer_size(topo));
  const bool robust = generator == Generator::robust;
  const std::int8_t* w = weights.data();
  const glm::vec3* positions = topo.positions.data();
  const IndexPair* faces = topo.edge_faces.data();
  const IndexPair* vertices = topo.edge_vertices.data();
  const std::size_t regular = topo.regular_edge_count();
  if (clamp != nullptr) {  // each piece: the edge between the planes that bound it, a ladder
    std::vector<float> u_cuts, v_cuts;
    for (const std::uint32_t e : casting) {
      const IndexPair& uv = e < regular ? vertices[e] : topo.irregular_vertices[e - regular];
      const glm::vec3& u = positions[uv[0]];
      const glm::vec3& v = positions[uv[1]];
      const std::uint32_t part = out.parts != nullptr ? topo.vertex_part[uv[0]] : 0;
      edge_pieces(topo, *clamp, robust, w, e, [&](float begin, float end, int weight) {
        ray_cuts(*clamp, uv[0], begin, end, u_cuts);
        ray_cuts(*clamp, uv[1], begin, end, v_cuts);
        ladder(begin, end, u_cuts, v_cuts, [&](float u0, float u1, float v1, float v0) {
          out.vertices[0] = segment_end(u, light, *clamp, u0, far_plane);
          out.vertices[1] = segment_end(u, light, *clamp, u1, far_plane);
          out.vertices[2] = segment_end(v, light, *clamp, v1, far_plane);
          out.vertices[3] = segment_end(v, light, *clamp, v0, far_plane);
          finish_primitive(kQuadCorners, weight, part, out);
        });
      });
    }
    return;
  }
  // Each casting edge needs its vertex pair and two positions from far-apart places in memory:
  // prefetch in two steps, the pair kAhead edges ahead, the positions kAhead / 2 ahead (whose
  // pair was asked for kAhead / 2 iterations ago), so that the misses overlap.
  constexpr std::size_t kAhead = 16;
  for (std::size_t k = 0; k < casting.size(); ++k) {
    if (k + kAhead < casting.size() && casting[k + kAhead] < regular)
      __builtin_prefetch(&vertices[casting[k + kAhead]]);
    if (k + kAhead / 2 < casting.size() && casting[k + kAhead / 2] < regular) {
      const IndexPair& ahead = vertices[casting[k + kAhead / 2]];
      __builtin_prefetch(&positions[ahead[0]]);
      __builtin_prefetch(&positions[ahead[1]]);
    }
    const std::uint32_t e = casting[k];
    if (e < regular) {
      const int w0 = w[faces[e][0]], w1 = w[faces[e][1]];
      const glm::vec3& u = positions[vertices[e][0]];
      const glm::vec3& v = positions[vertices[e][1]];
      const std::uint32_t part = out.parts != nullptr ? topo.vertex_part[vertices[e][0]] : 0;
      if (!robust) {
        write_quad(u, v, light, far_plane, w0 - w1, part, out);
      } else {
        if (w0 != 0) write_quad(u, v, light, far_plane, w0, part, out);
        if (w1 != 0) write_quad(u, v, light, far_plane, -w1, part, out);
      }
      continue;
    }
    const std::size_t i = e - regular;
    const glm::vec3& u = positions[topo.irregular_vertices[i][0]];
    const glm::vec3& v = positions[topo.irregular_vertices[i][1]];
    const std::uint32_t part =
        out.parts != nullptr ? topo.vertex_part[topo.irregular_vertices[i][0]] : 0;
    int multiplicity = 0;
    for (std::uint32_t ref : irregular_refs(topo, i)) {
      const int term = edge_term(w, ref);
      if (robust && term != 0) write_quad(u, v, light, far_plane, term, part, out);
      multiplicity += term;
    }
    if (!robust) write_quad(u, v, light, far_plane, multiplicity, part, out);
  }
}

CapCount count_caps(const Topology& topo, const glm::vec4& light, const glm::vec4& far_plane,
                    Generator generator, std::span<const std::int8_t> weights, IndexRange faces,
                    const VolumeClamp* clamp) {
  assert(generator != Generator::automatic && weights.size() == weight_buffer_size(topo));
  const bool standard = generator == Generator::standard;
  const bool dark_caps = has_dark_caps(light, far_plane);
  CapCount count;
  if (clamp != nullptr) {
    for (std::size_t f = faces.begin; f < faces.end; ++f) {
      if (weights[f] == 0) continue;  // no volume of its own (edge-on, zero area, standard's back)
      for (const DepthInterval& i : clamp->of_leaf(clamp->leaf_of(f))) {
        ++(i.begin == -INFINITY ? count.light : count.dark);
        count.dark += i.end != INFINITY || dark_caps;
      }
    }
    return count;
  }
  for (std::size_t f = faces.begin; f < faces.end; ++f) {
    const CapWeights c = cap_weights(topo, standard, dark_caps, weights[f], f);
    count.light += c.light != 0;
    count.dark += c.dark != 0;
  }
  return count;
}

void write_caps(const Topology& topo, const glm::vec4& light, const glm::vec4& far_plane,
                Generator generator, std::span<const std::int8_t> weights, IndexRange faces,
                PrimitiveSpan light_caps, PrimitiveSpan dark_caps, const VolumeClamp* clamp) {
  assert(generator != Generator::automatic && weights.size() == weight_buffer_size(topo));
  const bool standard = generator == Generator::standard;
  const bool closed_far = has_dark_caps(light, far_plane);
  const std::uint32_t* fv = topo.face_vertices.data();
  if (clamp != nullptr) {
    for (std::size_t f = faces.begin; f < faces.end; ++f) {
      const int w = weights[f];
      if (w == 0) continue;
      const std::array<glm::vec3, 3> p{topo.positions[fv[3 * f]], topo.positions[fv[3 * f + 1]],
                                       topo.positions[fv[3 * f + 2]]};
      const std::uint32_t part = light_caps.parts != nullptr ? topo.vertex_part[fv[3 * f]] : 0;
      auto cap = [&](float t, int weight, PrimitiveSpan& out) {
        write_triangle(segment_end(p[0], light, *clamp, t, far_plane),
                       segment_end(p[1], light, *clamp, t, far_plane),
                       segment_end(p[2], light, *clamp, t, far_plane), weight, part, out);
      };
      for (const DepthInterval& i : clamp->of_leaf(clamp->leaf_of(f))) {
        cap(i.begin, w, i.begin == -INFINITY ? light_caps : dark_caps);
        if (i.end != INFINITY || closed_far) cap(i.end, -w, dark_caps);
      }
    }
    return;
  }
  for (std::size_t f = faces.begin; f < faces.end; ++f) {
    const CapWeights c = cap_weights(topo, standard, closed_far, weights[f], f);
    if (c.light == 0 && c.dark == 0) continue;
    const glm::vec3& a = topo.positions[fv[3 * f]];
    const glm::vec3& b = topo.positions[fv[3 * f + 1]];
    const glm::vec3& d = topo.positions[fv[3 * f + 2]];
    const std::uint32_t part = light_caps.parts != nullptr ? topo.vertex_part[fv[3 * f]] : 0;
    if (c.light != 0)
      write_triangle(glm::vec4(a, 1.0f), glm::vec4(b, 1.0f), glm::vec4(d, 1.0f), c.light, part,
                     light_caps);
    if (c.dark != 0)
      write_triangle(extrude(a, light, far_plane), extrude(b, light, far_plane),
                     extrude(d, light, far_plane), c.dark, part, dark_caps);
  }
}

void build_vertex_leaves(const Topology& topo, std::span<const std::uint32_t> face_leaf,
                         std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& leaves) {
  const std::size_t vertices = topo.positions.size();
  std::uint32_t leaf_count = 0;
  for (const std::uint32_t leaf : face_leaf) leaf_count = std::max(leaf_count, leaf + 1);
  std::vector<std::uint64_t> keys;
  keys.reserve(topo.face_vertices.size());
  for (std::size_t i = 0; i < topo.face_vertices.size(); ++i)
    keys.push_back(std::uint64_t{topo.face_vertices[i]} * leaf_count + face_leaf[i / 3]);
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  offsets.assign(vertices + 1, 0);
  leaves.clear();
  for (const std::uint64_t key : keys) {
    ++offsets[key / leaf_count + 1];
    leaves.push_back(static_cast<std::uint32_t>(key % leaf_count));
  }
  for (std::size_t v = 0; v < vertices; ++v) offsets[v + 1] += offsets[v];
}

void build_volume(const Topology& topo, const glm::vec4& light, const VolumeOptions& options,
                  VolumeScratch& scratch, VolumeBuffer& out, const VolumeClamp* clamp) {
  assert(clamp == nullptr || options.caps);
  const Generator generator = resolve_generator(options.generator, topo.report);
  out.clear();
  scratch.weights.assign(weight_buffer_size(topo), 0);
  compute_face_weights(topo, light, generator, {0, topo.face_count()}, scratch.weights);
  scratch.casting.clear();
  const std::size_t quads = find_casting_edges(topo, generator, scratch.weights,
                                               {0, topo.edge_count()}, scratch.casting, clamp);
  write_sides(topo, light, options.far_plane, generator, scratch.weights, scratch.casting,
              out.sides.grow(quads, kQuadCorners, options.parts), clamp);
  if (!options.caps) return;
  const IndexRange all_faces{0, topo.face_count()};
  const CapCount caps =
      count_caps(topo, light, options.far_plane, generator, scratch.weights, all_faces, clamp);
  write_caps(topo, light, options.far_plane, generator, scratch.weights, all_faces,
             out.light_caps.grow(caps.light, kTriangleCorners, options.parts),
             out.dark_caps.grow(caps.dark, kTriangleCorners, options.parts), clamp);
}

}  // namespace shadowvol
