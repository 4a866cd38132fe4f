// shadowvol render: VolumeCache, the CPU-built shadow volumes of the last frame.
//
// Owns: per light and object the volume core builds (in the object's own space) and what it was
// built from; a volume is rebuilt (in parallel, render/volume_builder.h) only where its object's
// topology, its light seen from the object or its VolumePlan's build options or clamp changed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "core/topology.h"
#include "core/volume.h"
#include "render/frame_plan.h"
#include "render/volume_builder.h"
#include "scene/scene.h"

namespace shadowvol {

class VolumeCache {
 public:
  // Rebuilds the volumes of this light that changed since the last call; counts built and reused
  // into stats. Returns, per object, whether its volume was rebuilt (1) or kept (0), valid until
  // the next call for this light (rebuilt(light)). Calls for one cache come from one thread at a
  // time (render/renderer.h runs them on a worker thread, beside the depth pass).
  const std::vector<std::uint8_t>& update(const Scene& scene, const FramePlan& plan,
                                          std::size_t light, FrameStats& stats);
  const std::vector<std::uint8_t>& rebuilt(std::size_t light) const { return rebuilt_[light]; }
  const VolumeBuffer& volume(std::size_t light, std::size_t object) const {
    return cache_[light][object].volume;
  }

 private:
  struct Entry {
    // Held, not just pointed to: while cached, no other topology can take its address.
    std::shared_ptr<const Topology> topology;
    glm::vec4 light{0.0f};
    VolumeOptions options;
    VolumeClamp clamp;  // the plan's, copied: what the volume was built with
    VolumeBuffer volume;
  };
  VolumeBuilder builder_;
  std::vector<std::vector<Entry>> cache_;  // [light][object]
  std::vector<VolumeJob> jobs_;
  std::vector<std::vector<std::uint8_t>> rebuilt_;  // [light][object]
};

}  // namespace shadowvol
