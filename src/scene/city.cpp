#include "scene/city.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "core/shapes.h"

namespace shadowvol {
namespace {

// A building's random draws: splitmix64 of (seed, draw), so that the city is the same on every
// platform (std's distributions are not).
struct Draws {
  std::uint64_t seed;
  std::uint64_t next = 0;
  double uniform() {
    std::uint64_t z = seed * 0x9e3779b97f4a7c15ull + (++next) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  float between(float lo, float hi) { return lo + (hi - lo) * static_cast<float>(uniform()); }
  bool chance(double p) { return uniform() < p; }
};

constexpr float kKerb = 0.15f;  // the blocks' slabs stand this high over the street
constexpr int kDesigns = 256;   // buildings are placed from this many designs, turned

// Three quads, open, on one vertical edge at `at`: that edge has three faces (non-manifold).
Mesh roof_sign(glm::vec3 at, float height, float reach, float turn) {
  Mesh m;
  m.positions = {at, at + glm::vec3(0, height, 0)};
  for (int k = 0; k < 3; ++k) {
    const float a = turn + glm::radians(120.0f * static_cast<float>(k));
    const glm::vec3 out(reach * std::cos(a), 0.0f, reach * std::sin(a));
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.push_back(at + out);
    m.positions.push_back(at + out + glm::vec3(0, height, 0));
    m.indices.insert(m.indices.end(), {0, base, base + 1, 0, base + 1, 1});
  }
  return m;
}

// A building on a lot centred on the origin, its foot on y = 0: stepped tiers with cornices and
// roof details. Towers (`tower`) are taller and carry an antenna.
Mesh building_design(Draws& d, bool tower) {
  Mesh m;
  const float height = tower ? d.between(60.0f, 150.0f) : d.between(9.0f, 32.0f);
  glm::vec2 half(d.between(5.0f, 8.0f), d.between(5.0f, 8.0f));
  const int tiers = tower ? 3 : d.chance(0.45) ? 2 : 1;
  const float shares[3][3] = {{1.0f}, {0.72f, 0.28f}, {0.55f, 0.3f, 0.15f}};
  float y = 0.0f;
  for (int t = 0; t < tiers; ++t) {
    const float top = y + height * shares[tiers - 1][t];
    append_mesh(m, make_box({-half.x, y, -half.y}, {half.x, top, half.y}));
    const float lip = 0.35f;  // a cornice round the tier's top
    append_mesh(m, make_box({-half.x - lip, top - 0.6f, -half.y - lip},
                            {half.x + lip, top + 0.2f, half.y + lip}));
    y = top;
    half *= glm::vec2(d.between(0.6f, 0.8f), d.between(0.6f, 0.8f));
  }
  const float roof = y + 0.2f;
  auto on_roof = [&](float margin) {
    return glm::vec3(d.between(-half.x + margin, half.x - margin), roof,
                     d.between(-half.y + margin, half.y - margin));
  };
  const int plant = 2 + static_cast<int>(d.uniform() * 3.0);
  for (int k = 0; k < plant; ++k) {
    const glm::vec3 at = on_roof(1.5f);
    const glm::vec3 size(d.between(0.8f, 1.5f), d.between(1.0f, 2.5f), d.between(0.8f, 1.5f));
    append_mesh(m, make_box(at - glm::vec3(size.x, 0.0f, size.z), at + size));
  }
  if (d.chance(0.55)) {
    const glm::vec3 at = on_roof(2.0f);
    append_mesh(m, make_tube(at, at + glm::vec3(0, d.between(3.0f, 4.5f), 0), d.between(1.2f, 1.9f),
                             d.between(1.2f, 1.9f), 16));
  }
  if (tower) {
    const glm::vec3 at(0.0f, roof, 0.0f);
    append_mesh(m, make_tube(at, at + glm::vec3(0, d.between(8.0f, 20.0f), 0), 0.35f, 0.12f, 6));
  }
  if (d.chance(0.35))
    append_mesh(m, roof_sign(on_roof(2.5f), d.between(2.0f, 3.5f), d.between(1.5f, 2.5f),
                             d.between(0.0f, 6.3f)));
  return m;
}

struct Design {
  std::shared_ptr<const Mesh> mesh;
  std::shared_ptr<const Topology> topology;
};

std::string city_name(int buildings, CityView view) {
  std::string name = view == CityView::street ? "city" : "city-above";
  if (buildings != kDefaultCityBuildings) name += ":" + std::to_string(buildings);
  return name;
}

}  // namespace

Scene make_city(int buildings, CityView view) {
  assert(buildings >= 1 && buildings <= kMaxCityBuildings);
  Scene s;
  s.name = city_name(buildings, view);
  constexpr int kPerBlock = kCityLotsPerSide * kCityLotsPerSide;
  constexpr float kBlock = kCityLotsPerSide * kCityLot, kPitch = kBlock + kCityStreet;
  const int blocks = (buildings + kPerBlock - 1) / kPerBlock;
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(blocks))));
  const int rows = (blocks + columns - 1) / columns;

  std::vector<Design> designs;
  for (int i = 0; i < kDesigns; ++i) {
    Draws d{static_cast<std::uint64_t>(i) + 1};
    auto mesh = std::make_shared<const Mesh>(building_design(d, i % 24 == 0));
    designs.push_back({mesh, std::make_shared<const Topology>(build_topology(*mesh))});
  }
  const glm::vec3 extent(columns * kPitch - kCityStreet, 0.0f, rows * kPitch - kCityStreet);
  s.objects.push_back(
      make_object("ground", make_ground(0.5f * std::max(extent.x, extent.z) + 300.0f),
                  glm::translate(glm::mat4(1.0f), 0.5f * extent), {0.32f, 0.32f, 0.34f}));
  const auto kerb = std::make_shared<const Mesh>(make_box({0, 0, 0}, {kBlock, kKerb, kBlock}));
  const auto kerb_topology = std::make_shared<const Topology>(build_topology(*kerb));
  Mesh car_mesh = make_box({-2.1f, 0.25f, -0.9f}, {2.1f, 1.05f, 0.9f});
  append_mesh(car_mesh, make_box({-1.2f, 1.05f, -0.8f}, {0.9f, 1.6f, 0.8f}));
  const auto car = std::make_shared<const Mesh>(std::move(car_mesh));
  const auto car_topology = std::make_shared<const Topology>(build_topology(*car));
  const glm::vec3 palette[] = {{0.72f, 0.68f, 0.6f}, {0.62f, 0.64f, 0.68f}, {0.78f, 0.72f, 0.62f},
                               {0.55f, 0.5f, 0.48f}, {0.68f, 0.58f, 0.5f},  {0.8f, 0.8f, 0.78f}};
  const glm::vec3 paints[] = {{0.75f, 0.15f, 0.12f},
                              {0.15f, 0.3f, 0.7f},
                              {0.85f, 0.85f, 0.82f},
                              {0.2f, 0.2f, 0.22f},
                              {0.85f, 0.65f, 0.15f}};
  int placed = 0;
  for (int b = 0; b < blocks; ++b) {
    const glm::vec3 origin(static_cast<float>(b % columns) * kPitch, 0.0f,
                           static_cast<float>(b / columns) * kPitch);
    s.objects.push_back({"kerb" + std::to_string(b),
                         kerb,
                         kerb_topology,
                         glm::translate(glm::mat4(1.0f), origin),
                         {{0.55f, 0.54f, 0.52f}},
                         {}});
    for (int lot = 0; lot < kPerBlock && placed < buildings; ++lot, ++placed) {
      Draws d{0x5eedull + static_cast<std::uint64_t>(placed)};
      const auto design = static_cast<std::size_t>(d.uniform() * kDesigns);
      const glm::vec3 at =
          origin + glm::vec3((static_cast<float>(lot % kCityLotsPerSide) + 0.5f) * kCityLot, kKerb,
                             (static_cast<float>(lot / kCityLotsPerSide) + 0.5f) * kCityLot);
      const float turn = 90.0f * static_cast<float>(static_cast<int>(d.uniform() * 4.0));
      s.objects.push_back(
          {"building" + std::to_string(placed),
           designs[design].mesh,
           designs[design].topology,
           glm::rotate(glm::translate(glm::mat4(1.0f), at), glm::radians(turn), {0, 1, 0}),
           {palette[static_cast<std::size_t>(d.uniform() * 6.0)]},
           {}});
    }
    // A car in the street along x past this block, in one lane or the other.
    Draws d{0xca7ull + static_cast<std::uint64_t>(b)};
    const float direction = d.chance(0.5) ? 1.0f : -1.0f;
    const glm::vec3 at = origin + glm::vec3(d.between(0.0f, kPitch), 0.0f,
                                            kBlock + 0.5f * kCityStreet + 3.2f * direction);
    SceneObject c{"car" + std::to_string(b),
                  car,
                  car_topology,
                  glm::rotate(glm::translate(glm::mat4(1.0f), at),
                              glm::radians(90.0f - 90.0f * direction), {0, 1, 0}),
                  {paints[static_cast<std::size_t>(d.uniform() * 5.0)]},
                  {}};
    c.animation.move = {direction * d.between(0.3f, 0.6f), 0.0f, 0.0f};
    s.objects.push_back(std::move(c));
  }
  // A low sun that turns over the frames.
  const float elevation = glm::radians(38.0f), azimuth = glm::radians(35.0f);
  s.lights.push_back({{std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                       std::cos(elevation) * std::sin(azimuth), 0.0f},
                      {1.0f, 0.95f, 0.85f},
                      1.0f,
                      0.5f});
  s.ambient = glm::vec3(0.2f, 0.21f, 0.24f);
  if (view == CityView::street) {
    // Down the street along x past the middle row of blocks, walking into the city.
    const float z =
        static_cast<float>(std::max(rows / 2 - 1, 0)) * kPitch + kBlock + 0.5f * kCityStreet - 1.5f;
    s.camera = {{-4.0f, 1.7f, z}, {96.0f, 6.0f, z + 4.0f}};
    s.camera.fov_y_degrees = 60.0f;
    s.camera.near = 0.25f;
    s.camera.move = {1.2f, 0.0f, 0.0f};
  } else {
    s.camera = {{-110.0f, 170.0f, -90.0f}, {220.0f, 0.0f, 260.0f}};
    s.camera.fov_y_degrees = 50.0f;
    s.camera.near = 2.0f;
    s.camera.move = {2.0f, 0.0f, 2.0f};
  }
  return s;
}

