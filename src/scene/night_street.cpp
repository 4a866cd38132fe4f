#include "scene/night_street.h"

#include <charconv>
#include <cstdint>
#include <memory>
#include <string>

#include <glm/ext/matrix_transform.hpp>

#include "core/shapes.h"

namespace shadowvol {
namespace {

constexpr std::string_view kName = "night-street";
constexpr float kLampSpacing = 10.0f, kLampHeight = 4.4f, kLampRange = 8.0f;
constexpr float kKerb = 4.0f, kHouseFront = 7.0f;

glm::mat4 at(glm::vec3 position, float yaw_degrees = 0.0f) {
  return glm::rotate(glm::translate(glm::mat4(1.0f), position), glm::radians(yaw_degrees),
                     glm::vec3(0, 1, 0));
}

// A small deterministic hash to vary heights and colours without a global generator.
float vary(int i, int salt) {
  std::uint32_t h =
      static_cast<std::uint32_t>(i) * 2654435761u ^ static_cast<std::uint32_t>(salt) * 40503u;
  h ^= h >> 13, h *= 0x5bd1e995u, h ^= h >> 15;
  return static_cast<float>(h & 0xffffu) / 65535.0f;
}

}  // namespace

Scene make_night_street(int lamps) {
  Scene s;
  s.name = lamps == kDefaultStreetLamps ? std::string(kName)
                                        : std::string(kName) + ":" + std::to_string(lamps);
  const int pairs = (lamps + 1) / 2;
  const float length =
      kLampSpacing * static_cast<float>(pairs) + 14.0f;  // from z = 7 down to -length + 7
  const float middle = 7.0f - 0.5f * length;
  Mesh ground = make_ground(0.5f * length + 6.0f);
  s.objects.push_back(
      make_object("road", std::move(ground), at({0.0f, 0.0f, middle}), {0.32f, 0.32f, 0.34f}));
  // House fronts along both sides, of varied heights, each an object of its own: a lamp's range
  // takes in a few of them, and the rest cast nothing of it.
  for (int side = 0; side < 2; ++side) {
    const float sign = side ? 1.0f : -1.0f;
    int k = 0;
    for (float z = 7.0f; z > 7.0f - length; z -= 6.0f, ++k) {
      const float height = 5.0f + 6.0f * vary(k, side);
      const float depth = 5.0f + 2.0f * vary(k, side + 7);
      const glm::vec3 lo(sign > 0 ? kHouseFront : -kHouseFront - depth, 0.0f, z - 5.8f);
      const glm::vec3 hi(sign > 0 ? kHouseFront + depth : -kHouseFront, height, z);
      const glm::vec3 tint = glm::vec3(0.62f, 0.55f, 0.48f) * (0.85f + 0.3f * vary(k, side + 11));
      s.objects.push_back(make_object((side ? "house_right" : "house_left") + std::to_string(k),
                                      make_box(lo, hi), glm::mat4(1.0f), tint));
    }
  }
  // Lamps: posts in pairs across the street, staggered, each carrying a light in a globe.
  // The post casts; its neck up to the globe does not (a top so close under the light would
  // throw a disc of shadow around the foot).
  const auto post = std::make_shared<const Mesh>(
      make_tube({0.0f, 0.0f, 0.0f}, {0.0f, kLampHeight - 1.0f, 0.0f}, 0.09f, 0.05f, 10));
  const auto post_topology = std::make_shared<const Topology>(build_topology(*post));
  // (It starts inside the post, thinner: no face of one lies on a face of the other.)
  const auto neck = std::make_shared<const Mesh>(make_tube(
      {0.0f, kLampHeight - 1.1f, 0.0f}, {0.0f, kLampHeight - 0.22f, 0.0f}, 0.04f, 0.03f, 10));
  const auto neck_topology = std::make_shared<const Topology>(build_topology(*neck));
  const auto globe = std::make_shared<const Mesh>(make_sphere(glm::vec3(0.0f), 0.25f, 8, 16));
  const auto globe_topology = std::make_shared<const Topology>(build_topology(*globe));
  for (int i = 0; i < lamps; ++i) {
    const float sign = i % 2 ? 1.0f : -1.0f;
    // (2.5 - 5 m never equals a house front 7 - 6 k or side 1.2 - 6 k: no light lies in the plane
    // of a face, which the geometry shader's float facing cannot decide as exactly as the CPU.)
    const float z = 2.5f - kLampSpacing * static_cast<float>(i / 2) - (i % 2 ? 5.0f : 0.0f);
    const glm::vec3 foot(sign * (kKerb + 0.4f), 0.0f, z);
    s.objects.push_back(
        {"post" + std::to_string(i), post, post_topology, at(foot), {{0.2f, 0.22f, 0.2f}}, {}});
    SceneObject top{"neck" + std::to_string(i), neck, neck_topology, at(foot),
                    {{0.2f, 0.22f, 0.2f}},      {}};
    top.casts_shadows = false;
    s.objects.push_back(std::move(top));
    SceneObject lamp{"globe" + std::to_string(i),
                     globe,
                     globe_topology,
                     at(foot + glm::vec3(0.0f, kLampHeight, 0.0f)),
                     {{1.0f, 0.9f, 0.7f}},
                     {}};
    lamp.casts_shadows = false;  // the light is inside it
    lamp.receives_shadows = false;
    s.objects.push_back(std::move(lamp));
    SceneLight light;
    light.position = glm::vec4(foot + glm::vec3(0.0f, kLampHeight, 0.0f), 1.0f);
    light.color = i % 3 == 0 ? glm::vec3(1.0f, 0.78f, 0.5f) : glm::vec3(1.0f, 0.88f, 0.7f);
    light.intensity = 18.0f;
    light.range = kLampRange;
    s.lights.push_back(light);
  }
  // Parked cars along the kerbs, people walking on the pavements.
  const auto robot = std::make_shared<const Mesh>(make_robot());
  const auto robot_topology = std::make_shared<const Topology>(build_topology(*robot));
  for (int i = 0; i < pairs + 2; ++i) {
    const float sign = i % 2 ? 1.0f : -1.0f;
    const float z = 1.0f - 6.5f * static_cast<float>(i) - 2.0f * vary(i, 3);
    if (z < 7.0f - length + 3.0f) break;
    Mesh car = make_box({-0.9f, 0.25f, -2.1f}, {0.9f, 1.0f, 2.1f});
    append_mesh(car, make_box({-0.8f, 1.0f, -1.1f}, {0.8f, 1.5f, 0.9f}));
    const glm::vec3 paint[] = {{0.55f, 0.1f, 0.08f},
                               {0.12f, 0.2f, 0.45f},
                               {0.7f, 0.7f, 0.68f},
                               {0.1f, 0.1f, 0.11f},
                               {0.2f, 0.38f, 0.25f}};
    s.objects.push_back(make_object("car" + std::to_string(i), std::move(car),
                                    at({sign * (kKerb - 1.3f), 0.0f, z}),
                                    paint[static_cast<int>(vary(i, 4) * 4.99f)]));
    SceneObject walker{"walker" + std::to_string(i),
                       robot,
                       robot_topology,
                       at({sign * (kKerb + 1.4f), 0.0f, z - 3.0f}, sign > 0 ? 0.0f : 180.0f),
                       {{0.5f + 0.3f * vary(i, 6), 0.45f, 0.4f}},
                       {}};
    walker.animation.move = {0.0f, 0.0f, sign * 0.05f};
    s.objects.push_back(std::move(walker));
  }
  s.ambient = glm::vec3(0.04f, 0.045f, 0.06f);
  s.camera = {{1.2f, 1.7f, 8.0f}, {0.0f, 2.2f, -30.0f}};
  return s;
}

bool is_night_street_name(std::string_view name) {
  return name == kName || (name.starts_with(kName) && name[kName.size()] == ':');
}

Expected<Scene> night_street_by_name(std::string_view name) {
  int lamps = kDefaultStreetLamps;
  if (name.size() > kName.size()) {
    const char* first = name.data() + kName.size() + 1;
    const char* end = name.data() + name.size();
    const auto [stop, error] = std::from_chars(first, end, lamps);
    if (first == end || error != std::errc{} || stop != end || lamps < 1 || lamps > kMaxStreetLamps)
      return make_error("scene '" + std::string(name) + "': a night street is named " +
                        std::string(kName) + " or " + std::string(kName) +
                        ":N, with N lamps from 1 to " + std::to_string(kMaxStreetLamps));
  }
  return make_night_street(lamps);
}

}  // namespace shadowvol
