// shadowvol core: silhouettes and shadow-volume geometry, per frame, per light.
//
// Owns: facing per face (computed once per face per light, never per edge), the signed weight
// of every side quad, and the caps. One implementation serves every generator:
//
//   - multiplicity (Kim, Kim & Turk 2008, §1.1-1.2): the general one, exact on any triangle
//     soup. The side quad of edge e has weight m(e) = sum over the faces f using e of
//     facing(f) * orient(f, e), where facing is +1 / -1 / 0 (light in front / behind / in the
//     plane or zero area) and orient is +1 when f runs along e's stored direction, -1 when
//     against. Caps per face: light cap weight facing(f), dark cap weight -facing(f).
//   - robust (GPU Gems 3 ch. 11, §11.3.1): the per-face form of the same sum. Every face, front
//     or back, closes its own volume; an edge is extruded once per face unless its two faces
//     are a consistent manifold pair with the same facing. Non-manifold and inconsistently
//     wound edges are treated as open, as the chapter's preprocessing does. Each quad has
//     weight +-1 (what a stencil buffer can add in one draw), so it emits more primitives.
//   - standard (Intel, "mainstream shadow volumes"; GPU Gems 3 §11.2.2): only faces that face the
//     light count (facing > 0). Silhouette quads get weight +-1, light cap = front faces,
//     dark cap = back faces projected to infinity. Exact only on closed 2-manifolds
//     (TopologyReport::closed_manifold); check_generator refuses it elsewhere.
//   - automatic: standard on closed manifolds, multiplicity otherwise.
//
// The law every generator keeps (tests/core/volume_law_test.cpp proves it with exact
// arithmetic): for any point P, the signed number of volume primitives crossed on a path from a
// point outside every shadow to P (+weight entering through the front side of a primitive,
// -weight through its back) equals the number of caster surfaces on the segment from P to the
// light: all of them for multiplicity and robust, the light-facing ones for standard.
//
// Orientation: every primitive is counter-clockwise seen from outside its volume (its front
// side), as in the GPU Gems 3 listing 11-1. A weight w on a primitive means "this primitive,
// drawn w times" (w < 0: drawn |w| times with the opposite winding).
//
// Where a volume ends: extruded to infinity (w = 0) by default, or ended on a finite far plane
// (see kPlaneAtInfinity), the same volume cut where no receiver lies. Clamped (VolumeClamp, CC
// shadow volumes §3.2.1, §3.3): kept only over intervals of depth, per sub-object of the mesh.
//
// Spaces: everything is in the mesh's own space; pass the light and the far plane in that space
// too (the inverse model matrix times the world light; the transpose of the model matrix times
// the world plane). Vertices at infinity have w = 0. A caller that maps the
// volume by a transform with negative determinant must negate every weight, since the
// transform reverses every primitive's winding.
//
// Pure: no I/O, no threads, no globals. The range functions let a caller split one mesh over
// threads (render/volume_builder.h does, with oneTBB) and get the same output in the same order.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/expected.h"
#include "core/topology.h"

namespace shadowvol {

enum class Generator : std::uint8_t { standard, robust, multiplicity, automatic };

std::string_view to_string(Generator generator);
// Accepts "standard", "robust", "multiplicity", "auto"; the error lists the valid names.
Expected<Generator> parse_generator(std::string_view name);

// What `automatic` becomes for a mesh with this report; other generators are returned as given.
Generator resolve_generator(Generator requested, const TopologyReport& report);

// Refuses `standard` on a mesh that is not a closed 2-manifold (its volumes would leak), naming
// `source` and the offending counts. Any other generator is accepted for any mesh.
Expected<void> check_generator(Generator requested, const TopologyReport& report,
                               std::string_view source);

// The far plane F = (n, d) of a volume: every extrusion ends where it meets F, and the volume is
// the infinite one cut by the half-space n.x + d <= 0 (the kept side), closed there by dark caps.
// Points on the kept side are in the cut volume exactly when they are in the infinite one, so a
// far plane beyond every receiver changes no shadow and leaves less to rasterize (Laine 2005 §7
// extrudes to the scene's extent). The default, the plane at infinity (0, 0, 0, -1), keeps every
// finite point and gives the classic volume. Precondition for a finite F, which the caller
// ensures from the caster's bounds: every caster vertex p lies on the kept side, and its ray
// away from the light meets F ahead (n . r > 0, r = light.w * p - light.xyz).
inline const glm::vec4 kPlaneAtInfinity{0.0f, 0.0f, 0.0f, -1.0f};

// Where the ray from p away from the light meets the far plane, in homogeneous form (w = n . r;
// w = 0 for the plane at infinity). Positive scaling keeps every primitive's winding.
glm::vec4 extrude(const glm::vec3& p, const glm::vec4& light, const glm::vec4& far_plane);

// Refuses what is not a light: a non-finite coordinate, w other than 1 (point) or 0
// (directional), or a directional light without a direction.
Expected<void> check_light(const glm::vec4& light);

// Allocates like std::allocator but leaves new elements of trivial types uninitialised on
// resize: a volume list is resized to its final size and then written in full, so zeroing it
// first would write every byte twice.
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}  // NOLINT
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;  // default-, not value-initialised
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using VolumeVector = std::vector<T, UninitializedAllocator<T>>;

