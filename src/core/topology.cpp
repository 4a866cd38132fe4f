// Topology construction: welding, edge table, report. Runs once per mesh (load time), so it
// favours clarity over speed; the per-frame code lives in volume.cpp.
#include "core/topology.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace shadowvol {
namespace {

// Bit pattern of a coordinate with -0 folded onto +0, so that exact welding treats them alike.
std::uint32_t coordinate_bits(float x) {
  const float folded = x + 0.0f;
  std::uint32_t bits;
  std::memcpy(&bits, &folded, sizeof bits);
  return bits;
}

struct PositionKey {
  std::array<std::uint32_t, 3> bits;
  bool operator==(const PositionKey&) const = default;
};

struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the three words
    for (std::uint32_t w : k.bits) h = (h ^ w) * 1099511628211ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

std::vector<std::uint32_t> weld_exact(const std::vector<glm::vec3>& positions,
                                      std::vector<glm::vec3>& welded) {
  std::vector<std::uint32_t> remap(positions.size());
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> first;
  first.reserve(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    const PositionKey key{{coordinate_bits(p.x), coordinate_bits(p.y), coordinate_bits(p.z)}};
    auto [it, inserted] = first.try_emplace(key, static_cast<std::uint32_t>(welded.size()));
    if (inserted) welded.push_back(p + glm::vec3(0.0f));
    remap[i] = it->second;
  }
  return remap;
}

// Grid of cells of side epsilon: a vertex within epsilon of a representative lies in one of the
// 27 cells around its own.
std::vector<std::uint32_t> weld_epsilon(const std::vector<glm::vec3>& positions, float epsilon,
                                        std::vector<glm::vec3>& welded) {
  struct CellHash {
    std::size_t operator()(const std::array<std::int64_t, 3>& c) const {
      return static_cast<std::size_t>(c[0] * 73856093ll ^ c[1] * 19349663ll ^ c[2] * 83492791ll);
    }
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>, CellHash> cells;
  const double inv = 1.0 / static_cast<double>(epsilon);
  auto cell_of = [&](const glm::vec3& p) {
    return std::array<std::int64_t, 3>{static_cast<std::int64_t>(std::floor(p.x * inv)),
                                       static_cast<std::int64_t>(std::floor(p.y * inv)),
                                       static_cast<std::int64_t>(std::floor(p.z * inv))};
  };
  std::vector<std::uint32_t> remap(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    const auto c = cell_of(p);
    std::uint32_t found = UINT32_MAX;
    for (int dz = -1; dz <= 1 && found == UINT32_MAX; ++dz)
      for (int dy = -1; dy <= 1 && found == UINT32_MAX; ++dy)
        for (int dx = -1; dx <= 1 && found == UINT32_MAX; ++dx) {
          auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == cells.end()) continue;
          for (std::uint32_t w : it->second)
            if (glm::distance(welded[w], p) <= epsilon && w < found) found = w;
        }
    if (found == UINT32_MAX) {
      found = static_cast<std::uint32_t>(welded.size());
      welded.push_back(p);
      cells[c].push_back(found);
    }
    remap[i] = found;
  }
  return remap;
}

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

bool is_collapsed(const std::uint32_t* v) { return v[0] == v[1] || v[1] == v[2] || v[2] == v[0]; }

}  // namespace

std::size_t Topology::frame_bytes() const {
  return face_planes.size() * 4 * sizeof(float) + edge_faces.size() * sizeof(IndexPair) +
         irregular_vertices.size() * sizeof(IndexPair) +
         irregular_offsets.size() * sizeof(std::uint32_t) +
         irregular_faces.size() * sizeof(std::uint32_t);
}

namespace {

// The face's plane scaled by a power of two so that its largest normal component lies in
// [0.5, 1): no overflow in float for any finite mesh, and no rounding for small integers.
glm::vec4 face_plane(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
  if (largest == 0.0) return glm::vec4(0.0f);
  int exponent = 0;
  std::frexp(largest, &exponent);
  const glm::dvec3 scaled = n * std::ldexp(1.0, -exponent);
  return glm::vec4(glm::vec3(scaled), static_cast<float>(-glm::dot(scaled, a)));
}

}  // namespace

