// shadowvol gl: the GLSL of the OpenGL backend (gl_backend.cpp is its only reader).
//
// Why each piece is as it is:
//   - Every position reaches clip space through to_clip() on a vec4, in every stage, so that a
//     light cap and the surface it lies on get bit-identical depths (GPU Gems 3 §11.3.2: "transform
//     the actual rendered scene geometry exactly like the geometry in the shadow volume shader").
//   - Uniform locations are fixed in the source; gl_backend.cpp names them in one enum.
//   - The count passes' fragment shaders, built with STRIPS defined, keep to a strip of the image
//     (discrete clamping, accel/slices.h): a fragment test, so that no triangle is cut and a light
//     cap keeps its surface's depths (raster::ScreenStrip).
//   - Every count draw runs twice, with a pair of programs (SHADOWVOL_GLSL_SLIVERS): the slivers'
//     program alone writes a fragment depth (kCountPrelude), so the rest keeps early depth and
//     stencil tests.
//   - The geometry shader decides a face's facing from its three vertices symmetrically (three
//     normals, three light directions), so that a face gets the same answer as itself and as a
//     neighbour (GPU Gems 3 listing 11-1), and a face of zero area gets 0 and casts nothing.
#pragma once

namespace shadowvol::gl::glsl {

// Uniform locations shared by the programs.
inline constexpr int kMvp = 0, kModel = 1, kNormalMatrix = 2, kRuleSign = 3, kLight = 4,
                     kRobust = 5, kCaps = 6, kEmit = 7, kAlbedo = 8, kRadiance = 9,
                     kCountTexture = 10, kFirstId = 11, kAmbient = 12, kSpecular = 13,
                     kShininess = 14, kBackgroundTop = 15, kBackgroundBottom = 16, kHeight = 17,
                     kFarPlane = 18, kPerCount = 19, kLightMap = 20, kVisibleOnly = 21,
                     kStripAcross = 22, kStripBounds = 23, kViewport = 24, kFalloff = 25,
                     kSmoothNormals = 26, kTextured = 27, kAmbientOnly = 28, kFacingOnly = 29,
                     kSliverPass = 30, kEye = 31;

// Shader storage bindings of the lit pass.
inline constexpr int kFaceNormalsBinding = 0, kPositionsBinding = 1, kIndicesBinding = 2,
                     kCornerNormalsBinding = 3, kUvsBinding = 5;
// The lit pass's texture unit for Material::base_color_map (units 0-2: counts, light map, ids).
inline constexpr int kBaseColorUnit = 3;

// The vertices of a face in the vertex shader's volume mesh (kVolumeExtrusionVertex).
inline constexpr int kVertexVolumeCorners = 24;

// Which caps the volume geometry shader emits (uniform kCaps).
inline constexpr int kCapsNone = 0;   // z-pass of an opaque caster: sides only
inline constexpr int kCapsLight = 1;  // z-pass of a transparent caster: light caps too
inline constexpr int kCapsAll = 2;    // z-fail: light and dark caps

// What the volume geometry shader emits in one draw (uniform kEmit).
inline constexpr int kEmitPositive = 0;  // every primitive of weight +1 (stencil, first draw)
inline constexpr int kEmitNegative = 1;  // back faces' light caps, weight -1, own vertex order
inline constexpr int kEmitWeighted = 2;  // everything, each with its signed weight (additive)

#define SHADOWVOL_GLSL_PRELUDE               \
  "#version 450 core\n"                      \
  "layout(location = 0) uniform mat4 mvp;\n" \
  "vec4 to_clip(vec4 p) {\n"                 \
  "  precise vec4 c = mvp * p;\n"            \
  "  return c;\n"                            \
  "}\n"

// Scene geometry: the depth-and-id pass and the lit passes.
inline constexpr const char* kSurfaceVertex = SHADOWVOL_GLSL_PRELUDE R"(
layout(location = 0) in vec4 position;  // w = 1
layout(location = 1) uniform mat4 model;  // eye-relative
out Surface { vec3 eye_position; } surface;
invariant gl_Position;
void main() {
  surface.eye_position = (model * position).xyz;
  gl_Position = to_clip(position);
}
)";

// With geometry-shader volumes the scene passes through a geometry shader too: a driver may
// place a geometry shader's output on the screen with other rounding than a vertex shader's
// (llvmpipe does), and a light cap must get the depth of the surface it lies on.
inline constexpr const char* kSurfaceGeometry = R"(#version 450 core
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in Surface { vec3 eye_position; } vertices[];
out Surface { vec3 eye_position; } surface;
invariant gl_Position;
void main() {
  for (int i = 0; i < 3; ++i) {
    gl_Position = gl_in[i].gl_Position;
    gl_PrimitiveID = gl_PrimitiveIDIn;
    surface.eye_position = vertices[i].eye_position;
    EmitVertex();
  }
  EndPrimitive();
}
)";

// Depth pass: the face id (0 = background) and the ambient term. Also, with visible_only, a
// colour pass over the faces the depth pass left visible (a face coincident with the visible
// one passes an equal-depth test too, and must not add its colour a second time).
inline constexpr const char* kDepthFragment = R"(#version 450 core
layout(location = 11) uniform uint first_id;
layout(location = 8) uniform vec3 albedo;
layout(location = 12) uniform vec3 ambient;
layout(location = 21) uniform bool visible_only;
layout(binding = 2) uniform usampler2D visible_ids;
layout(location = 0) out uint id;
layout(location = 1) out vec4 color;
void main() {
  id = first_id + uint(gl_PrimitiveID) + 1u;
  if (visible_only && texelFetch(visible_ids, ivec2(gl_FragCoord.xy), 0).r != id) discard;
  color = vec4(ambient * albedo, 1.0);
}
)";

