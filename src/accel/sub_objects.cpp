#include "accel/sub_objects.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "core/clip_polygon.h"

namespace shadowvol {
namespace {

struct Cell {
  glm::dvec3 lo, hi;
  std::vector<std::uint32_t> touching;  // faces whose bounds meet the cell
  std::vector<std::uint32_t> owned;     // faces whose centroid lies in it
  int longest() const {
    const glm::dvec3 d = hi - lo;
    return d.x >= d.y && d.x >= d.z ? 0 : d.y >= d.z ? 1 : 2;
  }
  double size() const { return hi[longest()] - lo[longest()]; }
};

}  // namespace

SubObjects split_sub_objects(const Topology& topo, float cell_size, std::size_t max_leaves) {
  SubObjects out;
  out.cell = cell_size;
  const std::size_t faces = topo.face_count();
  out.face_leaf.assign(faces, 0);
  auto vertex = [&](std::size_t f, int k) {
    return glm::dvec3(topo.positions[topo.face_vertices[3 * f + k]]);
  };
  Cell root{glm::dvec3(INFINITY), glm::dvec3(-INFINITY), {}, {}};
  for (std::size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) {
      root.lo = glm::min(root.lo, vertex(f, k));
      root.hi = glm::max(root.hi, vertex(f, k));
    }
  if (faces == 0) return out;
  root.touching.resize(faces);
  root.owned.resize(faces);
  for (std::size_t f = 0; f < faces; ++f)
    root.touching[f] = root.owned[f] = static_cast<std::uint32_t>(f);

  std::vector<Cell> cells;
  cells.push_back(std::move(root));
  // The largest cell first, so that a limit on leaves spends them where the mesh is widest.
  for (;;) {
    std::size_t largest = 0;
    for (std::size_t c = 1; c < cells.size(); ++c)
      if (cells[c].size() > cells[largest].size()) largest = c;
    if (cells.size() >= max_leaves || !(cells[largest].size() > cell_size)) break;
    Cell parent = std::move(cells[largest]);
    const int axis = parent.longest();
    const double middle = 0.5 * (parent.lo[axis] + parent.hi[axis]);
    Cell left{parent.lo, parent.hi, {}, {}}, right{parent.lo, parent.hi, {}, {}};
    left.hi[axis] = right.lo[axis] = middle;
    for (const std::uint32_t f : parent.touching) {
      const double a = vertex(f, 0)[axis], b = vertex(f, 1)[axis], c = vertex(f, 2)[axis];
      if (std::min({a, b, c}) <= middle) left.touching.push_back(f);
      if (std::max({a, b, c}) >= middle) right.touching.push_back(f);
    }
    for (const std::uint32_t f : parent.owned) {
      const double centroid = (vertex(f, 0)[axis] + vertex(f, 1)[axis] + vertex(f, 2)[axis]) / 3;
      (centroid < middle ? left : right).owned.push_back(f);
    }
    cells[largest] = std::move(left);
    cells.push_back(std::move(right));
  }

  // Each cell's leaf: the bounds of its owned faces, and of every touching face cut to it.
  for (const Cell& cell : cells) {
    SubObjects::Leaf leaf;
    const auto index = static_cast<std::uint32_t>(out.leaves.size());
    for (const std::uint32_t f : cell.owned) {
      out.face_leaf[f] = index;
      for (int k = 0; k < 3; ++k) {
        leaf.caster_lo = glm::min(leaf.caster_lo, glm::vec3(vertex(f, k)));
        leaf.caster_hi = glm::max(leaf.caster_hi, glm::vec3(vertex(f, k)));
      }
    }
    leaf.faces = cell.owned.size();
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const std::uint32_t f : cell.touching) {
      std::array<glm::dvec3, 9> poly{vertex(f, 0), vertex(f, 1), vertex(f, 2)};
      int n = 3;
      for (int side = 0; side < 6 && n >= 3; ++side) {
        const int axis = side / 2;
        clip_polygon(poly, n, [&](const glm::dvec3& p) {
          return side % 2 ? cell.hi[axis] - p[axis] : p[axis] - cell.lo[axis];
        });
      }
      for (int i = 0; i < n; ++i) lo = glm::min(lo, poly[i]), hi = glm::max(hi, poly[i]);
    }
    if (!(lo.x <= hi.x) && !leaf.casts()) continue;  // the surface misses the cell
    if (lo.x <= hi.x) {                              // within the cell, rounded outwards to float
      lo = glm::max(lo, cell.lo);
      hi = glm::min(hi, cell.hi);
      leaf.receiver_lo = glm::vec3(lo);
      leaf.receiver_hi = glm::vec3(hi);
      for (int k = 0; k < 3; ++k) {
        if (double(leaf.receiver_lo[k]) > lo[k])
          leaf.receiver_lo[k] = std::nextafter(leaf.receiver_lo[k], -INFINITY);
        if (double(leaf.receiver_hi[k]) < hi[k])
          leaf.receiver_hi[k] = std::nextafter(leaf.receiver_hi[k], INFINITY);
      }
    }
    out.leaves.push_back(leaf);
  }
  build_vertex_leaves(topo, out.face_leaf, out.vertex_leaf_offsets, out.vertex_leaves);
  return out;
}

}  // namespace shadowvol