Scene with_buildings_merged(const Scene& city) {
  Scene merged = city;
  merged.objects.clear();
  Mesh buildings;
  for (const SceneObject& o : city.objects) {
    if (!o.name.starts_with("building")) {
      merged.objects.push_back(o);
      continue;
    }
    Mesh placed = *o.mesh;
    for (glm::vec3& p : placed.positions) p = glm::vec3(o.transform * glm::vec4(p, 1.0f));
    append_mesh(buildings, placed);
  }
  merged.objects.push_back(
      make_object("buildings", std::move(buildings), glm::mat4(1.0f), {0.7f, 0.7f, 0.7f}));
  return merged;
}

bool is_city_name(std::string_view name) {
  return name == "city" || name == "city-above" || name.starts_with("city:") ||
         name.starts_with("city-above:");
}

Expected<Scene> city_by_name(std::string_view name) {
  const std::string_view full = name;
  CityView view = CityView::street;
  if (name.starts_with("city-above"))
    view = CityView::above, name.remove_prefix(10);
  else
    name.remove_prefix(4);
  int buildings = kDefaultCityBuildings;
  if (!name.empty()) {  // ":N"
    const char* end = name.data() + name.size();
    const auto [at, error] = std::from_chars(name.data() + 1, end, buildings);
    if (name[0] != ':' || name.size() < 2 || error != std::errc{} || at != end || buildings < 1 ||
        buildings > kMaxCityBuildings)
      return make_error("scene '" + std::string(full) +
                        "': a city is named city, city:N, city-above or city-above:N, with N "
                        "buildings from 1 to " +
                        std::to_string(kMaxCityBuildings));
  }
  return make_city(buildings, view);
}

}  // namespace shadowvol
