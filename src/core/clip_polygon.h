// shadowvol core: clipping a convex polygon against one plane (Sutherland and Hodgman 1974), in
// homogeneous or affine coordinates, for the rasterizer's clipper and for anything that must
// cut geometry the way it does.
#pragma once

#include <array>
#include <cassert>
#include <cstddef>

namespace shadowvol {

// Where the edge from `in` (distance d_in >= 0) to `out` (d_out < 0) crosses the plane, computed
// from the inside vertex whichever way a polygon runs the edge.
template <class Vertex, class Scalar>
inline Vertex plane_crossing(const Vertex& in, const Vertex& out, Scalar d_in, Scalar d_out) {
  const Scalar t = d_in / (d_in - d_out);
  return in + (out - in) * t;
}

// Keeps the part of the convex polygon v[0 .. n) where distance(vertex) >= 0 (NaN counts as
// outside) and returns whether anything was cut. Each new vertex is computed from its edge's
// inside vertex towards the outside one, whichever way the polygon runs the edge: two polygons
// that share an edge cut it at the same point, bit for bit, and stay watertight along the cut.
// N must leave room for one more vertex than n.
template <class Vertex, std::size_t N, class Distance>
bool clip_polygon(std::array<Vertex, N>& v, int& n, Distance&& distance) {
  using Scalar = decltype(distance(v[0]));
  std::array<Scalar, N> d;
  bool cut = false;
  for (int i = 0; i < n; ++i) {
    d[i] = distance(v[i]);
    cut |= !(d[i] >= Scalar(0));
  }
  if (!cut) return false;
  std::array<Vertex, N> out;
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const bool in_i = d[i] >= Scalar(0), in_j = d[j] >= Scalar(0);
    if (in_i) out[m++] = v[i];
    if (in_i != in_j) {
      const int in = in_i ? i : j, outside = in_i ? j : i;
      out[m++] = plane_crossing(v[in], v[outside], d[in], d[outside]);
    }
    assert(m <= static_cast<int>(N));
  }
  v = out;
  n = m;
  return true;
}

}  // namespace shadowvol
