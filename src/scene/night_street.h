// shadowvol scene: a street at night, lit by its lamps: many point lights of limited range
// (SceneLight::range), each reaching a stretch of the street (the many-lights case of GPU Gems 3
// §11.2.3 and of engines: per light, work only within its range and scissor).
//
// Owns: the built-in scene `night-street` (kDefaultStreetLamps lamps) and `night-street:N` (N
// lamps, 1 .. kMaxStreetLamps): lamp posts along both kerbs, staggered, a pair every 10 units, each
// lamp a point light 4.4 units up with a range of 8, its glass globe around the light casting no
// shadows and receiving none (it glows); house fronts on both sides, parked cars, people walking
// (they move a little each frame), the camera at eye height looking down the street.
#pragma once

#include <string_view>

#include "core/expected.h"
#include "scene/scene.h"

namespace shadowvol {

inline constexpr int kDefaultStreetLamps = 24, kMaxStreetLamps = 256;

Scene make_night_street(int lamps);
// Whether `name` is night-street or night-street:..., which night_street_by_name answers (with
// an error that says what N must be where it is not a count).
bool is_night_street_name(std::string_view name);
Expected<Scene> night_street_by_name(std::string_view name);

}  // namespace shadowvol
