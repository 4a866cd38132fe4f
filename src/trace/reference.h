// shadowvol trace: the ray-traced reference (Embree 3). Independent of all shadow-volume code:
// it shares only the scene description and the camera with the renderer.
//
// Owns: an Embree device and scene built from the world-space triangles of a Scene, primary
// rays through the same pixel centres the rasterizer samples (or any other point of the window),
// and one shadow ray per visible point and light. Errors from Embree come back as values.
// Transparent casters (Material::opacity < 1) are seen through, so a primary ray finds the
// nearest opaque surface and, in front of it, the nearest transparent one; a shadow ray stops
// at an opaque surface and multiplies the transmittances of all the transparent ones it crosses.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "core/expected.h"
#include "scene/scene.h"

namespace shadowvol {

// A surface whose normal makes a cosine below this with the direction to a light (either side)
// faces the light or not by rounding alone: a renderer's point for the pixel, a float's step
// from the reference's, turns it either way (a light in the plane of a floor), and the light's
// direct term there is nearly 0 either way. verify does not compare a frame's facing there.
inline constexpr double kGrazingCosine = 1e-4;

// What the reference sees of one surface along one primary ray.
struct ReferenceSurface {
  std::int32_t object = -1;  // scene object index, -1 for none
  std::uint32_t face = 0;    // face of that object
  double distance = 0.0;     // from the eye, along the ray (infinite where none)
  // Per light: whether the surface faces the light (its normal, turned towards the eye, points
  // to the light's side, and it lies within the light's range), and whether the segment to the
  // light crosses an opaque surface; whether it is seen nearly edge-on from the light
  // (kGrazingCosine).
  std::vector<std::uint8_t> faces_light, shadowed, grazing;
  // Scenes with transparent casters only: per light, the product of the transmittances of the
  // transparent surfaces the segment crosses, each counted once (any-hit over all hits); 0 where
  // shadowed.
  std::vector<glm::vec3> transmitted;
};

// What the reference sees along one primary ray: the nearest opaque surface, and in front of it
// the nearest transparent one (object -1 where none, or where the scene has none).
struct ReferenceSample : ReferenceSurface {
  ReferenceSurface glass;
};

// A reference: what the rays through points of a width x height window of scene.camera see.
// Embree's (ReferenceTracer, below) decides; a second one written apart (brute/, every triangle
// in double) checks it.
class ReferenceSampler {
 public:
  virtual ~ReferenceSampler() = default;
  // The ray through window point (x, y), in pixels from the top-left corner: pixel (i, j) is
  // sampled at (i + 0.5, j + 0.5), as the rasterizer samples it.
  virtual ReferenceSample sample(double x, double y) const = 0;
  // Per light, whether the point where the ray through (x, y) leaves the near plane lies in a
  // shadow: a surface that casts shadows (opaque or transparent) crosses the segment from it to
  // the light. There z-pass, which counts from the near plane, cannot be exact (Everitt &
  // Kilgard 2002; the eye in a shadow is the common case of it).
  virtual std::vector<std::uint8_t> near_plane_shadowed(double x, double y) const = 0;
  // Whether face `face` of object `object` crosses, nearer the eye than `distance`, a ray through
  // the square of window points within one pixel of (x, y) (triangle_nearer_within): a surface in
  // front of what the ray through (x, y) sees, whose outline therefore passes within a pixel of
  // it, though it may be hidden everywhere (a face turned away from the eye, behind its neighbour
  // at a silhouette of an object over itself, seen edge-on: thinner than any sampling).
  virtual bool face_nearer_within(double x, double y, std::int32_t object, std::uint32_t face,
                                  double distance) const = 0;
  // The light where the ray through (x, y) meets the plane of face `face` of object `object`,
  // as sample() would give it had that face continued there unhidden (object -1 where the ray
  // meets the plane behind the near plane, or not at all): the shadow on a surface beyond a
  // crease of its object, where another face of it stands on it (a cabin on a car's body).
  virtual ReferenceSurface on_face_plane(double x, double y, std::int32_t object,
                                         std::uint32_t face) const = 0;
  // Empty, or the error met while tracing.
  virtual std::string error() const { return {}; }
};

// Whether the eye-relative triangle c, in front of the eye, covers part of the window square
// within one pixel of (x, y) nearer the eye than `distance` along the rays through it: exactly, the
// triangle's window projection cut to the square and its plane's depth at the corners left.
// to_window: an eye-relative point to window (x, y) and its clip w; ray: the unit direction
// through a window point. A triangle reaching behind the eye is taken as not covering it.
bool triangle_nearer_within(const glm::dvec3 (&c)[3], double x, double y, double distance,
                            const std::function<glm::dvec3(const glm::dvec3&)>& to_window,
                            const std::function<glm::dvec3(double, double)>& ray);

// The scene built once for Embree, traced through a width x height window of scene.camera.
class ReferenceTracer final : public ReferenceSampler {
 public:
  // Fails if Embree cannot be set up or cannot build the scene.
  static Expected<std::shared_ptr<const ReferenceTracer>> create(const Scene& scene, int width,
                                                                 int height);
  ~ReferenceTracer() override;
  ReferenceSample sample(double x, double y) const override;
  std::vector<std::uint8_t> near_plane_shadowed(double x, double y) const override;
  bool face_nearer_within(double x, double y, std::int32_t object, std::uint32_t face,
                          double distance) const override;
  ReferenceSurface on_face_plane(double x, double y, std::int32_t object,
                                 std::uint32_t face) const override;
  // Empty, or the error Embree has reported while tracing.
  std::string error() const override;

