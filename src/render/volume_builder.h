// shadowvol render: VolumeBuilder, shadow volumes of many objects built in parallel (oneTBB).
//
// Owns: the threads of volume generation and the per-object scratch memory that lets a frame
// reuse the last frame's allocations. Output is deterministic: each job's buffer is exactly what
// core's build_volume produces for it, whatever the thread count, because one mesh is split
// into chunks whose size depends on the mesh alone, each chunk counts what it will emit, and
// then writes it in place at the offset the counts before it give (no join, no copy).
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
  VolumeBuffer* out = nullptr;         // caller-owned; cleared and refilled
  const VolumeClamp* clamp = nullptr;  // clamped (core/volume.h), or null
};

class VolumeBuilder {
 public:
  // Faces or edges per chunk: about kChunksPerPass chunks per pass, so that even a small mesh
  // splits across cores, but never so small that scheduling (about 1 us a task) shows, nor so
  // large that the cores wait for one another at the end of a pass. It depends on the mesh
  // alone, never on the thread count: that is what keeps the output deterministic.
  static constexpr std::size_t kChunksPerPass = 16;
  static constexpr std::size_t kMinChunk = 2048;
  static constexpr std::size_t kMaxChunk = 32768;
  static std::size_t chunk_size(std::size_t items);

  // Builds every job. Uses the oneTBB arena of the calling thread, so a tbb::global_control or
  // task_arena set up by the caller limits the threads. Jobs must not share an `out` buffer.
  void build(std::span<const VolumeJob> jobs);

 private:
  struct Scratch {
    std::vector<std::int8_t> weights;
    std::vector<std::vector<std::uint32_t>> casting;  // per edge chunk: its casting edges
    std::vector<std::size_t> quads;                   // per edge chunk: quads they cast
    std::vector<CapCount> caps;                       // per face chunk
  };
  std::vector<Scratch> scratch_;  // one per job slot, kept between frames
};

}  // namespace shadowvol