// Where a writer puts primitives: `vertices` has room for kCorners per primitive, `weights` one,
// and `parts`, where not null, one.
struct PrimitiveSpan {
  glm::vec4* vertices = nullptr;
  std::int32_t* weights = nullptr;
  std::uint32_t* parts = nullptr;
};

// A list of volume primitives of one kind: `vertices` holds kCorners homogeneous vertices per
// primitive, `weights` one signed weight per primitive, and `parts` (only where the volume was
// built with VolumeOptions::parts, else empty) the part of the mesh (Topology::vertex_part) that
// cast each one.
struct PrimitiveList {
  VolumeVector<glm::vec4> vertices;
  VolumeVector<std::int32_t> weights;
  VolumeVector<std::uint32_t> parts;

  std::size_t size() const { return weights.size(); }
  void clear() {
    vertices.clear();
    weights.clear();
    parts.clear();
  }
  // Makes room for `primitives` more of `corners` vertices each, and their parts if `with_parts`,
  // uninitialised, and says where.
  PrimitiveSpan grow(std::size_t primitives, int corners, bool with_parts = false);
};

// The caller owns it and reuses it from frame to frame: clear() keeps the capacity, so a frame
// that emits no more than an earlier one allocates nothing.
struct VolumeBuffer {
  // Side quads (u, u_far, v_far, v): the edge u->v extruded away from the light, u and v with
  // w = 1, their extrusions on the far plane (w = 0 at infinity). Split into triangles by
  // kQuadTriangles.
  PrimitiveList sides;
  // Light caps: the caster triangles themselves, in their own vertex order (the order the depth
  // pass draws them, so that they rasterize to exactly the surface's depth); a cap facing away
  // from the light gets a negative weight instead of a reversed order.
  PrimitiveList light_caps;
  // Dark caps: caster triangles projected onto the far plane, own vertex order, signed weight.
  // Empty for directional lights extruded to infinity: every vertex projects to the same point.
  PrimitiveList dark_caps;

  void clear() {
    sides.clear();
    light_caps.clear();
    dark_caps.clear();
  }
  std::size_t primitive_count() const {
    return sides.size() + light_caps.size() + dark_caps.size();
  }
};