// Occlusion queries (render/occlusion_culling.h): boxes and extruded boxes, eye-relative, drawn
// with the depth test and no writes; with surfaces_only, only where the depth pass left a face
// (the background's depth is 0, which a fragment at infinity would pass).
inline constexpr const char* kQueryVertex = SHADOWVOL_GLSL_PRELUDE R"(
layout(location = 0) in vec4 position;  // w = 0 at infinity
void main() { gl_Position = to_clip(position); }
)";
inline constexpr const char* kQueryFragment = R"(#version 450 core
layout(location = 21) uniform bool surfaces_only;
layout(binding = 2) uniform usampler2D visible_ids;
void main() {
  if (surfaces_only && texelFetch(visible_ids, ivec2(gl_FragCoord.xy), 0).r == 0u) discard;
}
)";

// The opaque depth pass of many objects in one multi-draw (GlBackend::draw_depth): each draw is
// one object, its index the draw's base instance, which picks its transform, first face id and
// albedo. The same product, mvp * p, as to_clip's.
inline constexpr const char* kSurfaceBatchVertex = R"(#version 450 core
struct Object { mat4 mvp; uvec4 first_id; vec4 albedo; };
layout(std430, binding = 4) readonly buffer Objects { Object objects[]; };
layout(location = 0) in vec4 position;  // w = 1
layout(location = 2) in uint object;
flat out uint object_first_id;
flat out vec3 object_albedo;
invariant gl_Position;
void main() {
  object_first_id = objects[object].first_id.x;
  object_albedo = objects[object].albedo.rgb;
  precise vec4 c = objects[object].mvp * position;
  gl_Position = c;
}
)";
inline constexpr const char* kDepthBatchFragment = R"(#version 450 core
flat in uint object_first_id;
flat in vec3 object_albedo;
layout(location = 12) uniform vec3 ambient;
layout(location = 0) out uint id;
layout(location = 1) out vec4 color;
void main() {
  id = object_first_id + uint(gl_PrimitiveID) + 1u;
  color = vec4(ambient * object_albedo, 1.0);
}
)";

// One light where the count is 0: by the stencil test, or by reading the additive count target;
// with transparent casters, times the light that passes them, exp of the log light map. Only
// on the face the depth pass left visible: coincident faces pass the equal-depth test too.
inline constexpr const char* kLitFragment = R"(#version 450 core
in Surface { vec3 eye_position; } surface;
layout(std430, binding = 0) readonly buffer FaceNormals { vec4 normals[]; };
// Smooth shading (render/shading.h, interpolate_smooth): the face's corners, their normals and
// terminator offsets (w).
layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 3) readonly buffer CornerNormals { vec4 corner_normals[]; };
layout(location = 26) uniform bool smooth_normals;
// A texture (Material::base_color_map, sRGB, bilinear, repeating): the corners' coordinates.
layout(std430, binding = 5) readonly buffer Uvs { vec2 uvs[]; };
layout(location = 27) uniform bool textured;
layout(binding = 3) uniform sampler2D base_color_map;
// The ambient term of a textured surface (its depth pass wrote none): radiance * albedo here.
layout(location = 28) uniform bool ambient_only;
// Only whether the face faces the light (RenderOptions::record_facing): 1 where it does.
layout(location = 29) uniform bool facing_only;
layout(location = 1) uniform mat4 model;  // eye-relative
layout(location = 2) uniform mat3 normal_matrix;
layout(location = 8) uniform vec3 albedo;
layout(location = 4) uniform vec4 light;  // eye-relative
layout(location = 9) uniform vec3 radiance;
layout(location = 10) uniform bool count_texture;
layout(location = 13) uniform float specular;
layout(location = 14) uniform float shininess;
layout(location = 20) uniform bool light_map;
layout(location = 25) uniform vec2 falloff;  // render/shading.h: 1 / range^2, inverse square
layout(binding = 0) uniform sampler2D counts;
layout(binding = 1) uniform sampler2D log_light;
layout(location = 11) uniform uint first_id;
layout(binding = 2) uniform usampler2D visible_ids;
layout(location = 1) out vec4 color;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (texelFetch(visible_ids, pixel, 0).r != first_id + uint(gl_PrimitiveID) + 1u) discard;
  // Where needed, the point's barycentric coordinates in its face (render/shading.h).
  vec3 eye_position = surface.eye_position;
  vec3 w = vec3(0.0);
  bool inside = false;
  if (smooth_normals || textured) {
    vec3 c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = (model * positions[indices[3 * gl_PrimitiveID + k]]).xyz;
    vec3 across = cross(c[1] - c[0], c[2] - c[0]);
    if (dot(across, across) > 0.0) {
      w = vec3(max(0.0, dot(cross(c[2] - c[1], eye_position - c[1]), across)),
               max(0.0, dot(cross(c[0] - c[2], eye_position - c[2]), across)),
               max(0.0, dot(cross(c[1] - c[0], eye_position - c[0]), across)));
      float sum = w.x + w.y + w.z;
      inside = sum > 0.0;
      if (inside) w /= sum;
    }
  }
  vec3 surface_albedo = albedo;
  if (textured && inside) {
    int corner = 3 * gl_PrimitiveID;
    vec2 uv = w.x * uvs[corner] + w.y * uvs[corner + 1] + w.z * uvs[corner + 2];
    surface_albedo *= textureLod(base_color_map, vec2(uv.x, 1.0 - uv.y), 0.0).rgb;
  }
  if (ambient_only) {
    color = vec4(radiance * surface_albedo, 0.0);
    return;
  }
  vec3 face = normal_matrix * normals[gl_PrimitiveID].xyz;
  face = length(face) > 0.0 ? normalize(face) : vec3(0.0, 1.0, 0.0);
  vec3 to_eye = normalize(-eye_position);  // the eye is the origin
  bool back = dot(face, to_eye) < 0.0;  // two-sided: light the side we see, as the face shows
  if (back) face = -face;
  vec3 towards = light.w != 0.0 ? light.xyz / light.w - eye_position : light.xyz;
  float d2 = dot(towards, towards);
  float x = d2 * falloff.x;
  // The face, not the normal shaded with, decides the side of the light the surface is on
  // (render/shading.h).
  if (!(dot(face, towards) > 0.0 && x * x < 1.0)) discard;
  if (facing_only) {
    color = vec4(1.0);
    return;
  }
  if (count_texture && texelFetch(counts, ivec2(gl_FragCoord.xy), 0).r != 0.0) discard;
  vec3 arriving = light_map ? exp(texelFetch(log_light, ivec2(gl_FragCoord.xy), 0).rgb) : vec3(1.0);
  vec3 n = face;
  float offset = 0.0;
  if (smooth_normals && inside) {
    int corner = 3 * gl_PrimitiveID;
    vec4 a = corner_normals[corner], b = corner_normals[corner + 1], d = corner_normals[corner + 2];
    vec3 mixed = normal_matrix * (w.x * a.xyz + w.y * b.xyz + w.z * d.xyz);
    if (length(mixed) > 0.0) {
      n = normalize(mixed);
      if (back) n = -n;
      offset = dot(w, vec3(a.w, b.w, d.w));
    }
  }
  float window = 1.0 - x * x;
  float reaching = window * window / (1.0 + d2 * falloff.y);
  vec3 to_light = normalize(towards);
  float lambert = (dot(n, to_light) - offset) / (1.0 - offset);
  if (lambert <= 0.0 || reaching <= 0.0) discard;
  float spec = pow(max(0.0, dot(n, normalize(to_light + to_eye))), shininess);
  color = vec4(reaching * radiance * arriving * (surface_albedo * lambert + vec3(specular * spec)),
               0.0);
}
)";

