#include "render/volume_builder.h"

#include <algorithm>

#include <tbb/parallel_for.h>

namespace shadowvol {
namespace {

std::size_t chunk_count(std::size_t n) {
  const std::size_t size = VolumeBuilder::chunk_size(n);
  return (n + size - 1) / size;
}

IndexRange chunk_range(std::size_t chunk, std::size_t n) {
  const std::size_t size = VolumeBuilder::chunk_size(n);
  return {chunk * size, std::min(n, (chunk + 1) * size)};
}

void reserve_for(PrimitiveList& list, std::size_t primitives, int corners) {
  list.vertices.reserve(primitives * static_cast<std::size_t>(corners));
  list.weights.reserve(primitives);
}

}  // namespace

std::size_t VolumeBuilder::chunk_size(std::size_t items) {
  return std::clamp(items / kChunksPerPass, kMinChunk, kMaxChunk);
}

void VolumeBuilder::build(std::span<const VolumeJob> jobs) {
  if (scratch_.size() < jobs.size()) scratch_.resize(jobs.size());
  tbb::parallel_for(std::size_t{0}, jobs.size(), [&](std::size_t j) {
    const VolumeJob& job = jobs[j];
    const Topology& topo = *job.topology;
    Scratch& scratch = scratch_[j];
    const Generator generator = resolve_generator(job.options.generator, topo.report);
    const std::size_t faces = topo.face_count(), edges = topo.edge_count();

    scratch.weights.resize(weight_buffer_size(topo));
    scratch.weights.back() = 0;
    tbb::parallel_for(std::size_t{0}, chunk_count(faces), [&](std::size_t c) {
      const IndexRange r = chunk_range(c, faces);
      compute_face_weights(topo, job.light, generator, r,
                           std::span(scratch.weights).subspan(r.begin, r.end - r.begin));
    });

    // Chunks [0, edge chunks) emit sides, the rest caps: the same order build_volume writes.
    const std::size_t side_chunks = chunk_count(edges);
    const std::size_t cap_chunks = job.options.caps ? chunk_count(faces) : 0;
    scratch.chunks.resize(side_chunks + cap_chunks);
    tbb::parallel_for(std::size_t{0}, side_chunks + cap_chunks, [&](std::size_t c) {
      VolumeBuffer& part = scratch.chunks[c];
      part.clear();
      if (c < side_chunks)
        append_sides(topo, job.light, generator, scratch.weights, chunk_range(c, edges), part);
      else
        append_caps(topo, job.light, generator, scratch.weights,
                    chunk_range(c - side_chunks, faces), part);
    });

    // Join in chunk order. Reserving first keeps a growing first frame from copying its output
    // again at every doubling.
    VolumeBuffer& out = *job.out;
    out.clear();
    std::size_t sides = 0, light_caps = 0, dark_caps = 0;
    for (const VolumeBuffer& part : scratch.chunks) {
      sides += part.sides.size();
      light_caps += part.light_caps.size();
      dark_caps += part.dark_caps.size();
    }
    reserve_for(out.sides, sides, kQuadCorners);
    reserve_for(out.light_caps, light_caps, kTriangleCorners);
    reserve_for(out.dark_caps, dark_caps, kTriangleCorners);
    for (const VolumeBuffer& part : scratch.chunks) out.append(part);
  });
}

}  // namespace shadowvol
