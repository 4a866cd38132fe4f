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
    const std::size_t face_chunks = chunk_count(faces), edge_chunks = chunk_count(edges);
    const std::size_t cap_chunks = job.options.caps ? face_chunks : 0;

    // 1. Face weights, once per face.
    scratch.weights.resize(weight_buffer_size(topo));
    scratch.weights.back() = 0;
    tbb::parallel_for(std::size_t{0}, face_chunks, [&](std::size_t c) {
      const IndexRange r = chunk_range(c, faces);
      compute_face_weights(topo, job.light, generator, r,
                           std::span(scratch.weights).subspan(r.begin, r.end - r.begin));
    });

    // 2. What each chunk will emit: chunks [0, edge_chunks) sides, the rest caps.
    scratch.casting.resize(edge_chunks);
    scratch.quads.assign(edge_chunks, 0);
    scratch.caps.assign(cap_chunks, {});
    tbb::parallel_for(std::size_t{0}, edge_chunks + cap_chunks, [&](std::size_t c) {
      if (c < edge_chunks) {
        scratch.casting[c].clear();
        scratch.quads[c] = find_casting_edges(topo, generator, scratch.weights,
                                              chunk_range(c, edges), scratch.casting[c], job.clamp);
      } else {
        scratch.caps[c - edge_chunks] =
            count_caps(topo, job.light, job.options.far_plane, generator, scratch.weights,
                       chunk_range(c - edge_chunks, faces), job.clamp);
      }
    });

    // 3. Room for all of it, then every chunk writes its part at its own offset.
    VolumeBuffer& out = *job.out;
    out.clear();
    std::size_t quads = 0, light_caps = 0, dark_caps = 0;
    for (std::size_t q : scratch.quads) quads += q;
    for (const CapCount& c : scratch.caps) light_caps += c.light, dark_caps += c.dark;
    const bool parts = job.options.parts;
    const PrimitiveSpan sides_at = out.sides.grow(quads, kQuadCorners, parts);
    const PrimitiveSpan light_at = out.light_caps.grow(light_caps, kTriangleCorners, parts);
    const PrimitiveSpan dark_at = out.dark_caps.grow(dark_caps, kTriangleCorners, parts);
    auto advance = [](PrimitiveSpan at, std::size_t primitives, int corners) {
      return PrimitiveSpan{at.vertices + primitives * static_cast<std::size_t>(corners),
                           at.weights + primitives,
                           at.parts != nullptr ? at.parts + primitives : nullptr};
    };
    tbb::parallel_for(std::size_t{0}, edge_chunks + cap_chunks, [&](std::size_t c) {
      if (c < edge_chunks) {
        std::size_t before = 0;
        for (std::size_t k = 0; k < c; ++k) before += scratch.quads[k];
        write_sides(topo, job.light, job.options.far_plane, generator, scratch.weights,
                    scratch.casting[c], advance(sides_at, before, kQuadCorners), job.clamp);
      } else {
        CapCount before;
        for (std::size_t k = 0; k < c - edge_chunks; ++k) {
          before.light += scratch.caps[k].light;
          before.dark += scratch.caps[k].dark;
        }
        write_caps(topo, job.light, job.options.far_plane, generator, scratch.weights,
                   chunk_range(c - edge_chunks, faces),
                   advance(light_at, before.light, kTriangleCorners),
                   advance(dark_at, before.dark, kTriangleCorners), job.clamp);
      }
    });
  });
}

}  // namespace shadowvol