// Clip points in homogeneous window coordinates (at infinity where w = 0), and the lines through
// them: what the volume stages' sliver test and the count passes' sliver depth share.
#define SHADOWVOL_GLSL_WINDOW                                                                     \
  "layout(location = 24) uniform vec2 viewport;\n"                                                \
  "vec3 to_window(vec4 c) { return vec3((c.xy + c.w) * (0.5 * viewport), c.w); }\n"               \
  "vec3 window_line(vec4 a, vec4 b) { return cross(to_window(a), to_window(b)); }\n"

// Each count draw runs twice, once per program of a pair: the slivers' program draws the
// triangles where kCountPrelude's volume_depth may keep a sliver's depth, the other the rest with
// the rasterizer's depth, early depth and stencil tests and all. volume_depth acts only where both
// long edges of the side lie within half a pixel of the fragment, so a triangle goes to the
// slivers' program where some point of it lies within kReach of both lines (half a pixel, and
// room for snapping and rounding). Its part in front of the near plane (z <= w; nothing behind it
// is drawn: gl_backend.cpp's near_clip) mapped to (distance to one line, distance to the other) is
// a convex polygon; the separating axis test says whether it meets the square of side 2 kReach
// about 0. A cap (no corners) has no lines: it never does.
#define SHADOWVOL_GLSL_SLIVERS                                                                    \
  SHADOWVOL_GLSL_WINDOW                                                                           \
  "layout(location = 30) uniform bool sliver_pass;  // this program draws the slivers\n"          \
  "out float gl_ClipDistance[1];\n"                                                               \
  "// The near plane as a clip plane (enabled under z-fail, which clamps depth: near_clip).\n"    \
  "void set_position(vec4 c) {\n"                                                                 \
  "  gl_Position = c;\n"                                                                          \
  "  gl_ClipDistance[0] = c.w - c.z;\n"                                                           \
  "}\n"                                                                                           \
  "vec4 near_cut(vec4 a, vec4 b) {  // where a-b meets the near plane\n"                          \
  "  float da = a.w - a.z, db = b.w - b.z;\n"                                                     \
  "  return mix(a, b, da / (da - db));\n"                                                         \
  "}\n"                                                                                           \
  "// Whether polygon q (convex, in order) stays off the square |x|, |y| <= r along axis n.\n"    \
  "bool apart(vec2 n, vec2 q[4], float r) {\n"                                                    \
  "  float lo = dot(n, q[0]), hi = lo;\n"                                                         \
  "  for (int i = 1; i < 4; ++i) lo = min(lo, dot(n, q[i])), hi = max(hi, dot(n, q[i]));\n"       \
  "  float reach = r * (abs(n.x) + abs(n.y));\n"                                                  \
  "  return lo > reach || hi < -reach;\n"                                                         \
  "}\n"                                                                                           \
  "// Whether triangle p, q, r of side c (a, a_far, b, b_far) has a point in front of the near\n" \
  "// plane within kReach pixels of both long edges' lines.\n"                                    \
  "bool near_both_edges(vec4 c[4], vec4 p, vec4 q, vec4 r) {\n"                                   \
  "  const float kReach = 0.75;\n"                                                                \
  "  vec3 u = window_line(c[0], c[1]), v = window_line(c[2], c[3]);\n"                            \
  "  float lu = length(u.xy), lv = length(v.xy);\n"                                               \
  "  if (!(lu > 0.0 && lv > 0.0)) return false;  // a cap, or an edge seen end-on\n"              \
  "  bool ip = p.z <= p.w, iq = q.z <= q.w, ir = r.z <= r.w;\n"                                   \
  "  int inside = int(ip) + int(iq) + int(ir);\n"                                                 \
  "  if (inside == 0) return false;\n"                                                            \
  "  if (inside < 3) {  // the odd corner first: the one in front, or the one behind\n"           \
  "    bool odd_q = inside == 1 ? iq : !iq, odd_r = inside == 1 ? ir : !ir;\n"                    \
  "    vec4 t = p;\n"                                                                             \
  "    if (odd_q) p = q, q = r, r = t;\n"                                                         \
  "    else if (odd_r) p = r, r = q, q = t;\n"                                                    \
  "  }\n"                                                                                         \
  "  vec4 corner[4] = vec4[4](p, q, r, r);\n"                                                     \
  "  if (inside == 1) corner = vec4[4](p, near_cut(p, q), near_cut(p, r), near_cut(p, r));\n"     \
  "  if (inside == 2) corner = vec4[4](near_cut(p, q), q, r, near_cut(r, p));\n"                  \
  "  vec2 d[4];  // each corner's signed distances to the two lines\n"                            \
  "  for (int i = 0; i < 4; ++i) {\n"                                                             \
  "    if (!(corner[i].w > 0.0)) return true;  // a point at the eye's horizon\n"                 \
  "    vec3 h = to_window(corner[i]);\n"                                                          \
  "    d[i] = vec2(dot(u, h) / lu, dot(v, h) / lv) / h.z;\n"                                      \
  "  }\n"                                                                                         \
  "  if (apart(vec2(1.0, 0.0), d, kReach) || apart(vec2(0.0, 1.0), d, kReach)) return false;\n"   \
  "  for (int i = 0; i < 4; ++i) {\n"                                                             \
  "    vec2 e = d[(i + 1) % 4] - d[i];\n"                                                         \
  "    if (apart(vec2(-e.y, e.x), d, kReach)) return false;\n"                                    \
  "  }\n"                                                                                         \
  "  return true;\n"                                                                              \
  "}\n"                                                                                           \
  "// Whether this program draws triangle p, q, r of side c (a cap's corners: all 0).\n"          \
  "bool in_this_pass(vec4 c[4], vec4 p, vec4 q, vec4 r) {\n"                                      \
  "  return near_both_edges(c, p, q, r) == sliver_pass;\n"                                        \
  "}\n"

