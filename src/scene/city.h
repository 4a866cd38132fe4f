// shadowvol scene: a procedural city, the large scene of GPU Gems 3 ch. 11 §11.3.3 (RealityServer's
// city models), where most of the scene and most of its shadows lie behind the buildings in front.
//
// Owns: the city's layout and meshes, deterministic for the same size. Blocks of 4 x 4 lots
// between streets, in a square grid grown from one corner; on each lot a building of one to
// three stepped tiers with cornices, and on its roof plant boxes, some a water tank, towers an
// antenna, and some a sign of three fins that meet on one edge (non-manifold). Each block stands
// on a kerb slab; cars drive along the streets; a low sun turns over the frames.
#pragma once

#include <cstdint>
#include <string_view>

#include "core/expected.h"
#include "scene/scene.h"

namespace shadowvol {

// Where the camera stands: in the middle street at eye height, looking down it and walking along
// it (occlusion culling's case: the buildings on both sides hide the rest of the city), or above
// the city's corner looking over it.
enum class CityView : std::uint8_t { street, above };

inline constexpr int kDefaultCityBuildings = 10000;
inline constexpr int kMaxCityBuildings = 200000;
// A city block's lots a side, the block's pitch (lots and a street) in metres.
inline constexpr int kCityLotsPerSide = 4;
inline constexpr float kCityLot = 18.0f, kCityStreet = 14.0f;

// A city of `buildings` buildings (1 .. kMaxCityBuildings, asserted), about 120 triangles each.
Scene make_city(int buildings, CityView view);

// `city`, `city:N`, `city-above`, `city-above:N`: the city of N buildings (kDefaultCityBuildings
// without N) seen from the street or from above. is_city_name: whether a name has that form
// (`city:x` does, and city_by_name refuses it saying what N must be).
bool is_city_name(std::string_view name);

// The city with its buildings merged into one mesh in world space (the other objects as they
// are): what a user who merges a scene to save draws gives the renderer.
Scene with_buildings_merged(const Scene& city);
Expected<Scene> city_by_name(std::string_view name);

}  // namespace shadowvol
