// shadowvol core: the one camera projection every backend draws with.
//
// An infinite-far perspective (Everitt & Kilgard 2002) with reversed depth: clip space holds
// 0 <= z <= w inside (OpenGL's glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)), and window depth
// z / w = near / distance is 1 on the near plane and falls to 0 at infinity. A point at infinity
// (w = 0 in eye space, where shadow volumes are extruded to) lands exactly on depth 0, so the far
// plane never clips, and the only clip plane that changes what is drawn is the near plane z <= w.
//
// Why reversed: the conventional depth 1 - near / distance crowds every distant surface just
// below 1, where float steps are 6e-8 apart; near / distance keeps float's relative precision at
// every distance, finer by distance / near (50 to 100 times in the built-in scenes). Shadow
// volume sides start exactly on their caster's surface, so near a silhouette vertex their depth
// and the surface's can differ by less than the old steps, and a pixel there be counted wrong.
#pragma once

#include <cmath>

#include <glm/mat4x4.hpp>

namespace shadowvol {

// Eye space looks down -z, y up; `aspect` is width / height.
inline glm::mat4 infinite_reversed_perspective(float fov_y_radians, float aspect, float near) {
  const float f = 1.0f / std::tan(fov_y_radians / 2.0f);
  glm::mat4 m(0.0f);  // column-major: m[column][row]
  m[0][0] = f / aspect;
  m[1][1] = f;
  m[3][2] = near;  // clip z = near, clip w = distance in front of the eye
  m[2][3] = -1.0f;
  return m;
}

}  // namespace shadowvol
