#include "core/shading_normals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

namespace shadowvol {
namespace {

// The faces' directions and the corners around each point of the surface.
struct Around {
  std::vector<glm::dvec3> unit;        // per face: unit normal, or 0 for a face of no area
  std::vector<std::uint32_t> point;    // per vertex: its point (the first vertex at its position)
  std::vector<std::uint32_t> first;    // per point p: its corners are corners[first[p]..first[p+1])
  std::vector<std::uint32_t> corners;  // corner indices (3 f + k), grouped by point
};

Around around(const Mesh& mesh) {
  const std::size_t faces = mesh.triangle_count(), vertices = mesh.positions.size();
  Around a;
  a.unit.resize(faces);
  for (std::size_t f = 0; f < faces; ++f) {
    const glm::dvec3 p0(mesh.positions[mesh.indices[3 * f]]);
    const glm::dvec3 n = glm::cross(glm::dvec3(mesh.positions[mesh.indices[3 * f + 1]]) - p0,
                                    glm::dvec3(mesh.positions[mesh.indices[3 * f + 2]]) - p0);
    const double len = glm::length(n);
    a.unit[f] = len > 0.0 && std::isfinite(len) ? n / len : glm::dvec3(0.0);
  }
  // Vertices at one position are one point of the surface: files repeat them per face (OBJ
  // without normals, STL) or per part. Each index to the first vertex of its position.
  std::vector<std::uint32_t> order(vertices);
  std::vector<std::uint32_t>& point = a.point;
  point.resize(vertices);
  for (std::size_t v = 0; v < vertices; ++v) order[v] = static_cast<std::uint32_t>(v);
  const auto key = [&](std::uint32_t v) {
    const glm::vec3& p = mesh.positions[v];
    return std::tuple(p.x, p.y, p.z);
  };
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return key(x) < key(y) || (key(x) == key(y) && x < y);
  });
  for (std::size_t i = 0; i < vertices; ++i)
    point[order[i]] = i > 0 && key(order[i]) == key(order[i - 1]) ? point[order[i - 1]] : order[i];
  // The corners around each point (counting sort by point).
  a.first.assign(vertices + 1, 0);
  a.corners.resize(mesh.indices.size());
  for (const std::uint32_t v : mesh.indices) ++a.first[point[v] + 1];
  for (std::size_t v = 0; v < vertices; ++v) a.first[v + 1] += a.first[v];
  std::vector<std::uint32_t> fill(a.first.begin(), a.first.end() - 1);
  for (std::size_t c = 0; c < mesh.indices.size(); ++c)
    a.corners[fill[point[mesh.indices[c]]]++] = static_cast<std::uint32_t>(c);
  return a;
}

}  // namespace

std::vector<glm::vec3> crease_normals(const Mesh& mesh, float crease_degrees) {
  const Around a = around(mesh);
  // Each corner's angle: its face's weight there (a face cut into two triangles at a vertex
  // weighs there as it did whole).
  std::vector<double> angle(mesh.indices.size(), 0.0);
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
    const std::size_t f = c / 3, k = c % 3;
    const glm::dvec3 p(mesh.positions[mesh.indices[c]]);
    const glm::dvec3 u = glm::dvec3(mesh.positions[mesh.indices[3 * f + (k + 1) % 3]]) - p;
    const glm::dvec3 w = glm::dvec3(mesh.positions[mesh.indices[3 * f + (k + 2) % 3]]) - p;
    angle[c] = std::atan2(glm::length(glm::cross(u, w)), glm::dot(u, w));
  }
  const double cos_crease = std::cos(glm::radians(static_cast<double>(crease_degrees)));
  std::vector<glm::vec3> normals(mesh.indices.size(), glm::vec3(0.0f));
  // Per point, its faces joined across the edges they share there where they meet at less than
  // the crease (union-find over the point's fan); a corner's normal sums its set.
  std::vector<std::uint32_t> parent;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // (other point, fan index)
  std::vector<glm::dvec3> sum;
  const auto root = [&](std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t v = 0; v + 1 < a.first.size(); ++v) {
    const std::uint32_t begin = a.first[v], n = a.first[v + 1] - begin;
    if (n == 0) continue;
    parent.resize(n);
    edges.clear();
    for (std::uint32_t i = 0; i < n; ++i) {
      parent[i] = i;
      const std::uint32_t c = a.corners[begin + i], f = c / 3, k = c % 3;
      for (const std::uint32_t j : {(k + 1) % 3, (k + 2) % 3})
        edges.emplace_back(a.point[mesh.indices[3 * f + j]], i);
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t e = 0; e < edges.size(); ++e)
      for (std::size_t g = e + 1; g < edges.size() && edges[g].first == edges[e].first; ++g) {
        const glm::dvec3& x = a.unit[a.corners[begin + edges[e].second] / 3];
        const glm::dvec3& y = a.unit[a.corners[begin + edges[g].second] / 3];
        if (x != glm::dvec3(0.0) && y != glm::dvec3(0.0) && glm::dot(x, y) >= cos_crease)
          parent[root(edges[e].second)] = root(edges[g].second);
      }
    sum.assign(n, glm::dvec3(0.0));
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t c = a.corners[begin + i];
      sum[root(i)] += angle[c] * a.unit[c / 3];
    }
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t c = a.corners[begin + i];
      const glm::dvec3& own = a.unit[c / 3];
      if (own == glm::dvec3(0.0)) continue;  // no direction: it joins nothing
      const double len = glm::length(sum[root(i)]);
      normals[c] = glm::vec3(len > 0.0 ? sum[root(i)] / len : own);
    }
  }
  return normals;
}

ShadingNormals make_shading_normals(const Mesh& mesh, std::vector<glm::vec3> normals) {
  ShadingNormals out;
  out.offsets.assign(normals.size(), 0.0f);
  if (normals.size() == mesh.indices.size()) {
    const Around a = around(mesh);
    for (std::size_t v = 0; v + 1 < a.first.size(); ++v)
      for (std::uint32_t k = a.first[v]; k < a.first[v + 1]; ++k) {
        const std::uint32_t c = a.corners[k];
        const double len = glm::length(glm::dvec3(normals[c]));
        if (!(len > 0.0) || !std::isfinite(len)) continue;
        const glm::dvec3 n = glm::dvec3(normals[c]) / len;
        double offset = 0.0;
        for (std::uint32_t j = a.first[v]; j < a.first[v + 1]; ++j) {
          const glm::dvec3& face = a.unit[a.corners[j] / 3];
          if (glm::dot(face, n) > 0.0) offset = std::max(offset, glm::length(glm::cross(face, n)));
        }
        out.offsets[c] = static_cast<float>(std::min(offset, double(kMaxTerminatorOffset)));
      }
  }
  out.normals = std::move(normals);
  return out;
}

}  // namespace shadowvol