// Volumes built on the CPU: one signed weight per triangle.
inline constexpr const char* kVolumeVertex = SHADOWVOL_GLSL_PRELUDE R"(
layout(location = 0) in vec4 position;  // w = 0 at infinity
layout(location = 1) in int weight;
layout(location = 3) in vec4 side[4];  // its side's a, a_far, b, b_far; 0 on a cap
layout(location = 7) in int second;    // of its side's triangles (a, a_far, b_far), (a, b_far, b)
flat out int primitive_weight;
flat out vec4 side_corners[4];
flat out int side_face;  // kCountPrelude: not known here
invariant gl_Position;
)" SHADOWVOL_GLSL_SLIVERS R"(
void main() {
  primitive_weight = weight;
  side_face = 0;
  vec4 c[4];
  for (int i = 0; i < 4; ++i) c[i] = to_clip(side[i]);
  side_corners = c;
  bool drawn = in_this_pass(c, c[0], second != 0 ? c[3] : c[1], second != 0 ? c[2] : c[3]);
  set_position(drawn ? to_clip(position) : vec4(0.0));  // 0: nothing drawn
}
)";

// CPU volumes of many objects in one draw (GlBackend::count_volumes): each draw of a
// multi-draw is one object's volume, its index the draw's base instance (`object`, a per-instance
// attribute), which picks its transform and mirror sign. The same product, mvp * p, as to_clip's,
// so that a light cap keeps its surface's depths.
inline constexpr const char* kVolumeBatchVertex = R"(#version 450 core
struct Object { mat4 mvp; ivec4 mirror; };
layout(std430, binding = 3) readonly buffer Objects { Object objects[]; };
layout(location = 0) in vec4 position;  // w = 0 at infinity
layout(location = 1) in int weight;
layout(location = 2) in uint object;
layout(location = 3) in vec4 side[4];  // its side's a, a_far, b, b_far; 0 on a cap
layout(location = 7) in int second;    // of its side's triangles (a, a_far, b_far), (a, b_far, b)
flat out int primitive_weight;
flat out vec4 side_corners[4];
flat out int side_face;  // kCountPrelude: not known here
invariant gl_Position;
)" SHADOWVOL_GLSL_SLIVERS R"(
void main() {
  primitive_weight = weight * objects[object].mirror.x;
  side_face = 0;
  vec4 s[4];
  for (int i = 0; i < 4; ++i) s[i] = objects[object].mvp * side[i];
  side_corners = s;
  precise vec4 c = objects[object].mvp * position;
  bool drawn = in_this_pass(s, s[0], second != 0 ? s[3] : s[1], second != 0 ? s[2] : s[3]);
  set_position(drawn ? c : vec4(0.0));
}
)";

