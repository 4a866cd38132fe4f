// shadowvol_bench: silhouette + volume generation throughput (Google Benchmark).
//
// For bumpy tori of 10k, 100k and 1M triangles, on 1 and 2 threads, with and without caps:
//   tri/s        triangles per second through VolumeBuilder (face weights, sides, caps)
//   read_GB/s    bytes of the flat arrays the pass reads (Topology::frame_bytes) per second
//   stream_GB/s  the machine's streaming read bandwidth over a buffer of those same bytes, on
//                the same threads, measured in the same run just before the timed loop
//   bw_fraction  read_GB/s / stream_GB/s: how close the pass runs to a plain read of its input
// Goal (issue #3): bw_fraction >= 0.5, and 2 threads >= 1.8x the 1-thread tri/s.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <numeric>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_reduce.h>

#include "core/topology.h"
#include "backend/backend.h"
#include "soft/soft_backend.h"
#include "render/volume_builder.h"
#include "scene/scene.h"
#include "core/shapes.h"

namespace {

using namespace shadowvol;

const Topology& torus(std::size_t triangles) {
  static std::map<std::size_t, std::unique_ptr<Topology>> cache;
  auto& slot = cache[triangles];
  if (!slot) slot = std::make_unique<Topology>(build_topology(make_bumpy_torus_with(triangles)));
  return *slot;
}

// Best-of-N bytes per second of summing `words` (a plain streaming read, vectorised), split over
// the threads the current oneTBB limit allows, in chunks like the volume pass uses.
double stream_read_bandwidth(const std::vector<std::uint64_t>& words) {
  double best = 0.0;
  for (int rep = 0; rep < 20; ++rep) {
    const auto start = std::chrono::steady_clock::now();
    const std::uint64_t sum = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, words.size(), 8192), std::uint64_t{0},
        [&](const tbb::blocked_range<std::size_t>& r, std::uint64_t acc) {
          return std::accumulate(words.begin() + r.begin(), words.begin() + r.end(), acc);
        },
        std::plus<>());
    benchmark::DoNotOptimize(sum);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::max(best, static_cast<double>(words.size() * sizeof(std::uint64_t)) / seconds);
  }
  return best;
}

void BM_VolumeGeneration(benchmark::State& state) {
  const auto triangles = static_cast<std::size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const bool caps = state.range(2) != 0;
  const Topology& topo = torus(triangles);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);

  const std::size_t bytes = topo.frame_bytes();
  const std::vector<std::uint64_t> baseline(bytes / sizeof(std::uint64_t), 1);
  const double stream = stream_read_bandwidth(baseline);

  VolumeBuffer volume;
  VolumeBuilder builder;
  const VolumeJob job{&topo, {1.5f, 1.0f, 2.5f, 1.0f}, {Generator::automatic, caps}, &volume};
  builder.build({&job, 1});  // steady state: the buffers have grown once, as after any first frame
  for (auto _ : state) {
    builder.build({&job, 1});
    benchmark::DoNotOptimize(volume.sides.weights.data());
    benchmark::ClobberMemory();
  }
  const double frames = static_cast<double>(state.iterations());
  state.counters["tri/s"] = benchmark::Counter(frames * static_cast<double>(topo.face_count()),
                                               benchmark::Counter::kIsRate);
  state.counters["read_GB/s"] =
      benchmark::Counter(frames * static_cast<double>(bytes) / 1e9, benchmark::Counter::kIsRate);
  state.counters["stream_GB/s"] = stream / 1e9;
  state.counters["sides"] = static_cast<double>(volume.sides.size());
  // bw_fraction needs the loop's time, which Google Benchmark divides by only at report time:
  // computed in the reporter-independent way, from the rate counter's definition.
  state.counters["bw_fraction"] =
      benchmark::Counter(frames * static_cast<double>(bytes) / stream, benchmark::Counter::kIsRate);
}

BENCHMARK(BM_VolumeGeneration)
    ->ArgNames({"tris", "threads", "caps"})
    ->ArgsProduct({{10'000, 100'000, 1'000'000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.5);

// A frame of the demo scene at 1920 x 1080 through the software renderer (issue #4): time per
// stage, and the count pass's fill rate (pixels it processed per second of the count stage).
// Goal: under 0.5 s a frame on this 2-core machine.
void BM_RenderDemo1080(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(0)));
  const Scene scene = *builtin_scene("demo");
  Renderer renderer = soft::soft_renderer();
  const RenderOptions options{1920, 1080, Method::automatic, Generator::automatic};
  FrameStats sum;
  for (auto _ : state) {
    const Frame frame = renderer.render(scene, options);
    sum.ms_depth += frame.stats.ms_depth;
    sum.ms_volumes += frame.stats.ms_volumes;
    sum.ms_counts += frame.stats.ms_counts;
    sum.ms_shade += frame.stats.ms_shade;
    sum.counts.pixels_processed += frame.stats.counts.pixels_processed;
  }
  const double frames = static_cast<double>(state.iterations());
  state.counters["depth_ms"] = sum.ms_depth / frames;
  state.counters["volumes_ms"] = sum.ms_volumes / frames;
  state.counters["counts_ms"] = sum.ms_counts / frames;
  state.counters["shade_ms"] = sum.ms_shade / frames;
  state.counters["count_fill_Mpix/s"] =
      static_cast<double>(sum.counts.pixels_processed) / (sum.ms_counts * 1e3);
}

BENCHMARK(BM_RenderDemo1080)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Issue #5: the software count pass against llvmpipe's stencil pass, on the same volumes (the
// volume cache is warm in both: only the count pass is timed), in the same run. Scenes: the
// demo and light-in-view (a light in view: volumes fill the screen) at 1920 x 1080. Both use
// 2 threads (oneTBB's limit here; llvmpipe takes one rasterizer thread per core).
// Goal: the software backend at least 3x llvmpipe (gl_over_soft >= 3).
void BM_CountPassSoftVsLlvmpipe(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  const char* name = state.range(0) == 0 ? "demo" : "light-in-view";
  const Scene scene = *builtin_scene(name);
  const RenderOptions options{1920, 1080, Method::automatic, Generator::automatic};
  auto soft = make_renderer(Backend::soft);
  auto gl = make_renderer(Backend::gl, {gl::VolumePath::cpu, gl::CountTarget::stencil});
  if (!gl) {
    state.SkipWithError(gl.error().message.c_str());
    return;
  }
  soft->renderer->render(scene, options);  // warm the caches and compile the shaders
  gl->renderer->render(scene, options);
  double soft_ms = 0, gl_ms = 0;
  for (auto _ : state) {
    soft_ms += soft->renderer->render(scene, options).stats.ms_counts;
    gl_ms += gl->renderer->render(scene, options).stats.ms_counts;
  }
  const double frames = static_cast<double>(state.iterations());
  state.SetLabel(name);
  state.counters["soft_counts_ms"] = soft_ms / frames;
  state.counters["llvmpipe_stencil_ms"] = gl_ms / frames;
  state.counters["gl_over_soft"] = gl_ms / soft_ms;
}

BENCHMARK(BM_CountPassSoftVsLlvmpipe)
    ->ArgName("scene")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(8);

}  // namespace

BENCHMARK_MAIN();
