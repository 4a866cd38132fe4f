// Exact predicates on homogeneous points with integer coordinates, for the volume law test.
//
// Every vertex the tests feed the generators is a small integer, so the generators' float
// output (x, y, z, w) is exact, and every determinant below is computed exactly in __int128.
// A point is (x, y, z, w) with w = 1 for finite points and w = 0 for points at infinity
// (directions), as the volume buffer stores them; all w are >= 0, so a convex combination with
// non-negative coefficients is the segment or triangle a rasterizer draws.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include <glm/vec4.hpp>

namespace shadowvol::testing {

__extension__ typedef __int128 Int;  // GCC and Clang; exact for |det| < 2^127
using HPoint = std::array<std::int64_t, 4>;

inline HPoint exact(const glm::vec4& p) {
  HPoint h{};
  for (int i = 0; i < 4; ++i) {
    h[i] = static_cast<std::int64_t>(p[i]);
    if (static_cast<float>(h[i]) != p[i]) std::abort();  // the test only feeds integers
  }
  return h;
}

inline int sign(Int x) { return (x > 0) - (x < 0); }

// det[a b c d] with the points as rows, by 2x2 minors of the first two and last two rows.
inline Int det4(const HPoint& a, const HPoint& b, const HPoint& c, const HPoint& d) {
  auto m = [](const HPoint& p, const HPoint& q, int i, int j) {
    return Int(p[i]) * q[j] - Int(p[j]) * q[i];
  };
  return m(a, b, 0, 1) * m(c, d, 2, 3) - m(a, b, 0, 2) * m(c, d, 1, 3) +
         m(a, b, 0, 3) * m(c, d, 1, 2) + m(a, b, 1, 2) * m(c, d, 0, 3) -
         m(a, b, 1, 3) * m(c, d, 0, 2) + m(a, b, 2, 3) * m(c, d, 0, 1);
}

inline Int det3(const HPoint& a, const HPoint& b, const HPoint& c) {  // of x, y, z only
  return Int(a[0]) * (Int(b[1]) * c[2] - Int(b[2]) * c[1]) -
         Int(a[1]) * (Int(b[0]) * c[2] - Int(b[2]) * c[0]) +
         Int(a[2]) * (Int(b[0]) * c[1] - Int(b[1]) * c[0]);
}

// Three homogeneous points span less than a plane: the triangle has no area (in the projective
// sense: also a triangle whose vertices at infinity coincide). Such a primitive covers no pixel.
inline bool degenerate(const HPoint& a, const HPoint& b, const HPoint& c) {
  for (int drop = 0; drop < 4; ++drop) {
    HPoint pa{}, pb{}, pc{};
    for (int i = 0, k = 0; i < 4; ++i)
      if (i != drop) pa[k] = a[i], pb[k] = b[i], pc[k] = c[i], ++k;
    if (det3(pa, pb, pc) != 0) return false;
  }
  return true;
}

// Which side of triangle (x0, x1, x2) point p lies on: +1 in front (the side the
// counter-clockwise normal points to), -1 behind, 0 on its plane.
inline int side(const HPoint& x0, const HPoint& x1, const HPoint& x2, const HPoint& p) {
  return -sign(det4(x0, x1, x2, p));
}

enum class Crossing { none, crossed, ambiguous };

// Does the segment from a to b (positive combinations of a and b) cross the interior of the
// triangle (positive combinations of x0, x1, x2)? The five vectors in R^4 have a one-dimensional
// kernel c (Cramer: c_k = (-1)^k det of the other four); they meet iff c0, c1, c2 share one
// sign and c3, c4 the other. A zero means the segment touches an edge, a vertex or the plane:
// `ambiguous`, and the caller draws another sample (the test's rule for rays through edges).
// A degenerate triangle is never crossed.
inline Crossing segment_crosses(const HPoint& a, const HPoint& b, const HPoint& x0,
                                const HPoint& x1, const HPoint& x2) {
  if (degenerate(x0, x1, x2)) return Crossing::none;
  const int s3 = -sign(det4(x0, x1, x2, b)), s4 = sign(det4(x0, x1, x2, a));
  if (s3 == 0 || s4 == 0) return Crossing::ambiguous;
  if (s3 != s4) return Crossing::none;  // both ends on one side of the plane
  const int c[3] = {sign(det4(x1, x2, a, b)), -sign(det4(x0, x2, a, b)), sign(det4(x0, x1, a, b))};
  bool zero = false;
  for (int ci : c) {
    if (ci == s3) return Crossing::none;
    zero |= ci == 0;
  }
  return zero ? Crossing::ambiguous : Crossing::crossed;
}

// Does direction d (a point at infinity) lie inside the triangle at infinity (x0, x1, x2), all
// with w = 0? That is where a ray with direction d ends on a dark cap.
inline Crossing direction_inside(const HPoint& d, const HPoint& x0, const HPoint& x1,
                                 const HPoint& x2) {
  const int s = sign(det3(x0, x1, x2));
  if (s == 0) return Crossing::none;
  const int c[3] = {sign(det3(d, x1, x2)), sign(det3(x0, d, x2)), sign(det3(x0, x1, d))};
  bool zero = false;
  for (int ci : c) {
    if (ci == -s) return Crossing::none;
    zero |= ci == 0;
  }
  return zero ? Crossing::ambiguous : Crossing::crossed;
}

}  // namespace shadowvol::testing