// Volumes built on the GPU: the vertex shader hands on object-space positions, and clip-space
// ones computed exactly as the depth pass's vertex shader does (a geometry shader may round
// the same product differently).
inline constexpr const char* kPassVertex = SHADOWVOL_GLSL_PRELUDE R"(
layout(location = 0) in vec4 position;  // w = 0 marks "no neighbour"
out vec4 object_position;
invariant gl_Position;
void main() {
  object_position = position;
  gl_Position = to_clip(position);
}
)";

// What the volume shaders share (geometry and vertex): the volume's uniforms, a face's facing
// and the extrusion onto the far plane, so that both paths decide alike.
#define SHADOWVOL_GLSL_VOLUME                                                                      \
  "layout(location = 4) uniform vec4 light;  // object space\n"                                    \
  "layout(location = 5) uniform bool robust;  // false: standard, light-facing faces\n"            \
  "layout(location = 6) uniform int caps;     // kCapsNone, kCapsLight, kCapsAll\n"                \
  "layout(location = 7) uniform int emit;     // kEmitPositive, kEmitNegative, kEmitWeighted\n"    \
  "layout(location = 18) uniform vec4 far_plane;  // object space; (0, 0, 0, -1): at infinity\n"   \
  "layout(location = 31) uniform vec4 eye;        // object space\n"                              \
  "flat out int primitive_weight;\n"                                                               \
  "flat out vec4 side_corners[4];  // a side's corners (kCountPrelude); 0 on a cap\n"             \
  "flat out int side_face;         // kCountPrelude\n"                                            \
  "invariant gl_Position;\n"                                                                       \
  "\n"                                                                                             \
  "// Which side of the plane of a, b, c point x lies on: 1 in front, -1 behind, 0 on it.\n"       \
  "int side_of(vec4 a, vec4 b, vec4 c, vec4 x) {\n"                                                \
  "  precise vec3 na = cross(b.xyz - a.xyz, c.xyz - a.xyz);\n"                                     \
  "  precise vec3 nb = cross(c.xyz - b.xyz, a.xyz - b.xyz);\n"                                     \
  "  precise vec3 nc = cross(a.xyz - c.xyz, b.xyz - c.xyz);\n"                                     \
  "  precise float da = dot(na, x.xyz - x.w * a.xyz);\n"                                           \
  "  precise float db = dot(nb, x.xyz - x.w * b.xyz);\n"                                           \
  "  precise float dc = dot(nc, x.xyz - x.w * c.xyz);\n"                                           \
  "  if (da > 0.0 || db > 0.0 || dc > 0.0) return 1;\n"                                            \
  "  if (da < 0.0 || db < 0.0 || dc < 0.0) return -1;\n"                                           \
  "  return 0;\n"                                                                                  \
  "}\n"                                                                                            \
  "int facing(vec4 a, vec4 b, vec4 c) { return side_of(a, b, c, light); }\n"                       \
  "\n"                                                                                             \
  "// A side of face f's edges lies wholly on the far side of f's plane from the light, so the\n"  \
  "// eye's ray to a point of f meets it in front of f where eye and light lie on either side:\n"  \
  "// f + 1 then, -(f + 1) where they lie on one side, 0 where the eye is on the plane.\n"         \
  "int face_of_side(vec4 a, vec4 b, vec4 c, int f) {\n"                                            \
  "  int across = facing(a, b, c) * side_of(a, b, c, eye);\n"                                      \
  "  return across < 0 ? f + 1 : across > 0 ? -(f + 1) : 0;\n"                                     \
  "}\n"                                                                                            \
  "\n"                                                                                             \
  "// Its weight (core/volume.cpp, compute_face_weights): robust, the facing; standard, 1 where\n" \
  "// it faces the light or is edge-on to it (a light on its plane) and has an area, else 0.\n"    \
  "int face_weight(vec4 a, vec4 b, vec4 c) {\n"                                                    \
  "  int f = facing(a, b, c);\n"                                                                   \
  "  if (robust || f != 0) return robust ? f : max(f, 0);\n"                                       \
  "  precise vec3 n = cross(b.xyz - a.xyz, c.xyz - a.xyz);\n"                                      \
  "  return n != vec3(0.0) ? 1 : 0;\n"                                                             \
  "}\n"                                                                                            \
  "\n"                                                                                             \
  "// The weight of its dark cap: robust, -weight; standard, 1 for a face that faces away from\n"  \
  "// the light (in its own vertex order), else none: the front faces' caps would vanish where\n"  \
  "// they are edge-on to it (core/volume.cpp, cap_weights).\n"                                    \
  "int dark_cap_weight(vec4 a, vec4 b, vec4 c, int weight) {\n"                                    \
  "  return robust ? -weight : (facing(a, b, c) < 0 ? 1 : 0);\n"                                   \
  "}\n"                                                                                            \
  "\n"                                                                                             \
  "// Where the ray from p away from the light meets the far plane (core/volume.h, extrude).\n"    \
  "vec4 extrude(vec4 p) {\n"                                                                       \
  "  vec3 r = light.w * p.xyz - light.xyz;\n"                                                      \
  "  float along = dot(far_plane.xyz, r), before = dot(far_plane.xyz, p.xyz) + far_plane.w;\n"     \
  "  return vec4(along * p.xyz - before * r, along);\n"                                            \
  "}\n"                                                                                            \
  "\n"