Topology build_topology(const Mesh& mesh, const WeldOptions& options) {
  assert(validate_mesh(mesh, "build_topology").ok());
  Topology topo;
  topo.vertex_remap = options.epsilon > 0.0f
                          ? weld_epsilon(mesh.positions, options.epsilon, topo.positions)
                          : weld_exact(mesh.positions, topo.positions);
  topo.face_vertices.resize(mesh.indices.size());
  for (std::size_t i = 0; i < mesh.indices.size(); ++i)
    topo.face_vertices[i] = topo.vertex_remap[mesh.indices[i]];

  TopologyReport& r = topo.report;
  r.input_vertices = mesh.positions.size();
  r.vertices = topo.positions.size();
  r.triangles = mesh.triangle_count();

  // One half-edge per side of every non-collapsed triangle, keyed by its undirected edge; sorting
  // groups the faces of each edge together, in face order (deterministic).
  struct HalfEdge {
    std::uint64_t key;  // (low vertex << 32) | high vertex
    std::uint32_t face_ref;
  };
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(mesh.indices.size());
  topo.face_planes.reserve(r.triangles);
  UnionFind components(topo.positions.size());
  for (std::uint32_t f = 0; f < r.triangles; ++f) {
    const std::uint32_t* v = &topo.face_vertices[3 * f];
    components.unite(v[0], v[1]);
    components.unite(v[1], v[2]);
    const glm::dvec3 a(topo.positions[v[0]]), b(topo.positions[v[1]]), c(topo.positions[v[2]]);
    topo.face_planes.push_back(face_plane(a, b, c));
    if (topo.face_planes[f] == glm::vec4(0.0f)) ++r.degenerate_triangles;
    if (is_collapsed(v)) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t from = v[k], to = v[(k + 1) % 3];
      const bool reversed = from > to;
      const std::uint64_t key = (std::uint64_t{std::min(from, to)} << 32) | std::max(from, to);
      half_edges.push_back({key, (f << 1) | (reversed ? kReversedBit : 0u)});
    }
  }
  std::sort(half_edges.begin(), half_edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.key != y.key ? x.key < y.key : x.face_ref < y.face_ref;
  });

  const auto no_face = static_cast<std::uint32_t>(r.triangles);
  topo.edge_faces.reserve(half_edges.size() / 2);
  topo.edge_vertices.reserve(half_edges.size() / 2);
  topo.irregular_offsets.push_back(0);
  for (std::size_t i = 0; i < half_edges.size();) {
    std::size_t j = i;
    int forward = 0, backward = 0;
    for (; j < half_edges.size() && half_edges[j].key == half_edges[i].key; ++j)
      (is_reversed(half_edges[j].face_ref) ? backward : forward) += 1;
    const IndexPair low_high{static_cast<std::uint32_t>(half_edges[i].key >> 32),
                             static_cast<std::uint32_t>(half_edges[i].key & 0xffffffffu)};
    const std::uint32_t first = half_edges[i].face_ref;
    const std::size_t uses = j - i;
    if (uses == 1) ++r.boundary_edges;
    if (uses > 2) ++r.nonmanifold_edges;
    if (uses == 2 && (forward != 1 || backward != 1)) ++r.inconsistent_edges;
    if (uses == 1 || (uses == 2 && forward == 1 && backward == 1)) {
      // Regular: store it in the direction its first face runs it.
      topo.edge_faces.push_back(
          {face_of(first), uses == 2 ? face_of(half_edges[i + 1].face_ref) : no_face});
      topo.edge_vertices.push_back(is_reversed(first) ? IndexPair{low_high[1], low_high[0]}
                                                      : low_high);
    } else {
      topo.irregular_vertices.push_back(low_high);
      for (std::size_t k = i; k < j; ++k) topo.irregular_faces.push_back(half_edges[k].face_ref);
      topo.irregular_offsets.push_back(static_cast<std::uint32_t>(topo.irregular_faces.size()));
    }
    i = j;
  }
  r.edges = topo.edge_count();
  r.closed_manifold =
      r.edges > 0 && r.boundary_edges == 0 && r.nonmanifold_edges == 0 && r.inconsistent_edges == 0;

  // Parts numbered in face order: a part's number is given at its first face's first vertex.
  topo.vertex_part.assign(topo.positions.size(), Topology::kNoPart);
  std::vector<std::uint32_t> part_of_root(topo.positions.size(), Topology::kNoPart);
  for (const std::uint32_t v : topo.face_vertices) {
    std::uint32_t& part = part_of_root[components.find(v)];
    if (part == Topology::kNoPart) part = static_cast<std::uint32_t>(r.components++);
    topo.vertex_part[v] = part;
  }
  // Parts wound outwards: every edge of the part regular with two faces (1: an edge seen; 2: an
  // open or irregular one), and six times the part's signed volume, in double, positive.
  std::vector<std::uint8_t> edges_seen(r.components, 0);
  for (std::size_t e = 0; e < topo.regular_edge_count(); ++e)
    edges_seen[topo.vertex_part[topo.edge_vertices[e][0]]] |=
        topo.edge_faces[e][1] == no_face ? 2 : 1;
  for (const IndexPair& e : topo.irregular_vertices) edges_seen[topo.vertex_part[e[0]]] |= 2;
  std::vector<double> volume(r.components, 0.0);
  for (std::size_t f = 0; f < topo.face_count(); ++f) {
    const glm::dvec3 a(topo.positions[topo.face_vertices[3 * f]]);
    const glm::dvec3 b(topo.positions[topo.face_vertices[3 * f + 1]]);
    const glm::dvec3 c(topo.positions[topo.face_vertices[3 * f + 2]]);
    volume[topo.part_of_face(f)] += glm::dot(a, glm::cross(b, c));
  }
  topo.part_wound_outwards.resize(r.components);
  for (std::size_t p = 0; p < r.components; ++p) {
    topo.part_wound_outwards[p] = edges_seen[p] == 1 && volume[p] > 0.0;
    r.parts_wound_outwards += topo.part_wound_outwards[p];
  }
  return topo;
}

}  // namespace shadowvol
