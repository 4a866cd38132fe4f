// shadowvol accel: split planes for split-plane shadow volumes (Laine 2005 §4, §6).
//
// Owns: the shape of a caster or of one part of it (centroid, long and thin axes, elongated or
// flat), the planes Laine constructs from it (§4.1 Point-Camera-Light, §4.2 Point-Point-Light),
// ours for flat casters, and the alternatives the sampler weighs (soft/split_sampler.h). Every
// plane is eye-relative (the camera at the origin); any plane gives exact counts, a good one
// leaves most tiles needing no count at all. §6's decomposition into parts is the caller's: it
// asks for the shape of each part's vertices.
#pragma once

#include <optional>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace shadowvol {

// Laine 2005 §4.1, Eq. 4, eye-relative (the camera at the origin): the plane through the
// volume's centre line (from the light through p, or along a directional light) that is
// orthogonal to the plane of that line and the camera, so that it splits the volume in halves
// as the camera sees them; then (our alternatives, split_plane_candidates) `turn` radians about
// the centre line, where a quarter turn holds the camera, and `tilt` radians of the normal
// towards the centre line's direction, about p. Unit normal. Degenerate (zero) when the camera
// lies on the centre line, which the split test reads as z-fail everywhere: still exact.
glm::vec4 point_camera_light(const glm::vec3& p, const glm::vec4& light, double turn = 0.0,
                             double tilt = 0.0);

// Laine 2005 §4.2, Eq. 5: the plane through the light and the two points p1 and p2 (the ends of
// a long thin object's axis), so that it runs inside the flat volume such an object casts.
// Degenerate (zero) when the light lies on the line p1 p2: z-fail everywhere, still exact.
glm::vec4 point_point_light(const glm::vec3& p1, const glm::vec3& p2, const glm::vec4& light);

// An object's centroid (the mean of its vertices, where Point-Camera-Light puts its point) and
// its principal axes, from the covariance of its vertices (in double): the long axis
// (the principal direction, by power iteration), its ends where the vertices' projections end,
// and whether the object is at least twice as long as it is wide (as far across as its farthest
// vertex from the axis); the thin axis (the least principal direction, by power iteration on
// trace - covariance, whose largest eigenvalue is the trace minus the least), the interval of
// the vertices' projections on it, and whether the object is flat: a hundred times thinner along
// it than long, and not elongated (a rod is thin across both of its short axes); and the radius
// of the sphere about its bounding box.
struct Shape {
  glm::vec3 centroid{0.0f};
  float radius = 0.0f;
  glm::vec3 p1{0.0f}, p2{0.0f};
  bool elongated = false;
  glm::dvec3 thin_axis{0.0};
  double thin_lo = 0.0, thin_hi = 0.0;
  bool flat = false;
};

Shape shape_of(const std::vector<glm::vec3>& points);

// Ours, for a flat object: the plane across its thin axis, just past the object on the side away
// from the light (by a hundredth of its length), so that the object lies on the light's side and
// its whole volume on the other: pixels on the object take the rule that culls the volume. None
// where the light lies within the object's thickness (edge-on), or a directional light shines
// along the object.
std::optional<glm::vec4> flat_plane(const Shape& shape, const glm::vec4& light);

// The planes SplitPlanes::sampled weighs against the object's own (world, eye-relative): both
// whole-volume rules (z-fail everywhere is the zero plane; z-pass everywhere is the plane
// w = -z, whose camera side holds every tile) and, but for a flat object, whose own plane already
// sends its whole volume behind the surfaces, Point-Camera-Light turned about the centre line
// in steps of 15 degrees, tilted towards and away from the light, moved across by a quarter and
// half of the object's radius, and Point-Point-Light: 39 planes (2 for a flat object).
std::vector<glm::vec4> split_plane_candidates(const Shape& shape, const glm::vec4& light);

}  // namespace shadowvol