// GPU Gems 3 listing 11-1, in the mesh's own space, for the standard and robust generators.
inline constexpr const char* kVolumeGeometry = SHADOWVOL_GLSL_PRELUDE R"(
layout(triangles_adjacency) in;
layout(triangle_strip, max_vertices = 18) out;
in vec4 object_position[];
)" SHADOWVOL_GLSL_VOLUME SHADOWVOL_GLSL_SLIVERS R"(
vec4 corners[4];  // of the side being emitted (0 for a cap)
int face = 0;      // side_face of the side being emitted (0 for a cap)
// A vertex of the mesh (index i of the input), with the vertex shader's clip position.
void emit_vertex(int i, int weight) {
  primitive_weight = weight;
  side_corners = corners;
  side_face = face;
  set_position(gl_in[i].gl_Position);
  EmitVertex();
}
// The extrusion of vertex i onto the far plane.
void emit_far(int i, int weight) {
  primitive_weight = weight;
  side_corners = corners;
  side_face = face;
  set_position(to_clip(extrude(object_position[i])));
  EmitVertex();
}


void main() {
  vec4 p[6];
  for (int i = 0; i < 6; ++i) p[i] = object_position[i];
  int w = face_weight(p[0], p[2], p[4]), dark = dark_cap_weight(p[0], p[2], p[4], w);
  if (w == 0 && dark == 0) return;
  corners = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
  if (caps != 0 && !sliver_pass) {
    // The light cap keeps its own vertex order (the depth pass's), whatever its sign: a
    // reversed triangle may rasterize to other depths. Hence the separate kEmitNegative draw.
    if (w != 0 && (emit == 2 || (emit == 0 && w > 0) || (emit == 1 && w < 0))) {
      emit_vertex(0, w);
      emit_vertex(2, w);
      emit_vertex(4, w);
      EndPrimitive();
    }
    // The dark cap: reversed where a draw takes only weight +1. (A directional light's dark
    // caps at infinity collapse to a point: none.)
    if (dark != 0 && caps == 2 && emit != 1 &&
        (light.w != 0.0 || far_plane != vec4(0.0, 0.0, 0.0, -1.0))) {
      bool reverse = emit == 0 && dark < 0;
      int weight = emit == 0 ? 1 : dark;
      emit_far(0, weight);
      emit_far(reverse ? 4 : 2, weight);
      emit_far(reverse ? 2 : 4, weight);
      EndPrimitive();
    }
  }
  if (emit == 1 || w == 0) return;
  face = face_of_side(p[0], p[2], p[4], gl_PrimitiveIDIn);
  for (int i = 0; i < 3; ++i) {
    int a = 2 * i, neighbour = 2 * i + 1, b = (2 * i + 2) % 6;
    // Open, non-manifold and inconsistently wound edges have no neighbour (w = 0): every face
    // on them casts its own side. Otherwise a side where the two faces' weights differ.
    if (p[neighbour].w != 0.0 && face_weight(p[a], p[neighbour], p[b]) == w) continue;
    // The side quad (a, a_far, b_far, b) of weight w, as a strip a, a_far, b, b_far.
    if (emit == 0 && w < 0) { int t = a; a = b; b = t; }
    int weight = emit == 0 ? 1 : w;
    corners = vec4[4](gl_in[a].gl_Position, to_clip(extrude(p[a])), gl_in[b].gl_Position,
                      to_clip(extrude(p[b])));
    // As a strip where this program draws both triangles (a, a_far, b), (b, a_far, b_far).
    bool first = in_this_pass(corners, corners[0], corners[1], corners[2]);
    bool second = in_this_pass(corners, corners[2], corners[1], corners[3]);
    if (first) {
      emit_vertex(a, weight);
      emit_far(a, weight);
      emit_vertex(b, weight);
      if (!second) EndPrimitive();
    }
    if (second) {
      if (!first) {
        emit_vertex(b, weight);
        emit_far(a, weight);
      }
      emit_far(b, weight);
      EndPrimitive();
    }
  }
}
)";