 private:
  struct State;
  explicit ReferenceTracer(std::unique_ptr<State> state);
  // The light at eye-relative point pos of out.object, whose normal n is turned to the eye.
  void light_surface(const glm::dvec3& pos, const glm::dvec3& n, ReferenceSurface& out) const;
  std::unique_ptr<State> state_;
};

// One layer of a ReferenceFrame, per pixel what ReferenceSurface is per sample.
struct ReferenceLayer {
  std::vector<std::int32_t> object;                    // per pixel: scene object index, -1 for none
  std::vector<std::uint32_t> face;                     // per pixel: face of that object
  std::vector<std::vector<std::uint8_t>> faces_light;  // per light, per pixel: 1 or 0
  std::vector<std::vector<std::uint8_t>> shadowed;     // per light, per pixel: 1 or 0
  std::vector<std::vector<std::uint8_t>> grazing;      // per light, per pixel: 1 or 0
  std::vector<std::vector<glm::vec3>> transmitted;     // per light, per pixel; or empty
};

// The opaque surfaces' layer, and with transparent casters the glass layer in front of it (as
// Frame has them).
struct ReferenceFrame : ReferenceLayer {
  int width = 0, height = 0;
  ReferenceLayer glass;  // empty when the scene has no transparent caster
  // Per light, per pixel: ReferenceSampler::near_plane_shadowed at the pixel's centre.
  std::vector<std::vector<std::uint8_t>> near_plane_shadowed;
  // The sampler that made the frame, for samples between pixel centres.
  std::shared_ptr<const ReferenceSampler> tracer;
};

// Long work reports what it is doing and the fraction of it done, in [0, 1], now and then, on the
// calling thread (whatever threads do the work).
using Progress = std::function<void(std::string_view doing, float fraction)>;

// Traces the scene at width x height through scene.camera, at every pixel centre, rows in
// parallel. Fails if Embree cannot be set up.
Expected<ReferenceFrame> trace_reference(const Scene& scene, int width, int height,
                                         const Progress& progress = {});
// The same through any sampler made for that window and the scene's `lights`, which has
// transparent casters or not (`glass`). Fails if the sampler reports an error.
Expected<ReferenceFrame> trace_frame(std::shared_ptr<const ReferenceSampler> sampler, int width,
                                     int height, std::size_t lights, bool glass,
                                     const Progress& progress = {});

}  // namespace shadowvol
