#include "scene/node_animation.h"

#include <algorithm>
#include <cmath>

#include <glm/ext/matrix_transform.hpp>

namespace shadowvol {
namespace {

// The keys around `seconds` and how far between them it lies; one key where it lies outside.
template <class T, class Mix>
T sample_with(const Keyframes<T>& keys, double seconds, Mix mix) {
  const std::vector<double>& t = keys.seconds;
  const auto after = std::upper_bound(t.begin(), t.end(), seconds);
  if (after == t.begin()) return keys.values.front();
  if (after == t.end()) return keys.values.back();
  const std::size_t i = static_cast<std::size_t>(after - t.begin());
  const double span = t[i] - t[i - 1];
  const double along = span > 0.0 ? (seconds - t[i - 1]) / span : 1.0;
  return mix(keys.values[i - 1], keys.values[i], along);
}

const NodeChannels* channels_of(const NodeHierarchy& h, int node, int clip) {
  if (clip < 0 || clip >= static_cast<int>(h.clips.size())) return nullptr;
  for (const NodeChannels& c : h.clips[static_cast<std::size_t>(clip)].channels)
    if (c.node == node) return &c;
  return nullptr;
}

}  // namespace

glm::dvec3 sample(const Keyframes<glm::dvec3>& keys, double seconds) {
  return sample_with(keys, seconds, [](const glm::dvec3& a, const glm::dvec3& b, double s) {
    return a + (b - a) * s;
  });
}

glm::dquat sample(const Keyframes<glm::dquat>& keys, double seconds) {
  // glm::slerp takes the shorter way round, as glTF asks.
  return sample_with(keys, seconds, [](const glm::dquat& a, const glm::dquat& b, double s) {
    return glm::normalize(glm::slerp(a, b, s));
  });
}

glm::dmat4 NodeHierarchy::local_at(int node, int clip, double seconds) const {
  const HierarchyNode& n = nodes[static_cast<std::size_t>(node)];
  const NodeChannels* c = channels_of(*this, node, clip);
  if (c == nullptr) return n.rest;
  const glm::dvec3 t =
      c->translation.empty() ? n.rest_translation : sample(c->translation, seconds);
  const glm::dquat r = c->rotation.empty() ? n.rest_rotation : sample(c->rotation, seconds);
  const glm::dvec3 s = c->scale.empty() ? n.rest_scale : sample(c->scale, seconds);
  return glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(r) * glm::scale(glm::dmat4(1.0), s);
}

glm::dmat4 NodeHierarchy::world_at(int node, int clip, double seconds) const {
  glm::dmat4 world(1.0);
  for (int n = node; n >= 0; n = nodes[static_cast<std::size_t>(n)].parent)
    world = local_at(n, clip, seconds) * world;
  return world;
}

bool NodeHierarchy::moves(int node, int clip) const {
  for (int n = node; n >= 0; n = nodes[static_cast<std::size_t>(n)].parent)
    if (channels_of(*this, n, clip) != nullptr) return true;
  return false;
}

double NodeBinding::seconds_at(int frame) const {
  const double seconds = static_cast<double>(frame) / frames_per_second;
  const double duration = hierarchy->clips[static_cast<std::size_t>(clip)].duration;
  if (!(duration > 0.0)) return 0.0;
  const double wrapped = std::fmod(seconds, duration);
  return wrapped < 0.0 ? wrapped + duration : wrapped;
}

glm::mat4 NodeBinding::transform_at(int frame) const {
  return glm::mat4(placement * hierarchy->world_at(node, clip, seconds_at(frame)) * from_rest);
}

}  // namespace shadowvol