// Volumes extruded in the vertex shader (Intel, "Rendering Shadow Volumes"), with the geometry
// shader's decisions above, so that both paths draw the same primitives. The volume mesh is
// fixed per mesh and drawn whole every frame: 24 vertices per face (kVertexVolumeCorners), a
// light cap (0-2), a dark cap (3-5) and, per edge, a quad of two triangles (6-11, 12-17, 18-23),
// each vertex's role (which corner, extruded or not) its index within the face's 24. Its data are
// the geometry shader's input, read from storage buffers: the face's vertices and the far vertices
// of its neighbours (w = 0: none). A primitive the geometry shader would not emit collapses to
// a point, which rasterizes nothing. Extrusion is to the far plane (at infinity by default, w =
// 0), as on the other paths, not to a fixed distance.
inline constexpr const char* kVolumeExtrusionVertex = SHADOWVOL_GLSL_PRELUDE R"(
layout(std430, binding = 4) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 5) readonly buffer Adjacency { uint adjacency[]; };
)" SHADOWVOL_GLSL_VOLUME SHADOWVOL_GLSL_SLIVERS R"(
void main() {
  int face = gl_VertexID / 24, role = gl_VertexID % 24;
  vec4 p[6];
  for (int i = 0; i < 6; ++i) p[i] = points[adjacency[6 * face + i]];
  int w = face_weight(p[0], p[2], p[4]), dark = dark_cap_weight(p[0], p[2], p[4], w);
  // Which vertex of the face this corner is (0, 2 or 4), whether extruded, its primitive's
  // weight, and whether the primitive is drawn at all.
  int vertex = 0, weight = 0;
  bool far = false, drawn = false;
  side_corners = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
  side_face = 0;
  if (role < 3) {  // the light cap, in the depth pass's vertex order
    drawn = w != 0 && caps != 0 && (emit == 2 || (emit == 0 && w > 0) || (emit == 1 && w < 0));
    vertex = 2 * role;
    weight = w;
  } else if (role < 6) {  // the dark cap: reversed where a draw takes only +1
    drawn = dark != 0 && caps == 2 && emit != 1 &&
            (light.w != 0.0 || far_plane != vec4(0.0, 0.0, 0.0, -1.0));
    bool reverse = emit == 0 && dark < 0;
    int corner = role - 3;
    vertex = corner == 0 ? 0 : (corner == 1) == reverse ? 4 : 2;
    far = true;
    weight = emit == 0 ? 1 : dark;
  } else {  // the side of edge i: the strip a, a_far, b, b_far as triangles (a, a_far, b),
            // (b, a_far, b_far)
    int i = (role - 6) / 6, corner = (role - 6) % 6;
    int a = 2 * i, neighbour = 2 * i + 1, b = (2 * i + 2) % 6;
    drawn = w != 0 && emit != 1 &&
            (p[neighbour].w == 0.0 || face_weight(p[a], p[neighbour], p[b]) != w);
    if (emit == 0 && w < 0) { int t = a; a = b; b = t; }
    const int strip[6] = int[6](0, 1, 2, 2, 1, 3);  // strip positions of the two triangles
    int s = strip[corner];
    vertex = s < 2 ? a : b;
    far = s == 1 || s == 3;
    weight = emit == 0 ? 1 : w;
    if (drawn) {
      side_corners = vec4[4](to_clip(p[a]), to_clip(extrude(p[a])), to_clip(p[b]),
                             to_clip(extrude(p[b])));
      side_face = face_of_side(p[0], p[2], p[4], face);
    }
  }
  vec4 c[4] = side_corners;  // this corner's triangle: (a, a_far, b) or (b, a_far, b_far)
  drawn = drawn && (role < 6 || (role - 6) % 6 < 3 ? in_this_pass(c, c[0], c[1], c[2])
                                                   : in_this_pass(c, c[2], c[1], c[3]));
  primitive_weight = weight;
  set_position(!drawn ? vec4(0.0) : to_clip(far ? extrude(p[vertex]) : p[vertex]));
}
)";

// What the count passes' fragment shaders share. With STRIPS, the fragment test of a strip of the
// image, s = strip_across . ndc within strip_bounds (raster::ScreenStrip). And a side's depth where
// it is a sliver, both long edges within half a pixel of the fragment: seen edge-on, its depth
// plane, fitted to vertices snapped to the subpixel grid (llvmpipe: 1/256 pixel), may miss its
// depth there by the whole range (1.0 for 1e-4 on a city, where three sides of one silhouette
// vertex meet on one line behind a receiver), and the count is off by its weight. There its depth
// is kept between those of its long edges where a line across them through the fragment meets
// them; elsewhere it is the rasterizer's. Every stage that draws volumes hands on the corners.
// Only the slivers' program (SLIVERS defined) writes that depth: a written depth keeps the
// rasterizer from testing depth and stencil before the shader, which makes a primitive's fill
// cost two to three times as much on llvmpipe. Its text follows a "#version" line (and
// "#define STRIPS" for the strips' variant, "#define SLIVERS" for the slivers').
inline constexpr const char* kCountPrelude = SHADOWVOL_GLSL_WINDOW R"(
#ifdef STRIPS
layout(location = 22) uniform vec2 strip_across;
layout(location = 23) uniform vec2 strip_bounds;
#endif
void keep_to_strip() {
#ifdef STRIPS
  float s = dot(strip_across, gl_FragCoord.xy / viewport * 2.0 - 1.0);
  if (s < strip_bounds.x || s > strip_bounds.y) discard;
#endif
}

flat in vec4 side_corners[4];  // clip space: a, a_far, b, b_far; all 0 on a cap
// A side's face, f + 1 where the side lies in front of it as the eye sees it, -(f + 1) behind,
// 0 not known (volume stages: face_of_side). Where the depth pass saw f itself, the fragment's
// depth says so: the rasterizer's depths of f and of its edge-on side tie at the edge.
flat in int side_face;
layout(location = 11) uniform uint first_id;
layout(binding = 2) uniform usampler2D visible_ids;

// The window depth at window point q of that line; false where q lies off the segment (a side
// cut short by clamping ends before the fragment: its line is no bound there) or behind the eye.
bool depth_on(vec4 a, vec4 b, vec2 q, out float depth) {
  vec3 ha = to_window(a), d = to_window(b) - ha;
  vec2 num = q * ha.z - ha.xy, den = d.xy - q * d.z;
  float t = abs(den.x) > abs(den.y) ? num.x / den.x : num.y / den.y;
  if (!(t >= 0.0 && t <= 1.0)) return false;
  float w = a.w + t * (b.w - a.w);
  depth = (a.z + t * (b.z - a.z)) / w;
  return w > 0.0;
}

