// shadowvol render: VolumeBuilder, shadow volumes of many objects built in parallel (oneTBB).
//
// Owns: the threads of volume generation and the per-object scratch memory that lets a frame
// reuse the last frame's allocations. Output is deterministic: each job's buffer is exactly what
// core's build_volume produces for it, whatever the thread count, because one mesh is split
// into fixed-size chunks (not into as many pieces as there are threads) whose outputs are
// joined in chunk order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "core/topology.h"
#include "core/volume.h"

namespace shadowvol {

struct VolumeJob {
  const Topology* topology = nullptr;
  glm::vec4 light{0.0f};  // homogeneous, in the mesh's own space (see core/volume.h)
  VolumeOptions options;
  VolumeBuffer* out = nullptr;  // caller-owned; cleared and refilled
};

class VolumeBuilder {
 public:
  // Faces or edges per chunk: large enough that a chunk's work dwarfs the scheduling cost
  // (about 1 us per task), small enough that a 100k-triangle mesh still splits across cores.
  static constexpr std::size_t kChunk = 16384;

  // Builds every job. Uses the oneTBB arena of the calling thread, so a tbb::global_control or
  // task_arena set up by the caller limits the threads. Jobs must not share an `out` buffer.
  void build(std::span<const VolumeJob> jobs);

 private:
  struct Scratch {
    std::vector<std::int8_t> weights;
    std::vector<VolumeBuffer> chunks;
  };
  std::vector<Scratch> scratch_;  // one per job slot, kept between frames
};

}  // namespace shadowvol
