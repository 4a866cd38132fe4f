// The threaded builder gives exactly core's single-threaded output, whatever the thread count.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "core/topology.h"
#include "render/volume_builder.h"
#include "core/shapes.h"
#include "test_meshes.h"

namespace shadowvol {
namespace {

void expect_same(const VolumeBuffer& a, const VolumeBuffer& b) {
  EXPECT_EQ(a.sides.vertices, b.sides.vertices);
  EXPECT_EQ(a.sides.weights, b.sides.weights);
  EXPECT_EQ(a.light_caps.vertices, b.light_caps.vertices);
  EXPECT_EQ(a.light_caps.weights, b.light_caps.weights);
  EXPECT_EQ(a.dark_caps.vertices, b.dark_caps.vertices);
  EXPECT_EQ(a.dark_caps.weights, b.dark_caps.weights);
  EXPECT_EQ(a.sides.parts, b.sides.parts);
  EXPECT_EQ(a.light_caps.parts, b.light_caps.parts);
  EXPECT_EQ(a.dark_caps.parts, b.dark_caps.parts);
}

TEST(VolumeBuilder, MatchesSerialBuildForAnyThreadCount) {
  // Big enough for several chunks of faces and edges, plus small and open objects.
  std::vector<Topology> topologies;
  topologies.push_back(build_topology(make_bumpy_torus_with(50'000)));
  ASSERT_LT(VolumeBuilder::chunk_size(topologies[0].face_count()) * 8,
            topologies[0].face_count());  // many chunks of faces, and of edges
  topologies.push_back(build_topology(testing::box({-1, -1, -1}, {1, 1, 1}, false)));
  topologies.push_back(build_topology(testing::adversarial_meshes(3).back().mesh));
  const glm::vec4 lights[] = {{0.3f, 2.0f, 3.0f, 1.0f}, {0.2f, -0.4f, 1.0f, 0.0f}};
  // The soup has many parts: with parts recorded, each chunk writes them at its own offset too.
  ASSERT_GT(topologies[2].part_count(), 10u);
  for (const glm::vec4& light : lights)
    for (Generator g : {Generator::automatic, Generator::robust, Generator::multiplicity})
      for (const bool parts : {false, true}) {
        const VolumeOptions options{g, true, kPlaneAtInfinity, parts};
        std::vector<VolumeBuffer> serial(topologies.size());
        VolumeScratch scratch;
        for (std::size_t i = 0; i < topologies.size(); ++i)
          build_volume(topologies[i], light, options, scratch, serial[i]);
        ASSERT_GT(serial[0].sides.size(), 100u);
        EXPECT_EQ(serial[2].sides.parts.size(), parts ? serial[2].sides.size() : 0u);
        for (int threads : {1, 2, 4}) {
          tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
          std::vector<VolumeBuffer> parallel(topologies.size());
          std::vector<VolumeJob> jobs;
          for (std::size_t i = 0; i < topologies.size(); ++i)
            jobs.push_back({&topologies[i], light, options, &parallel[i]});
          VolumeBuilder builder;
          builder.build(jobs);
          builder.build(jobs);  // the second frame reuses the scratch memory
          for (std::size_t i = 0; i < topologies.size(); ++i) {
            SCOPED_TRACE("object " + std::to_string(i) + ", " + std::to_string(threads) +
                         " threads, " + std::string(to_string(g)) + (parts ? ", parts" : ""));
            expect_same(parallel[i], serial[i]);
          }
        }
      }
}

}  // namespace
}  // namespace shadowvol