// The fragment's depth: on a sliver, kept between the long edges' depths where the line through
// the fragment across the first edge meets each (the fragment lies between them, so its true
// depth does too).
float volume_depth() {
  const float kSliver = 0.5;  // pixels from the fragment to either edge
  float z = gl_FragCoord.z;
  if (side_face != 0 &&
      texelFetch(visible_ids, ivec2(gl_FragCoord.xy), 0).r == first_id + uint(abs(side_face)))
    return side_face > 0 ? 1.0 : 0.0;  // reversed depth: 1 at the near plane, 0 at infinity
  vec3 u = window_line(side_corners[0], side_corners[1]);
  vec3 v = window_line(side_corners[2], side_corners[3]);
  float lu = length(u.xy), lv = length(v.xy);
  if (!(lu > 0.0 && lv > 0.0)) return z;  // a cap, or no side
  vec2 p = gl_FragCoord.xy, n = u.xy / lu;
  float to_u = dot(u, vec3(p, 1.0)) / lu, across = dot(v.xy, n);
  if (!(abs(across) > 0.5 * lv)) return z;  // the edges are far from parallel: no sliver
  float to_v = -dot(v, vec3(p, 1.0)) / across;
  if (!(abs(to_u) < kSliver && abs(to_v) < kSliver)) return z;
  float zu, zv;
  if (!depth_on(side_corners[0], side_corners[1], p - to_u * n, zu) ||
      !depth_on(side_corners[2], side_corners[3], p + to_v * n, zv))
    return z;
  return clamp(clamp(z, min(zu, zv), max(zu, zv)), 0.0, 1.0);
}
)";

// Counts: additive target (R32F, blended ONE + ONE) or, with colour writes off, the stencil.
// z-pass adds a front face's weight, z-fail subtracts it (kRuleSign), back faces the opposite.
// After kCountPrelude.
inline constexpr const char* kCountFragment = R"(
flat in int primitive_weight;
layout(location = 3) uniform float rule_sign;
layout(location = 0) out float count;
void main() {
  keep_to_strip();
#ifdef SLIVERS
  gl_FragDepth = volume_depth();
#endif
  count = rule_sign * float(primitive_weight) * (gl_FrontFacing ? 1.0 : -1.0);
}
)";

// The log light map of transparent casters (RGBA32F, blended ONE + ONE; Kim et al. §3, Eq. 3):
// each count, as above, times its caster's log transmittance (per_count). After kCountPrelude.
inline constexpr const char* kLightMapFragment = R"(
flat in int primitive_weight;
layout(location = 3) uniform float rule_sign;
layout(location = 19) uniform vec3 per_count;
layout(location = 0) out vec4 log_light;
void main() {
  keep_to_strip();
#ifdef SLIVERS
  gl_FragDepth = volume_depth();
#endif
  float count = rule_sign * float(primitive_weight) * (gl_FrontFacing ? 1.0 : -1.0);
  log_light = vec4(count * per_count, 0.0);
}
)";

// The frame out: lit colour or background, to sRGB.
inline constexpr const char* kFullscreenVertex = R"(#version 450 core
void main() {
  vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Transparent surfaces between the eye and the opaque one: each adds its log transmittance
// (per_count) into the log light target, whichever way it faces; then the colour target is
// multiplied by exp of the sum (blended ZERO, SRC_COLOR): what is seen through all of them.
inline constexpr const char* kCoverFragment = R"(#version 450 core
layout(location = 19) uniform vec3 per_count;
layout(location = 0) out vec4 count;
void main() { count = vec4(per_count, 0.0); }
)";

inline constexpr const char* kSeeThroughFragment = R"(#version 450 core
layout(binding = 1) uniform sampler2D log_light;
layout(location = 1) out vec4 color;
void main() { color = vec4(exp(texelFetch(log_light, ivec2(gl_FragCoord.xy), 0).rgb), 1.0); }
)";

// The background, first into the colour target, so that transparent surfaces filter it too.
inline constexpr const char* kBackgroundFragment = R"(#version 450 core
layout(location = 15) uniform vec3 background_top;
layout(location = 16) uniform vec3 background_bottom;
layout(location = 17) uniform int height;
layout(location = 1) out vec4 color;
void main() {
  float row = float(height - 1 - int(gl_FragCoord.y));  // row 0 at the top, as in soft
  float fade = 1.0 - row / float(height);
  color = vec4(background_bottom + (background_top - background_bottom) * fade, 1.0);
}
)";

inline constexpr const char* kResolveFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D accumulated;
layout(location = 0) out vec4 color;
float to_srgb(float c) {
  c = clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}
void main() {
  vec3 c = texelFetch(accumulated, ivec2(gl_FragCoord.xy), 0).rgb;
  color = vec4(to_srgb(c.r), to_srgb(c.g), to_srgb(c.b), 1.0);
}
)";

#undef SHADOWVOL_GLSL_PRELUDE
#undef SHADOWVOL_GLSL_WINDOW
#undef SHADOWVOL_GLSL_SLIVERS

}  // namespace shadowvol::gl::glsl