// CC shadow volumes' clamping (Lloyd, Wendt, Govindaraju and Manocha 2004, §3.2.1 and §3.3): the
// volume kept only where its depth lies in one of the intervals of the sub-object (leaf) that
// casts it, each piece (a segment) closed by caps where it starts and ends.
//
// Depth is the affine function depth(x) = dot(depth, (x, 1)) in the mesh's space (a light view's
// axis), growing along every ray away from the light from each caster vertex (n . r > 0 in
// extrude's terms). An interval [begin, end] of a leaf: begin -inf starts at the caster itself
// (its light caps; a leaf's first interval must, so that it holds the leaf's own points), else
// at the plane depth = begin, which lies beyond every vertex of the leaf's faces; end +inf
// reaches the volume's far plane (VolumeOptions::far_plane), else the plane depth = end. A
// segment is the volume between its two planes: side quads from the silhouette edge projected
// onto the first to its projection onto the second, each face of weight w projected onto the
// first plane (weight w) and onto the second (-w). A leaf is no closed mesh, so standard too
// closes its segments by its front faces (not by its back faces, which cap a whole closed mesh
// alike). Both caps lie in the scene, so every rule counts them (dark_caps holds both kinds);
// only the light caps lie on surfaces.
//
// Sub-objects (§3.3): an edge between faces of two leaves casts, over each stretch of depth, the
// sum of the terms of the leaves whose intervals hold it (the paper merges the occupied intervals
// on both sides of a shared edge): where both sides are kept alike it casts what the whole mesh
// casts, nothing for an edge that is no silhouette. The robust generator keeps weights +-1: each
// face's term over its own leaf's intervals. A leaf without intervals casts nothing (culled).
//
// Watertight: the ray of a vertex may bound pieces that end at different planes on its two sides
// (one leaf's interval ends where the other's goes on). A rasterizer leaves cracks at such a
// T-junction, so every piece is cut along each of its vertices' rays at every bound of the
// intervals of the leaves around that vertex (vertex_leaves), the pieces of its neighbours
// likewise: a piece is then a ladder of quads, some with two corners at one point (triangles).
//
// The law (volume_law_test.cpp): the count at P is the number of caster surfaces between P and
// the light whose leaf holds depth(P) in one of its intervals.
struct DepthInterval {
  float begin = 0.0f, end = 0.0f;
  bool operator==(const DepthInterval&) const = default;
};

struct VolumeClamp {
  glm::vec4 depth{0.0f};
  // Per face, its leaf; empty: every face in leaf 0. And per vertex, the leaves of the faces
  // around it: vertex v's are vertex_leaves[vertex_leaf_offsets[v] .. [v + 1]) (empty with
  // face_leaf). Point into storage the caller keeps alive while the clamp is used (the
  // sub-objects of the mesh).
  std::span<const std::uint32_t> face_leaf;
  std::span<const std::uint32_t> vertex_leaf_offsets, vertex_leaves;
  // Leaf k's intervals are intervals[offsets[k] .. offsets[k + 1]), sorted, disjoint.
  std::vector<std::uint32_t> offsets;
  std::vector<DepthInterval> intervals;

  std::size_t leaf_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::span<const DepthInterval> of_leaf(std::size_t leaf) const {
    return std::span(intervals).subspan(offsets[leaf], offsets[leaf + 1] - offsets[leaf]);
  }
  std::uint32_t leaf_of(std::size_t face) const { return face_leaf.empty() ? 0 : face_leaf[face]; }
  // The leaves of the faces around vertex v.
  std::span<const std::uint32_t> leaves_around(std::size_t v) const {
    static constexpr std::uint32_t kOnlyLeaf[1] = {0};
    if (vertex_leaf_offsets.empty()) return kOnlyLeaf;
    return vertex_leaves.subspan(vertex_leaf_offsets[v],
                                 vertex_leaf_offsets[v + 1] - vertex_leaf_offsets[v]);
  }
  // The plane depth = t as a far plane (kept side depth <= t); +inf: `far_plane`.
  glm::vec4 plane_at(float t, const glm::vec4& far_plane) const {
    return t == INFINITY ? far_plane : glm::vec4(glm::vec3(depth), depth.w - t);
  }
  // The same clamp: same depth, same leaves (by address) and intervals.
  bool operator==(const VolumeClamp& o) const {
    return depth == o.depth && face_leaf.data() == o.face_leaf.data() &&
           face_leaf.size() == o.face_leaf.size() && offsets == o.offsets &&
           intervals == o.intervals;
  }
};

inline constexpr int kQuadCorners = 4;
inline constexpr int kTriangleCorners = 3;
// The one split of a side quad into two triangles that every consumer uses, so that neighbouring
// quads share the edges u-u_inf exactly.
inline constexpr int kQuadTriangles[6] = {0, 1, 2, 0, 2, 3};

struct IndexRange {
  std::size_t begin = 0;
  std::size_t end = 0;
};

