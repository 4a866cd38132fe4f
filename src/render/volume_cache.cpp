#include "render/volume_cache.h"

namespace shadowvol {

const std::vector<std::uint8_t>& VolumeCache::update(const Scene& scene, const FramePlan& plan,
                                                     std::size_t light, FrameStats& stats) {
  if (cache_.size() < scene.lights.size()) cache_.resize(scene.lights.size());
  if (rebuilt_.size() < scene.lights.size()) rebuilt_.resize(scene.lights.size());
  std::vector<std::uint8_t>& rebuilt = rebuilt_[light];
  std::vector<Entry>& cache = cache_[light];
  cache.resize(scene.objects.size());
  jobs_.clear();
  rebuilt.assign(scene.objects.size(), 0);
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& object = scene.objects[o];
    const VolumePlan& v = plan.volume(light, o);
    Entry& c = cache[o];
    if (v.culled) continue;  // kept as it was: built again if it changed when next drawn
    if (c.topology == object.topology && c.light == v.object_light && c.options == v.build &&
        c.clamp == v.clamp) {
      ++stats.volumes_reused;
      continue;
    }
    c.topology = object.topology;
    c.light = v.object_light;
    c.options = v.build;
    c.clamp = v.clamp;
    jobs_.push_back(
        {c.topology.get(), v.object_light, v.build, &c.volume, v.clamped() ? &c.clamp : nullptr});
    rebuilt[o] = 1;
    ++stats.volumes_built;
  }
  builder_.build(jobs_);
  return rebuilt;
}

}  // namespace shadowvol
