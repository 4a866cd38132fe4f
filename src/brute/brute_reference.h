// shadowvol brute: a second ray-traced reference, written apart from trace/ so that a bug the
// first shares with the rasterizers (loading, transforms, the camera, materials) cannot pass
// unseen: every ray against every triangle (no BVH, no Embree), all in double precision.
//
// Owns: the scene's triangles in eye-relative double coordinates, its own camera rays (built from
// the camera's position, target, up and field of view, not from the projection matrix the
// rasterizers and trace/ share), and the same answers as trace/'s ReferenceTracer: per window
// point, the nearest opaque surface and the nearest transparent one in front of it; per light,
// whether it faces the light, lies in its range, is shadowed, and what the transparent surfaces
// on the way let through. Only the types it answers in (trace/reference.h) are shared.
//
// Its cost is width x height x (1 + lights) x triangles: for small scenes and small windows
// (a box per object lets rays skip objects they miss; nothing else is skipped).
#pragma once

#include <memory>

#include "core/expected.h"
#include "scene/scene.h"
#include "trace/reference.h"

namespace shadowvol {

// Fails on a window without pixels.
Expected<std::shared_ptr<const ReferenceSampler>> make_brute_reference(const Scene& scene,
                                                                       int width, int height);

// trace_frame over make_brute_reference: every pixel centre, rows in parallel.
Expected<ReferenceFrame> trace_brute_reference(const Scene& scene, int width, int height,
                                               const Progress& progress = {});

}  // namespace shadowvol
