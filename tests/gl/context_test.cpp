// A headless OpenGL 4.5 core context through EGL: on machines without a GPU that is Mesa's
// llvmpipe, which the set-up script installs.
#include <gtest/gtest.h>

#include "gl/context.h"

namespace shadowvol::gl {
namespace {

TEST(GlContext, HeadlessCoreContextReportsItsDriverAndFeatures) {
  auto context = Context::create_headless();
  ASSERT_TRUE(context.ok()) << context.error().message;
  const Info info = context->info();
  EXPECT_FALSE(info.vendor.empty());
  EXPECT_FALSE(info.renderer.empty());
  EXPECT_EQ(info.version.rfind("4.", 0), 0u) << info.version;  // 4.5 core, or later
  EXPECT_TRUE(info.features.depth_clamp);
  EXPECT_TRUE(info.features.two_sided_stencil);
  EXPECT_TRUE(info.features.geometry_shaders);
  // Every missing feature is named with its fallback.
  EXPECT_EQ(info.features.fallbacks.empty(), info.features.depth_bounds);
  Context moved = std::move(*context);  // move-only, released once
  EXPECT_FALSE(moved.info().renderer.empty());
}

}  // namespace
}  // namespace shadowvol::gl
