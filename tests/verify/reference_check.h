// What the verify tests share: a frame rendered and checked against the ray-traced reference,
// which decides (DESIGN.md's invariant: no mismatch outside the one-pixel band).
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "backend/backend.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "trace/reference.h"
#include "verify/verify.h"

namespace shadowvol::testing {

// The renderer of a backend, or null (and a failure) where it cannot be made.
inline std::unique_ptr<Renderer> renderer_for(Backend backend) {
  auto made = make_renderer(backend);
  EXPECT_TRUE(made.ok()) << (made ? "" : made.error().message);
  return made ? std::move(made->renderer) : nullptr;
}

// Which surfaces face each light compared too (RenderOptions::record_facing).
inline Frame render_checked(Renderer& renderer, const Scene& scene, RenderOptions options) {
  options.record_facing = true;
  Frame frame = renderer.render(scene, options);
  auto reference = trace_reference(scene, options.width, options.height);
  EXPECT_TRUE(reference.ok());
  if (!reference) return frame;
  const Comparison c = compare(frame, *reference);
  EXPECT_GT(c.pixels_compared, 0u);
  EXPECT_EQ(c.mismatched_outside_band, 0u) << c.mismatched << " mismatched in all";
  return frame;
}

}  // namespace shadowvol::testing