// The weight of every face in [faces.begin, faces.end) for this light, as `generator` counts
// it, into weights[f - faces.begin]. Its facing first: +1 if the light is on the side face f's
// normal points to, -1 if on the other side, 0 if the light lies in the face's plane or the face
// has zero area (computed once per face per light, from Topology::face_planes). The weight is the
// facing for robust and multiplicity, and 1 for front faces, 0 for the others, for standard.
// `light` is homogeneous: (x, y, z, 1) a point light, (x, y, z, 0) a directional light shining
// from direction (x, y, z) towards -(x, y, z). `generator` must be resolved (not automatic).
void compute_face_weights(const Topology& topo, const glm::vec4& light, Generator generator,
                          IndexRange faces, std::span<std::int8_t> weights);

// The face-weight buffer of a mesh has one slot per face plus one extra slot, always 0, that
// stands for the missing second face of every boundary edge (Topology::edge_faces).
inline std::size_t weight_buffer_size(const Topology& topo) { return topo.face_count() + 1; }

// Side quads in two steps, so that threads can each write their part of one output in place.
// Edges are numbered regular first, then irregular (Topology::edge_count); `weights` is the
// whole mesh's weight buffer (weight_buffer_size entries) for the same generator and light.
//
// find_casting_edges appends, in edge order, the edges of `edges` that cast side quads to
// `casting` and returns how many quads they cast (one each; robust: one per face term).
// `clamp`, where not null: the segments' quads (VolumeClamp).
std::size_t find_casting_edges(const Topology& topo, Generator generator,
                               std::span<const std::int8_t> weights, IndexRange edges,
                               std::vector<std::uint32_t>& casting,
                               const VolumeClamp* clamp = nullptr);
// write_sides writes the quads of `casting`, in order, to `out` (room for the count
// find_casting_edges returned with the same clamp).
void write_sides(const Topology& topo, const glm::vec4& light, const glm::vec4& far_plane,
                 Generator generator, std::span<const std::int8_t> weights,
                 std::span<const std::uint32_t> casting, PrimitiveSpan out,
                 const VolumeClamp* clamp = nullptr);

// Caps in two steps likewise: count_caps says how many light and dark caps the faces in
// `faces` have, write_caps writes them in face order (clamped: per face, its segments' caps in
// order, the starting caps of segments that begin beyond the caster among the dark caps).
struct CapCount {
  std::size_t light = 0;
  std::size_t dark = 0;
};
CapCount count_caps(const Topology& topo, const glm::vec4& light, const glm::vec4& far_plane,
                    Generator generator, std::span<const std::int8_t> weights, IndexRange faces,
                    const VolumeClamp* clamp = nullptr);
void write_caps(const Topology& topo, const glm::vec4& light, const glm::vec4& far_plane,
                Generator generator, std::span<const std::int8_t> weights, IndexRange faces,
                PrimitiveSpan light_caps, PrimitiveSpan dark_caps,
                const VolumeClamp* clamp = nullptr);

// The leaves around each vertex (VolumeClamp::vertex_leaves), from each face's: vertex v's are
// leaves[offsets[v] .. offsets[v + 1]), sorted, each once.
void build_vertex_leaves(const Topology& topo, std::span<const std::uint32_t> face_leaf,
                         std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& leaves);

struct VolumeOptions {
  Generator generator = Generator::automatic;
  bool caps = true;  // only z-fail needs caps; z-pass draws the sides alone
  glm::vec4 far_plane = kPlaneAtInfinity;
  // Also record the part of every primitive (PrimitiveList::parts): the primitives of one part are
  // exactly the volume that part alone casts, since every edge and face lies in one part, so a
  // renderer may count each part by a rule of its own (Laine 2005 §6).
  bool parts = false;

  bool operator==(const VolumeOptions&) const = default;
};

// Per-frame scratch memory of build_volume, owned by the caller and reused between frames.
struct VolumeScratch {
  std::vector<std::int8_t> weights;  // the face weights of the last build
  std::vector<std::uint32_t> casting;
};

// The whole volume of one mesh for one light, on the calling thread: clears `out` and fills it
// with sides, then (if options.caps) light and dark caps; clamped where `clamp` is not null (its
// segments need their caps: options.caps must be set).
void build_volume(const Topology& topo, const glm::vec4& light, const VolumeOptions& options,
                  VolumeScratch& scratch, VolumeBuffer& out, const VolumeClamp* clamp = nullptr);

}  // namespace shadowvol
