// Frames render into caller-owned storage (DESIGN.md): once a frame of a size has been drawn,
// the next frames of that size reuse every buffer. Counted here by replacing the global
// operator new of this test binary, so that an allocation anywhere in the library shows.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <iostream>
#include <new>

#include "scene/scene.h"
#include "soft/soft_backend.h"

namespace {
std::atomic<long> allocations{0};
}  // namespace

// GCC sees these deletes free what the replaced new returned and, not knowing that new is
// malloc here, warns of a mismatch; the pair below is matched by construction.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace shadowvol {
namespace {

// Heap allocations per frame once the renderer and the frame are warm.
long steady_allocations_per_frame(const char* scene_name, Method method) {
  auto scene = builtin_scene(scene_name);
  EXPECT_TRUE(scene.ok());
  Renderer renderer = soft::soft_renderer();
  const RenderOptions options{320, 180, method, Generator::automatic};
  Frame frame;
  for (int i = 0; i < 2; ++i) renderer.render(*scene, options, frame);  // warm
  constexpr int kFrames = 4;
  const long before = allocations.load();
  for (int i = 0; i < kFrames; ++i) renderer.render(*scene, options, frame);
  EXPECT_FALSE(frame.image.rgba.empty());
  return (allocations.load() - before) / kFrames;
}

TEST(FrameAllocations, SteadyFramesOfDemoAndGlassAllocateAtMostTwoBlocks) {
  const long counted = allocations.load();
  ::operator delete(::operator new(8));    // a call, which unlike a new-expression is never elided
  ASSERT_GT(allocations.load(), counted);  // the counter sees the library's allocations
  for (const char* name : {"demo", "glass"})
    for (const Method method : {Method::automatic, Method::zfail}) {
      const long per_frame = steady_allocations_per_frame(name, method);
      EXPECT_LE(per_frame, 2) << name << ", " << to_string(method);
      std::cout << name << " " << to_string(method) << ": " << per_frame
                << " allocations a frame\n";
    }
}

}  // namespace
}  // namespace shadowvol
