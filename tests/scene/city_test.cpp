// The procedural city (scene/city.h): its size follows N, it is what the issue asks of it
// (buildings, triangles, non-manifold roof details, moving cars, a turning sun, two views), and
// its names are read or refused.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "scene/city.h"
#include "scene/scene.h"

namespace shadowvol {
namespace {

std::size_t count_named(const Scene& scene, const std::string& prefix) {
  std::size_t n = 0;
  for (const SceneObject& o : scene.objects) n += o.name.starts_with(prefix);
  return n;
}

std::size_t triangles(const Scene& scene) {
  std::size_t n = 0;
  for (const SceneObject& o : scene.objects) n += o.mesh->triangle_count();
  return n;
}

TEST(City, TheDefaultCityHasTenThousandBuildingsAndAMillionTriangles) {
  const Scene city = make_city(kDefaultCityBuildings, CityView::street);
  EXPECT_EQ(city.name, "city");
  EXPECT_EQ(count_named(city, "building"), std::size_t{10000});
  EXPECT_GE(triangles(city), std::size_t{1000000});
  std::size_t nonmanifold = 0, cars = 0;
  for (const SceneObject& o : city.objects) {
    nonmanifold += o.name.starts_with("building") && o.topology->report.nonmanifold_edges > 0;
    cars += o.name.starts_with("car") && !o.animation.still();
  }
  EXPECT_GT(nonmanifold, std::size_t{1000});  // roof signs: three fins on one edge
  EXPECT_GT(cars, std::size_t{100});
  ASSERT_EQ(city.lights.size(), std::size_t{1});
  EXPECT_EQ(city.lights[0].position.w, 0.0f);  // the sun
  EXPECT_NE(city.lights[0].orbit_degrees_per_frame, 0.0f);
}

TEST(City, SizeFollowsTheBuildingsAskedFor) {
  const Scene small = *builtin_scene("city:48");
  const Scene larger = *builtin_scene("city:480");
  EXPECT_EQ(small.name, "city:48");
  EXPECT_EQ(count_named(small, "building"), std::size_t{48});
  EXPECT_EQ(count_named(larger, "building"), std::size_t{480});
  EXPECT_EQ(count_named(small, "kerb"), std::size_t{3});  // 16 lots a block
  const double ratio = double(triangles(larger)) / double(triangles(small));
  EXPECT_GT(ratio, 8.0);
  EXPECT_LT(ratio, 12.0);
  // The same size gives the same city.
  const Scene again = *builtin_scene("city:48");
  ASSERT_EQ(again.objects.size(), small.objects.size());
  for (std::size_t o = 0; o < small.objects.size(); ++o)
    EXPECT_EQ(again.objects[o].transform, small.objects[o].transform);
}

TEST(City, TheStreetViewStandsInAStreetAndTheOtherAboveTheRoofs) {
  const Scene street = *builtin_scene("city:480");
  const Scene above = *builtin_scene("city-above:480");
  EXPECT_EQ(above.name, "city-above:480");
  EXPECT_LT(street.camera.position.y, 2.0f);
  EXPECT_NE(street.camera.move, glm::vec3(0.0f));
  float tallest = 0.0f;
  for (const SceneObject& o : above.objects)
    for (const glm::vec3& p : o.mesh->positions)
      tallest = std::max(tallest, (o.transform * glm::vec4(p, 1.0f)).y);
  EXPECT_GT(above.camera.position.y, tallest);
}

TEST(City, BadNamesAreRefusedSayingWhatNMustBe) {
  for (const char* name :
       {"city:", "city:0", "city:x", "city:12a", "city-above:-3", "city:999999"}) {
    auto scene = builtin_scene(name);
    ASSERT_FALSE(scene.ok()) << name;
    EXPECT_NE(scene.error().message.find("city:N"), std::string::npos) << scene.error().message;
  }
  EXPECT_FALSE(is_city_name("cityscape.json"));  // a file, not a city
}

}  // namespace
}  // namespace shadowvol
