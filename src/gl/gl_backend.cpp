#include "gl/gl_backend.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <map>
#include <string>
#include <tuple>

#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "accel/light_reach.h"
#include "core/names.h"
#include "gl/shaders.h"
#include "render/shading.h"
#include "render/volume_costs.h"

namespace shadowvol::gl {
namespace {

// One vertex of an uploaded CPU volume: the position (w = 0 at infinity), its triangle's
// weight, and its side's corners for the count passes' depth of slivers (glsl::kCountPrelude).
struct VolumeVertex {
  glm::vec4 position;
  std::int32_t weight = 0;
  glm::vec4 side[4] = {};   // a, a_far, b, b_far; 0 on a cap
  std::int32_t second = 0;  // of its side's triangles (kQuadTriangles): the sliver test's
};

// The attributes of VolumeVertex from binding 0 of `vao`: position, weight, the side's corners.
void bind_volume_vertices(GLuint vao, GLuint buffer) {
  glVertexArrayVertexBuffer(vao, 0, buffer, 0, sizeof(VolumeVertex));
  glVertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribIFormat(vao, 1, 1, GL_INT, offsetof(VolumeVertex, weight));
  for (GLuint c = 0; c < 4; ++c)
    glVertexArrayAttribFormat(vao, 3 + c, 4, GL_FLOAT, GL_FALSE,
                              GLuint(offsetof(VolumeVertex, side) + c * sizeof(glm::vec4)));
  glVertexArrayAttribIFormat(vao, 7, 1, GL_INT, offsetof(VolumeVertex, second));
  for (GLuint a : {0u, 1u, 3u, 4u, 5u, 6u, 7u}) {
    glVertexArrayAttribBinding(vao, a, 0);
    glEnableVertexArrayAttrib(vao, a);
  }
}

// Grows a buffer to hold `bytes` where it holds less (new storage, its contents lost), and fills
// it with `data` (none: left as it is).
void fill_buffer(Object& buffer, GLsizeiptr& capacity, const void* data, GLsizeiptr bytes) {
  if (bytes > capacity) {
    buffer = make_buffer();
    capacity = std::max(bytes, 2 * capacity);
    glNamedBufferStorage(buffer.get(), capacity, nullptr, GL_DYNAMIC_STORAGE_BIT);
  }
  if (data && bytes > 0) glNamedBufferSubData(buffer.get(), 0, bytes, data);
}

// Copies a bottom-up OpenGL read-back into top-down rows, converting each element.
template <class In, class Out, class Convert>
void flip_rows(const std::vector<In>& in, int w, int h, std::vector<Out>& out, Convert convert) {
  out.resize(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    const In* src = &in[static_cast<std::size_t>(h - 1 - y) * w];
    Out* dst = &out[static_cast<std::size_t>(y) * w];
    for (int x = 0; x < w; ++x) dst[x] = convert(src[x]);
  }
}

}  // namespace

std::string_view to_string(VolumePath path) {
  return path == VolumePath::cpu ? "cpu" : path == VolumePath::gpu ? "gpu" : "vs";
}

Expected<VolumePath> parse_volume_path(std::string_view name) {
  return parse_name(name, {VolumePath::cpu, VolumePath::gpu, VolumePath::vertex}, "volume path");
}

std::string_view to_string(CountTarget target) {
  switch (target) {
    case CountTarget::automatic:
      return "auto";
    case CountTarget::stencil:
      return "stencil";
    case CountTarget::additive:
      return "additive";
  }
  return "unknown";
}

Expected<CountTarget> parse_count_target(std::string_view name) {
  return parse_name(name, {CountTarget::stencil, CountTarget::additive, CountTarget::automatic},
                    "count target");
}

Expected<void> check_settings(const GlSettings& settings, Generator generator) {
  if (settings.volumes != VolumePath::cpu && generator == Generator::multiplicity)
    return make_error(
        "the geometry and vertex shaders build standard or robust volumes (one +-1 side per "
        "face and edge); use --generator robust, standard or auto with --volumes gpu or vs, or "
        "--volumes cpu for multiplicity");
  return {};
}

// The GPU copy of one mesh: what the depth and lit passes draw, and (built on first use) the
// triangles-with-adjacency input of the volume geometry shader.
struct GlBackend::MeshBuffers {
  std::shared_ptr<const Mesh> mesh;
  std::shared_ptr<const Topology> topology;
  Object positions = make_buffer(), indices = make_buffer(), normals = make_buffer();
  Object vao = make_vertex_array();
  GLsizei index_count = 0;
  Object adjacency_positions, adjacency_indices, adjacency_vao;
  GLsizei adjacency_index_count = 0;
  bool used = false;
  std::uint64_t serial = 0;  // unique per backend: a new copy is never taken for an old one

  void build_adjacency();
};

// Six indices per face: its vertices at 0, 2, 4 and, at 1, 3, 5, the far vertex of the face
// across edges 0-1, 1-2, 2-0. Edges that are not a consistent manifold pair (open,
// non-manifold, inconsistently wound: Topology's irregular and boundary edges) point at an
// extra vertex with w = 0, "no neighbour", as in GPU Gems 3 §11.3.2.
void GlBackend::MeshBuffers::build_adjacency() {
  const Topology& topo = *topology;
  const std::size_t faces = topo.face_count();
  const auto none = static_cast<std::uint32_t>(topo.positions.size());
  std::vector<glm::vec4> points;
  points.reserve(topo.positions.size() + 1);
  for (const glm::vec3& p : topo.positions) points.emplace_back(p, 1.0f);
  points.emplace_back(0.0f);
  std::vector<std::uint32_t> adjacency(6 * faces, none);
  const std::uint32_t* fv = topo.face_vertices.data();
  for (std::size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) adjacency[6 * f + 2 * k] = fv[3 * f + k];
  // The far vertex of face g across edge a-b, and the slot of edge a->b in face f.
  auto far_vertex = [&](std::size_t g, std::uint32_t a, std::uint32_t b) {
    for (int k = 0; k < 3; ++k)
      if (fv[3 * g + k] != a && fv[3 * g + k] != b) return fv[3 * g + k];
    return none;
  };
  auto slot = [&](std::size_t f, std::uint32_t a, std::uint32_t b) {
    for (int k = 0; k < 3; ++k)
      if (fv[3 * f + k] == a && fv[3 * f + (k + 1) % 3] == b) return k;
    return -1;
  };
  for (std::size_t e = 0; e < topo.regular_edge_count(); ++e) {
    const auto [f0, f1] = topo.edge_faces[e];
    if (f1 == faces) continue;  // boundary edge
    const auto [u, v] = topo.edge_vertices[e];
    const int s0 = slot(f0, u, v), s1 = slot(f1, v, u);
    if (s0 < 0 || s1 < 0) continue;  // a collapsed face: keep "no neighbour"
    adjacency[6 * f0 + 2 * s0 + 1] = far_vertex(f1, u, v);
    adjacency[6 * f1 + 2 * s1 + 1] = far_vertex(f0, u, v);
  }
  adjacency_positions = make_buffer();
  adjacency_indices = make_buffer();
  adjacency_vao = make_vertex_array();
  glNamedBufferStorage(adjacency_positions.get(),
                       static_cast<GLsizeiptr>(points.size() * sizeof(glm::vec4)), points.data(),
                       0);
  glNamedBufferStorage(adjacency_indices.get(),
                       static_cast<GLsizeiptr>(adjacency.size() * sizeof(std::uint32_t)),
                       adjacency.data(), 0);
  glVertexArrayVertexBuffer(adjacency_vao.get(), 0, adjacency_positions.get(), 0,
                            sizeof(glm::vec4));
  glVertexArrayAttribFormat(adjacency_vao.get(), 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(adjacency_vao.get(), 0, 0);
  glEnableVertexArrayAttrib(adjacency_vao.get(), 0);
  glVertexArrayElementBuffer(adjacency_vao.get(), adjacency_indices.get());
  adjacency_index_count = static_cast<GLsizei>(adjacency.size());
}

// One CPU-built volume on the GPU, its triangles grouped by weight so that a stencil draw can
// take each group with the stencil ops of its sign, |weight| times.
struct GlBackend::VolumeUpload {
  Object buffer = make_buffer();
  Object vao = make_vertex_array();
  struct Group {
    bool zfail;  // counted by z-fail (else z-pass)
    std::int32_t weight;
    GLint first;
    GLsizei count;
  };
  std::vector<Group> groups;  // the z-pass groups first
  GLsizei vertices = 0;
  GLsizei zfail_first = 0;   // the z-fail groups' vertices are [zfail_first, vertices)
  bool unit_weights = true;  // every weight +-1
  // What it was uploaded for: the rule per part changes with the view, not the volume.
  bool zfail = false;
  std::vector<std::uint8_t> part_zfail;

  // The primitives the plan counts, each by its rule (the volume's, or its part's), grouped by
  // rule and weight.
  void upload(const VolumeBuffer& volume, const VolumePlan& plan);
  bool made_for(const VolumePlan& plan) const {
    return zfail == (plan.rule == VolumeRule::zfail) && part_zfail == plan.part_zfail;
  }
};

void GlBackend::VolumeUpload::upload(const VolumeBuffer& volume, const VolumePlan& plan) {
  zfail = plan.rule == VolumeRule::zfail;
  part_zfail = plan.part_zfail;
  std::map<std::pair<bool, std::int32_t>, std::vector<VolumeVertex>> by_rule_and_weight;
  // `everywhere`: the list counts under either rule (else only where z-fail does: caps).
  auto add = [&](const PrimitiveList& list, int corners, bool everywhere) {
    const int per = corners == kQuadCorners ? 2 : 1;
    for (std::size_t p = 0; p < list.size(); ++p) {
      const std::int32_t w = list.weights[p];
      const bool by_zfail = plan.by_part_rule() ? plan.part_zfail[list.parts[p]] != 0 : zfail;
      if (w == 0 || (!everywhere && !by_zfail)) continue;
      std::vector<VolumeVertex>& out = by_rule_and_weight[{by_zfail, w}];
      const glm::vec4* v = &list.vertices[p * static_cast<std::size_t>(corners)];
      for (int t = 0; t < per; ++t)
        for (int k = 0; k < 3; ++k) {
          VolumeVertex vertex{v[kQuadTriangles[3 * t + k]], w};
          if (corners == kQuadCorners)  // (u, u_far, v_far, v): long edges u-u_far, v-v_far
            vertex.side[0] = v[0], vertex.side[1] = v[1], vertex.side[2] = v[3],
            vertex.side[3] = v[2], vertex.second = t;
          out.push_back(vertex);
        }
    }
  };
  add(volume.sides, kQuadCorners, true);
  add(volume.light_caps, kTriangleCorners, plan.light_caps_everywhere);
  add(volume.dark_caps, kTriangleCorners, plan.dark_caps_everywhere());
  std::vector<VolumeVertex> all;
  groups.clear();
  unit_weights = true;
  zfail_first = -1;
  for (auto& [key, vertices] : by_rule_and_weight) {
    const auto [by_zfail, weight] = key;
    if (by_zfail && zfail_first < 0) zfail_first = static_cast<GLsizei>(all.size());
    groups.push_back(
        {by_zfail, weight, static_cast<GLint>(all.size()), static_cast<GLsizei>(vertices.size())});
    all.insert(all.end(), vertices.begin(), vertices.end());
    unit_weights = unit_weights && (weight == 1 || weight == -1);
  }
  vertices = static_cast<GLsizei>(all.size());
  if (zfail_first < 0) zfail_first = vertices;
  buffer = make_buffer();  // storage is immutable: a new buffer per upload
  glNamedBufferStorage(
      buffer.get(),
      static_cast<GLsizeiptr>(std::max<std::size_t>(all.size(), 1) * sizeof(VolumeVertex)),
      all.empty() ? nullptr : all.data(), 0);
  bind_volume_vertices(vao.get(), buffer.get());
}

// The draw buffers of a framebuffer with the ids at attachment 0 and the colour at 1.
namespace {
const GLenum kBoth[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
const GLenum kIdsOnly[] = {GL_COLOR_ATTACHMENT0, GL_NONE};
const GLenum kColourOnly[] = {GL_NONE, GL_COLOR_ATTACHMENT1};
const GLenum kNone[] = {GL_NONE, GL_NONE};
}  // namespace

// The frame's render targets, remade when the size changes.
struct GlBackend::Targets {
  int width = 0, height = 0;
  Object ids = make_texture(GL_TEXTURE_2D), color = make_texture(GL_TEXTURE_2D),
         depth_stencil = make_texture(GL_TEXTURE_2D), counts = make_texture(GL_TEXTURE_2D),
         log_light = make_texture(GL_TEXTURE_2D), out = make_texture(GL_TEXTURE_2D),
         faces = make_texture(GL_TEXTURE_2D);
  // scene: ids, colour, depth-stencil; count: the additive count target and the same
  // depth-stencil; light: the log light map of transparent casters (RGBA32F) and the same
  // depth-stencil; resolved: the sRGB frame; facing: which surfaces face a light
  // (RenderOptions::record_facing), as the lit pass's colour, without depth.
  Object scene = make_framebuffer(), count = make_framebuffer(), light = make_framebuffer(),
         resolved = make_framebuffer(), facing = make_framebuffer();

  Targets(int w, int h) : width(w), height(h) {
    glTextureStorage2D(ids.get(), 1, GL_R32UI, w, h);
    glTextureStorage2D(color.get(), 1, GL_RGBA32F, w, h);
    glTextureStorage2D(depth_stencil.get(), 1, GL_DEPTH32F_STENCIL8, w, h);
    glTextureStorage2D(counts.get(), 1, GL_R32F, w, h);
    glTextureStorage2D(log_light.get(), 1, GL_RGBA32F, w, h);
    glTextureStorage2D(out.get(), 1, GL_RGBA8, w, h);
    glTextureStorage2D(faces.get(), 1, GL_R8, w, h);
    // Read with texelFetch only; nearest filtering also keeps the integer texture complete.
    for (const Object* texture : {&ids, &color, &counts, &log_light, &out}) {
      glTextureParameteri(texture->get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(texture->get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glNamedFramebufferTexture(scene.get(), GL_COLOR_ATTACHMENT0, ids.get(), 0);
    glNamedFramebufferTexture(scene.get(), GL_COLOR_ATTACHMENT1, color.get(), 0);
    glNamedFramebufferTexture(scene.get(), GL_DEPTH_STENCIL_ATTACHMENT, depth_stencil.get(), 0);
    glNamedFramebufferTexture(count.get(), GL_COLOR_ATTACHMENT0, counts.get(), 0);
    glNamedFramebufferTexture(count.get(), GL_DEPTH_STENCIL_ATTACHMENT, depth_stencil.get(), 0);
    glNamedFramebufferTexture(light.get(), GL_COLOR_ATTACHMENT0, log_light.get(), 0);
    glNamedFramebufferTexture(light.get(), GL_DEPTH_STENCIL_ATTACHMENT, depth_stencil.get(), 0);
    glNamedFramebufferTexture(resolved.get(), GL_COLOR_ATTACHMENT0, out.get(), 0);
    glNamedFramebufferTexture(facing.get(), GL_COLOR_ATTACHMENT1, faces.get(), 0);
    glNamedFramebufferDrawBuffers(facing.get(), 2, kColourOnly);
  }
  bool complete() const {
    for (const Object* fbo : {&scene, &count, &light, &resolved, &facing})
      if (glCheckNamedFramebufferStatus(fbo->get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return false;
    return true;
  }
};

Expected<std::unique_ptr<GlBackend>> GlBackend::create(GlSettings settings,
                                                       std::optional<Context> context) {
  if (epoxy_gl_version() < 45)
    return make_error("the OpenGL backend needs OpenGL 4.5; the current context has " +
                      std::to_string(epoxy_gl_version() / 10) + "." +
                      std::to_string(epoxy_gl_version() % 10));
  std::unique_ptr<GlBackend> r(new GlBackend);
  r->context_ = std::move(context);
  r->settings_ = settings;
  r->info_ = query_info();
  GLint texture = 0, viewport[2] = {0, 0}, fbo_width = 0, fbo_height = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &fbo_width);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &fbo_height);
  r->max_image_side_ = std::min({texture, viewport[0], viewport[1], fbo_width, fbo_height});
  using namespace glsl;
  // The count passes' fragment shaders, [strips][slivers]: without and with the strips' fragment
  // test, for the rest and for the slivers.
  std::string count[2][2], light_map[2][2];
  for (int strips = 0; strips < 2; ++strips)
    for (int slivers = 0; slivers < 2; ++slivers) {
      const std::string defined = std::string("#version 450 core\n") +
                                  (strips ? "#define STRIPS\n" : "") +
                                  (slivers ? "#define SLIVERS\n" : "") + kCountPrelude;
      count[strips][slivers] = defined + kCountFragment;
      light_map[strips][slivers] = defined + kLightMapFragment;
    }
  struct Build {
    Object* out;
    const char* name;
    std::initializer_list<ShaderSource> sources;
  };
  const Build builds[] = {
      {&r->surface_depth_[0],
       "depth",
       {{GL_VERTEX_SHADER, kSurfaceVertex}, {GL_FRAGMENT_SHADER, kDepthFragment}}},
      {&r->surface_lit_[0],
       "lit",
       {{GL_VERTEX_SHADER, kSurfaceVertex}, {GL_FRAGMENT_SHADER, kLitFragment}}},
      {&r->surface_depth_[1],
       "depth through a geometry shader",
       {{GL_VERTEX_SHADER, kSurfaceVertex},
        {GL_GEOMETRY_SHADER, kSurfaceGeometry},
        {GL_FRAGMENT_SHADER, kDepthFragment}}},
      {&r->surface_lit_[1],
       "lit through a geometry shader",
       {{GL_VERTEX_SHADER, kSurfaceVertex},
        {GL_GEOMETRY_SHADER, kSurfaceGeometry},
        {GL_FRAGMENT_SHADER, kLitFragment}}},
      {&r->cover_,
       "transparent surfaces in front",
       {{GL_VERTEX_SHADER, kSurfaceVertex}, {GL_FRAGMENT_SHADER, kCoverFragment}}},
      {&r->see_through_,
       "seen through transparent surfaces",
       {{GL_VERTEX_SHADER, kFullscreenVertex}, {GL_FRAGMENT_SHADER, kSeeThroughFragment}}},
      {&r->background_,
       "background",
       {{GL_VERTEX_SHADER, kFullscreenVertex}, {GL_FRAGMENT_SHADER, kBackgroundFragment}}},
      {&r->resolve_,
       "resolve",
       {{GL_VERTEX_SHADER, kFullscreenVertex}, {GL_FRAGMENT_SHADER, kResolveFragment}}},
  };
  auto link = [](const Build& b, const std::string& name) -> Expected<void> {
    auto program = link_program(name.c_str(), b.sources);
    if (!program) return program.error();
    *b.out = std::move(*program);
    return {};
  };
  for (const Build& b : builds)
    if (auto ok = link(b, b.name); !ok) return ok.error();
  // The count passes, over the whole image ([0]) and in strips ([1]), from CPU or GPU volumes,
  // each a pair: the rest and the slivers (sliver_pass set once).
  for (int strips = 0; strips < 2; ++strips)
    for (int slivers = 0; slivers < 2; ++slivers) {
      auto pick = [slivers](CountPrograms& pair) { return slivers ? &pair.slivers : &pair.rest; };
      const char* count_fs = count[strips][slivers].c_str();
      const char* light_map_fs = light_map[strips][slivers].c_str();
      const std::string in = std::string(strips ? " in strips" : "") + (slivers ? ", slivers" : "");
      const Build counts[] = {
          {pick(r->volume_cpu_[strips]),
           "cpu volumes",
           {{GL_VERTEX_SHADER, kVolumeVertex}, {GL_FRAGMENT_SHADER, count_fs}}},
          {pick(r->volume_gpu_[strips]),
           "gpu volumes",
           {{GL_VERTEX_SHADER, kPassVertex},
            {GL_GEOMETRY_SHADER, kVolumeGeometry},
            {GL_FRAGMENT_SHADER, count_fs}}},
          {pick(r->light_map_cpu_[strips]),
           "cpu volumes into the light map",
           {{GL_VERTEX_SHADER, kVolumeVertex}, {GL_FRAGMENT_SHADER, light_map_fs}}},
          {pick(r->light_map_gpu_[strips]),
           "gpu volumes into the light map",
           {{GL_VERTEX_SHADER, kPassVertex},
            {GL_GEOMETRY_SHADER, kVolumeGeometry},
            {GL_FRAGMENT_SHADER, light_map_fs}}},
          {pick(r->volume_vs_[strips]),
           "volumes extruded in the vertex shader",
           {{GL_VERTEX_SHADER, kVolumeExtrusionVertex}, {GL_FRAGMENT_SHADER, count_fs}}},
          {pick(r->light_map_vs_[strips]),
           "volumes extruded in the vertex shader into the light map",
           {{GL_VERTEX_SHADER, kVolumeExtrusionVertex}, {GL_FRAGMENT_SHADER, light_map_fs}}},
          // Batches: CPU volumes only, never in strips (count_volumes).
          {strips ? nullptr : pick(r->volume_batch_),
           "cpu volumes in batches",
           {{GL_VERTEX_SHADER, kVolumeBatchVertex}, {GL_FRAGMENT_SHADER, count_fs}}},
          {strips ? nullptr : pick(r->light_map_batch_),
           "cpu volumes in batches into the light map",
           {{GL_VERTEX_SHADER, kVolumeBatchVertex}, {GL_FRAGMENT_SHADER, light_map_fs}}}};
      for (const Build& b : counts) {
        if (!b.out) continue;
        if (auto ok = link(b, b.name + in); !ok) return ok.error();
        glProgramUniform1i(b.out->get(), kSliverPass, slivers);
      }
    }
  r->empty_vao_ = make_vertex_array();
  r->batch_ = std::make_unique<Batch>();
  r->geometry_ = std::make_unique<SceneGeometry>();
  {
    auto program = link_program("depth in batches", {{GL_VERTEX_SHADER, kSurfaceBatchVertex},
                                                     {GL_FRAGMENT_SHADER, kDepthBatchFragment}});
    if (!program) return program.error();
    r->depth_batch_ = std::move(*program);
  }
  {
    auto query = link_program("occlusion query", {{GL_VERTEX_SHADER, kQueryVertex},
                                                  {GL_FRAGMENT_SHADER, kQueryFragment}});
    if (!query) return query.error();
    r->query_ = std::move(*query);
  }

  if (const std::string error = take_error(); !error.empty())
    return make_error("setting up the OpenGL backend failed with " + error);
  return r;
}

GlBackend::~GlBackend() = default;

GlBackend::MeshBuffers& GlBackend::mesh_buffers(const SceneObject& object) {
  std::unique_ptr<MeshBuffers>& slot = meshes_[object.topology.get()];
  if (!slot || slot->mesh != object.mesh) {
    slot = std::make_unique<MeshBuffers>();
    MeshBuffers& m = *slot;
    m.mesh = object.mesh;
    m.topology = object.topology;
    m.serial = ++mesh_serial_;
    const Mesh& mesh = *object.mesh;
    std::vector<glm::vec4> points;
    points.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) points.emplace_back(p, 1.0f);
    std::vector<glm::vec4> normals(mesh.triangle_count());
    for (std::size_t f = 0; f < normals.size(); ++f) {
      const glm::dvec3 a(mesh.positions[mesh.indices[3 * f]]);
      const glm::dvec3 n = glm::cross(glm::dvec3(mesh.positions[mesh.indices[3 * f + 1]]) - a,
                                      glm::dvec3(mesh.positions[mesh.indices[3 * f + 2]]) - a);
      const double len = glm::length(n);
      normals[f] = glm::vec4(len > 0.0 ? glm::vec3(n / len) : glm::vec3(0.0f), 0.0f);
    }
    glNamedBufferStorage(m.positions.get(),
                         static_cast<GLsizeiptr>(points.size() * sizeof(glm::vec4)), points.data(),
                         0);
    glNamedBufferStorage(m.indices.get(),
                         static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                         mesh.indices.data(), 0);
    glNamedBufferStorage(
        m.normals.get(),
        static_cast<GLsizeiptr>(std::max<std::size_t>(normals.size(), 1) * sizeof(glm::vec4)),
        normals.data(), 0);
    glVertexArrayVertexBuffer(m.vao.get(), 0, m.positions.get(), 0, sizeof(glm::vec4));
    glVertexArrayAttribFormat(m.vao.get(), 0, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(m.vao.get(), 0, 0);
    glEnableVertexArrayAttrib(m.vao.get(), 0);
    glVertexArrayElementBuffer(m.vao.get(), m.indices.get());
    m.index_count = static_cast<GLsizei>(mesh.indices.size());
  }
  slot->used = true;
  return *slot;
}

GlBackend::CornerBuffer& GlBackend::corner_buffer(const std::shared_ptr<const void>& source) {
  CornerBuffer& entry = corner_buffers_[source.get()];
  if (!entry.source) entry.source = source;
  entry.used = true;
  return entry;
}

void GlBackend::object_attributes(const SceneObject& object) {
  GLuint normals = 0, uvs = 0;
  if (const ShadingNormals* smooth = smooth_shading(object)) {
    CornerBuffer& entry = corner_buffer(object.shading);
    if (!entry.buffer) {  // per corner the normal and its terminator offset (w)
      std::vector<glm::vec4> corners(smooth->normals.size());
      for (std::size_t c = 0; c < corners.size(); ++c)
        corners[c] = glm::vec4(smooth->normals[c], smooth->offsets[c]);
      entry.buffer = make_buffer();
      glNamedBufferStorage(entry.buffer.get(),
                           static_cast<GLsizeiptr>(corners.size() * sizeof(glm::vec4)),
                           corners.data(), 0);
    }
    normals = entry.buffer.get();
  }
  if (const std::vector<glm::vec2>* coordinates = texture_coordinates(object)) {
    CornerBuffer& entry = corner_buffer(object.uvs);
    if (!entry.buffer) {
      entry.buffer = make_buffer();
      glNamedBufferStorage(entry.buffer.get(),
                           static_cast<GLsizeiptr>(coordinates->size() * sizeof(glm::vec2)),
                           coordinates->data(), 0);
    }
    uvs = entry.buffer.get();
    const std::shared_ptr<const Texture>& map = object.material.base_color_map;
    GlTexture& t = textures_[map.get()];
    if (!t.source) {
      t.source = map;
      t.texture = make_texture(GL_TEXTURE_2D);
      glTextureStorage2D(t.texture.get(), 1, GL_SRGB8_ALPHA8, map->width, map->height);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTextureSubImage2D(t.texture.get(), 0, 0, 0, map->width, map->height, GL_RGBA,
                          GL_UNSIGNED_BYTE, map->rgba.data());
      glTextureParameteri(t.texture.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(t.texture.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(t.texture.get(), GL_TEXTURE_WRAP_S, GL_REPEAT);
      glTextureParameteri(t.texture.get(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    }
    t.used = true;
  }
  frame_normals_.push_back(normals);
  frame_uvs_.push_back(uvs);
}

Expected<void> check_frame(const GlSettings& settings, const RenderOptions& options) {
  if (soft_only(options.method))
    return make_error("method " + std::string(to_string(options.method)) +
                      " runs in the soft backend only (the split test and the ZP+ pre-fill are "
                      "built in the software rasterizer)");
  if (options.tile_work)
    return make_error("the tile work of a heatmap is counted by the software rasterizer only");
  if (settings.volumes != VolumePath::cpu && clamps_continuous(options.clamp))
    return make_error(
        "continuous clamping builds each volume's segments on the CPU (CC shadow volumes sec. "
        "5.1: volumes built on the GPU do not adapt to it); use --volumes cpu, or --clamp "
        "discrete, which the geometry shader's volumes take");
  return check_settings(settings, options.generator);
}

Expected<void> GlBackend::supports(const RenderOptions& options) const {
  if (options.width > max_image_side_ || options.height > max_image_side_)
    return make_error("image size " + std::to_string(options.width) + "x" +
                      std::to_string(options.height) + " is more than this OpenGL driver draws (" +
                      std::to_string(max_image_side_) + " pixels a side); the soft backend draws " +
                      std::to_string(raster::kMaxViewport));
  return check_frame(settings_, options);
}

void GlBackend::finish() { glFinish(); }

template <class PerObject>
void GlBackend::draw_surfaces(std::span<const std::uint32_t> objects, PerObject&& per_object) {
  const FramePlan& plan = in_->plan;
  for (const std::uint32_t o : objects) {
    const glm::mat4 mvp = plan.view_proj * plan.objects[o].model;
    glUniformMatrix4fv(glsl::kMvp, 1, GL_FALSE, glm::value_ptr(mvp));
    per_object(o);
    glBindVertexArray(frame_meshes_[o]->vao.get());
    glDrawElements(GL_TRIANGLES, frame_meshes_[o]->index_count, GL_UNSIGNED_INT, nullptr);
  }
}

struct GlBackend::SceneGeometry {
  struct Place {
    GLint base_vertex = 0;
    GLuint first_index = 0;
  };
  struct ObjectData {
    glm::mat4 mvp;
    glm::uvec4 first_id;
    glm::vec4 albedo;
  };
  struct Command {  // DrawElementsIndirectCommand
    GLuint count, instances, first_index;
    GLint base_vertex;
    GLuint base_instance;
  };
  Object vertices, indices, vao, objects = make_buffer(), commands = make_buffer();
  Object instance_ids;
  GLsizeiptr object_bytes = 0, command_bytes = 0;
  std::vector<std::uint64_t> made_for;  // the meshes' serials, in the order of first use
  std::unordered_map<const MeshBuffers*, Place> places;
  std::vector<ObjectData> object_data;
  std::vector<Command> draws;
};

void GlBackend::make_scene_geometry() {
  SceneGeometry& g = *geometry_;
  std::vector<const MeshBuffers*> meshes;
  std::vector<std::uint64_t> serials;
  for (const MeshBuffers* m : frame_meshes_)
    if (std::find(meshes.begin(), meshes.end(), m) == meshes.end())
      meshes.push_back(m), serials.push_back(m->serial);
  if (serials == g.made_for && g.vao && g.object_data.capacity() >= frame_meshes_.size()) return;
  g.object_data.reserve(frame_meshes_.size());
  g.made_for = serials;
  g.places.clear();
  GLsizeiptr vertex_count = 0, index_count = 0;
  for (const MeshBuffers* m : meshes) {
    g.places[m] = {GLint(vertex_count), GLuint(index_count)};
    vertex_count += GLsizeiptr(m->mesh->positions.size());
    index_count += m->index_count;
  }
  g.vertices = make_buffer();
  g.indices = make_buffer();
  g.vao = make_vertex_array();
  glNamedBufferStorage(g.vertices.get(), std::max<GLsizeiptr>(vertex_count, 1) * 16, nullptr, 0);
  glNamedBufferStorage(g.indices.get(), std::max<GLsizeiptr>(index_count, 1) * 4, nullptr, 0);
  for (const MeshBuffers* m : meshes) {
    const SceneGeometry::Place at = g.places[m];
    if (!m->mesh->positions.empty())
      glCopyNamedBufferSubData(m->positions.get(), g.vertices.get(), 0,
                               GLintptr(at.base_vertex) * 16,
                               GLsizeiptr(m->mesh->positions.size()) * 16);
    if (m->index_count > 0)
      glCopyNamedBufferSubData(m->indices.get(), g.indices.get(), 0, GLintptr(at.first_index) * 4,
                               GLsizeiptr(m->index_count) * 4);
  }
  std::vector<GLuint> ids(std::max<std::size_t>(frame_meshes_.size(), 1));
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = GLuint(i);
  g.instance_ids = make_buffer();
  glNamedBufferStorage(g.instance_ids.get(), GLsizeiptr(ids.size() * sizeof(GLuint)), ids.data(),
                       0);
  glVertexArrayVertexBuffer(g.vao.get(), 0, g.vertices.get(), 0, sizeof(glm::vec4));
  glVertexArrayAttribFormat(g.vao.get(), 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayVertexBuffer(g.vao.get(), 1, g.instance_ids.get(), 0, sizeof(GLuint));
  glVertexArrayAttribIFormat(g.vao.get(), 2, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayBindingDivisor(g.vao.get(), 1, 1);
  for (GLuint a : {0u, 2u}) {
    glVertexArrayAttribBinding(g.vao.get(), a, a == 2 ? 1 : 0);
    glEnableVertexArrayAttrib(g.vao.get(), a);
  }
  glVertexArrayElementBuffer(g.vao.get(), g.indices.get());
}

void GlBackend::begin_frame(const FrameInputs& inputs) {
  in_ = &inputs;
  queries_used_ = 0;
  const int w = inputs.options.width, h = inputs.options.height;
  if (!targets_ || targets_->width != w || targets_->height != h) {
    targets_ = std::make_unique<Targets>(w, h);
    assert(targets_->complete());
  }
  for (auto& [topology, buffers] : meshes_) buffers->used = false;
  for (auto& [texture, gl_texture] : textures_) gl_texture.used = false;
  for (auto& [source, buffer] : corner_buffers_) buffer.used = false;
  frame_meshes_.clear();
  frame_normals_.clear();
  frame_uvs_.clear();
  transparent_.clear();
  for (std::uint32_t o = 0; o < inputs.scene.objects.size(); ++o) {
    frame_meshes_.push_back(&mesh_buffers(inputs.scene.objects[o]));
    object_attributes(inputs.scene.objects[o]);
    if (inputs.plan.transparent(o)) transparent_.push_back(o);
  }
  std::erase_if(meshes_, [](const auto& entry) { return !entry.second->used; });
  std::erase_if(textures_, [](const auto& entry) { return !entry.second.used; });
  std::erase_if(corner_buffers_, [](const auto& entry) { return !entry.second.used; });
  cpu_ = settings_.volumes == VolumePath::cpu;
  gs_ = settings_.volumes == VolumePath::gpu;
  uploads_.resize(std::max(uploads_.size(), inputs.scene.lights.size()));

  glViewport(0, 0, w, h);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_DEPTH_CLAMP);
  // Reversed depth, as core/projection.h makes it: clip z in [0, w], window depth z / w.
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

// The opaque layer: the background, then face ids and the ambient term. The glass layer: the
// nearest transparent surface in front of the opaque one (ids), then its ambient term where it
// is the one left visible (end_depth).
void GlBackend::begin_depth(Layer layer) {
  layer_ = layer;
  depth_read_ = false;
  drawn_[static_cast<int>(layer)].clear();
  Targets& t = *targets_;
  glBindFramebuffer(GL_FRAMEBUFFER, t.scene.get());
  if (layer == Layer::glass) return;
  // The clear takes draw buffer 0 as the draw buffers stand: attachment 0 must be among them.
  glNamedFramebufferDrawBuffers(t.scene.get(), 2, kBoth);
  const GLuint no_id = 0;
  glClearNamedFramebufferuiv(t.scene.get(), GL_COLOR, 0, &no_id);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  glClearNamedFramebufferfi(t.scene.get(), GL_DEPTH_STENCIL, 0, 0.0f, 0);
  glNamedFramebufferDrawBuffers(t.scene.get(), 2, kColourOnly);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(background_.get());
  glUniform3fv(glsl::kBackgroundTop, 1, glm::value_ptr(shading::kBackgroundTop));
  glUniform3fv(glsl::kBackgroundBottom, 1, glm::value_ptr(shading::kBackgroundBottom));
  glUniform1i(glsl::kHeight, in_->options.height);
  glBindVertexArray(empty_vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void GlBackend::draw_depth(std::span<const std::uint32_t> objects) {
  const Scene& scene = in_->scene;
  const FramePlan& plan = in_->plan;
  const bool opaque = layer_ == Layer::opaque;
  Targets& t = *targets_;
  // The state each batch, as queries between batches change it.
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_GREATER);  // nearer is greater
  glNamedFramebufferDrawBuffers(t.scene.get(), 2, opaque ? kBoth : kIdsOnly);
  glUseProgram(surface_depth_[gs_ ? 1 : 0].get());
  std::vector<std::uint32_t>& drawn = drawn_[static_cast<int>(layer_)];
  drawn.insert(drawn.end(), objects.begin(), objects.end());
  // The opaque layer's objects in one multi-draw, where the surfaces pass the vertex shader alone.
  if (batching_ && !gs_ && opaque && objects.size() > 1) {
    make_scene_geometry();
    SceneGeometry& g = *geometry_;
    g.object_data.resize(plan.objects.size());
    g.draws.clear();
    for (const std::uint32_t o : objects) {
      const SceneGeometry::Place at = g.places.at(frame_meshes_[o]);
      g.object_data[o] = {
          plan.view_proj * plan.objects[o].model, glm::uvec4(plan.objects[o].first_id),
          glm::vec4(frame_uvs_[o] != 0 ? glm::vec3(0.0f) : scene.objects[o].material.color, 1.0f)};
      g.draws.push_back(
          {GLuint(frame_meshes_[o]->index_count), 1, at.first_index, at.base_vertex, o});
    }
    fill_buffer(g.objects, g.object_bytes, g.object_data.data(),
                GLsizeiptr(g.object_data.size() * sizeof(SceneGeometry::ObjectData)));
    fill_buffer(g.commands, g.command_bytes, g.draws.data(),
                GLsizeiptr(g.draws.size() * sizeof(SceneGeometry::Command)));
    glUseProgram(depth_batch_.get());
    glUniform3fv(glsl::kAmbient, 1, glm::value_ptr(scene.ambient));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, g.objects.get());
    glBindVertexArray(g.vao.get());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, g.commands.get());
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, GLsizei(g.draws.size()), 0);
    glDepthMask(GL_FALSE);
    return;
  }
  glUniform3fv(glsl::kAmbient, 1, glm::value_ptr(scene.ambient));
  glUniform1i(glsl::kVisibleOnly, GL_FALSE);
  draw_surfaces(objects, [&](std::size_t o) {
    glUniform1ui(glsl::kFirstId, plan.objects[o].first_id);
    const glm::vec3 albedo = frame_uvs_[o] != 0 ? glm::vec3(0.0f) : scene.objects[o].material.color;
    glUniform3fv(glsl::kAlbedo, 1, glm::value_ptr(albedo));
  });
  glDepthMask(GL_FALSE);
}

void GlBackend::end_depth() {
  ambient_textured(layer_);
  if (layer_ == Layer::opaque) return;
  const Scene& scene = in_->scene;
  const FramePlan& plan = in_->plan;
  Targets& t = *targets_;
  glUseProgram(surface_depth_[gs_ ? 1 : 0].get());
  glNamedFramebufferDrawBuffers(t.scene.get(), 2, kColourOnly);
  glDepthFunc(GL_EQUAL);
  glEnable(GL_BLEND);
  glBindTextureUnit(2, t.ids.get());  // read, not written: attachment 0 is off
  glUniform1i(glsl::kVisibleOnly, GL_TRUE);
  glBlendFunc(GL_ONE, GL_ONE);  // colour += opacity * ambient * albedo
  glUniform3fv(glsl::kAmbient, 1, glm::value_ptr(scene.ambient));
  draw_surfaces(drawn_[static_cast<int>(Layer::glass)], [&](std::size_t o) {
    const Material& material = scene.objects[o].material;
    const glm::vec3 reflected = frame_uvs_[o] != 0
                                    ? glm::vec3(0.0f)
                                    : material.opacity * material.color;  // ambient_textured
    glUniform1ui(glsl::kFirstId, plan.objects[o].first_id);
    glUniform3fv(glsl::kAlbedo, 1, glm::value_ptr(reflected));
  });
  glUniform1i(glsl::kVisibleOnly, GL_FALSE);
  glDisable(GL_BLEND);
  glDepthFunc(GL_GREATER);
}

FrameBackend::QueryId GlBackend::issue_query(std::span<const glm::vec4> triangles,
                                             bool surfaces_only) {
  if (queries_used_ == queries_.size())
    queries_.push_back(make_query(GL_ANY_SAMPLES_PASSED_CONSERVATIVE));
  const auto id = static_cast<QueryId>(queries_used_++);
  // A new buffer each query: immutable storage, released by the driver once drawn.
  const Object buffer = make_buffer();
  glNamedBufferStorage(buffer.get(), static_cast<GLsizeiptr>(triangles.size_bytes()),
                       triangles.data(), 0);
  glVertexArrayVertexBuffer(query_vao_.get(), 0, buffer.get(), 0, sizeof(glm::vec4));
  glVertexArrayAttribFormat(query_vao_.get(), 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(query_vao_.get(), 0, 0);
  glEnableVertexArrayAttrib(query_vao_.get(), 0);
  Targets& t = *targets_;
  glNamedFramebufferDrawBuffers(t.scene.get(), 2, kNone);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_GEQUAL);  // at or in front of the stored depth
  glUseProgram(query_.get());
  glUniformMatrix4fv(glsl::kMvp, 1, GL_FALSE, glm::value_ptr(in_->plan.view_proj));
  glUniform1i(glsl::kVisibleOnly, surfaces_only ? GL_TRUE : GL_FALSE);
  glBindTextureUnit(2, t.ids.get());
  glBindVertexArray(query_vao_.get());
  glBeginQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, queries_[id].get());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size()));
  glEndQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE);
  glDepthFunc(GL_GREATER);
  return id;
}

bool GlBackend::query_ready(QueryId query) {
  GLuint ready = GL_FALSE;
  glGetQueryObjectuiv(queries_[query].get(), GL_QUERY_RESULT_AVAILABLE, &ready);
  return ready == GL_TRUE;
}

bool GlBackend::query_visible(QueryId query) {
  GLuint passed = GL_FALSE;
  glGetQueryObjectuiv(queries_[query].get(), GL_QUERY_RESULT, &passed);
  return passed != GL_FALSE;
}

void GlBackend::read_ids(Layer layer, SurfaceLayer& out) {
  const int w = in_->options.width, h = in_->options.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  std::vector<std::uint32_t>& ids = read_ids_;
  ids.resize(pixels);
  glNamedFramebufferReadBuffer(targets_->scene.get(), GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, targets_->scene.get());
  glReadnPixels(0, 0, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT,
                static_cast<GLsizei>(pixels * sizeof(std::uint32_t)), ids.data());
  out.object.assign(pixels, -1);
  out.face.assign(pixels, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::uint32_t id = ids[static_cast<std::size_t>(h - 1 - y) * w + x];
      if (id == 0) continue;
      const auto [object, face] = in_->plan.object_of(id - 1);
      // After the glass layer's depth pass, the ids of opaque surfaces it did not cover remain.
      if (object < 0 ||
          in_->plan.transparent(static_cast<std::size_t>(object)) != (layer == Layer::glass))
        continue;
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      out.object[p] = object;
      out.face[p] = face;
    }
}

// Volumes: from the CPU cache (uploaded where rebuilt), or none to make here (the geometry
// shader builds them during the count pass).
void GlBackend::volumes_ready(std::size_t l, const std::vector<std::uint8_t>& rebuilt) {
  const FramePlan& plan = in_->plan;
  std::vector<std::unique_ptr<VolumeUpload>>& uploads = uploads_[l];
  unit_weights_ = true;
  if (!cpu_) uploads.clear();  // the cache may change unseen: upload afresh when back on cpu
  uploads.resize(plan.objects.size());
  for (std::size_t o = 0; cpu_ && o < plan.objects.size(); ++o) {
    const VolumePlan& v = plan.volume(l, o);
    if (v.culled) {  // not drawn; its cached volume may be stale: uploaded afresh when drawn
      uploads[o].reset();
      continue;
    }
    const bool fresh = !uploads[o];
    if (fresh) uploads[o] = std::make_unique<VolumeUpload>();
    if (fresh || rebuilt[o] || !uploads[o]->made_for(v))
      uploads[o]->upload(in_->volumes.volume(l, o), v);
    if (!plan.transparent(o)) unit_weights_ = unit_weights_ && uploads[o]->unit_weights;
  }
}

namespace {

// The clip-to-window depth rule of both backends: fragments nearer than the stored depth pass
// (z-pass counts them), the others fail (z-fail counts them).
enum class Rule : std::uint8_t { zpass, zfail };

// Sets up one draw of weight sign `sign` under `rule`, into an additive target or the stencil.
void count_state(const CountPrograms& programs, bool additive, Rule rule, int sign) {
  if (additive) {
    glDepthFunc(rule == Rule::zpass ? GL_GREATER : GL_LEQUAL);
    const auto rule_sign = static_cast<float>(rule == Rule::zpass ? sign : -sign);
    programs.each([&](GLuint p) { glProgramUniform1f(p, glsl::kRuleSign, rule_sign); });
    return;
  }
  glDepthFunc(GL_GREATER);
  const GLenum up = sign > 0 ? GL_INCR_WRAP : GL_DECR_WRAP;
  const GLenum down = sign > 0 ? GL_DECR_WRAP : GL_INCR_WRAP;
  if (rule == Rule::zpass) {
    glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, up);
    glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, down);
  } else {
    glStencilOpSeparate(GL_FRONT, GL_KEEP, down, GL_KEEP);
    glStencilOpSeparate(GL_BACK, GL_KEEP, up, GL_KEEP);
  }
}

// z-fail's dark caps lie on w = 0, where rounding may push a depth below 0: it clamps depth
// rather than clip there, and clips at the near plane by a clip distance, so that no drawn
// triangle reaches towards the eye's plane, where depth z / w grows without bound (a sliver's
// depth plane misses by its depth range; glsl::SHADOWVOL_GLSL_SLIVERS). What lies before the near
// plane never counts under z-fail: its clamped depth 1 passes. z-pass clips there as the software
// backend does.
void near_clip(Rule rule) {
  if (rule == Rule::zfail) {
    glEnable(GL_DEPTH_CLAMP);
    glEnable(GL_CLIP_DISTANCE0);
  } else {
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_CLIP_DISTANCE0);
  }
}

}  // namespace

void GlBackend::draw_volume(std::size_t l, std::size_t o, bool additive) {
  const FramePlan& plan = in_->plan;
  const VolumePlan& v = plan.volume(l, o);
  const glm::mat4 mvp = plan.view_proj * plan.objects[o].model;
  const CountPrograms& programs = *counting_;
  programs.each([&](GLuint p) {
    glProgramUniformMatrix4fv(p, glsl::kMvp, 1, GL_FALSE, glm::value_ptr(mvp));
    glProgramUniform1ui(p, glsl::kFirstId, plan.objects[o].first_id);
  });
  const int mirror = plan.objects[o].weight_sign;
  // The volume's primitives of one rule: all of them, or (CPU volumes under rules per part) those
  // of the parts of that rule.
  struct Range {
    Rule rule;
    GLint first = 0;
    GLsizei count = 0;
  };
  std::vector<Range> ranges;
  // The draws of a range: into the target, or (all) every primitive once, for its fill.
  std::function<void(const Range&)> draw, draw_all;
  if (cpu_) {
    const VolumeUpload* up = uploads_[l][o].get();
    glBindVertexArray(up->vao.get());
    ranges = {{Rule::zpass, 0, up->zfail_first},
              {Rule::zfail, up->zfail_first, up->vertices - up->zfail_first}};
    auto triangles = [this](GLint first, GLsizei count) {
      count_draw([=] { glDrawArrays(GL_TRIANGLES, first, count); });
    };
    draw = [&programs, up, additive, mirror, triangles](const Range& range) {
      if (additive) {
        count_state(programs, true, range.rule, mirror);
        triangles(range.first, range.count);
        return;
      }
      for (const VolumeUpload::Group& g : up->groups) {
        if (g.zfail != (range.rule == Rule::zfail)) continue;
        count_state(programs, false, range.rule, g.weight > 0 ? mirror : -mirror);
        for (int k = 0; k < std::abs(g.weight); ++k) triangles(g.first, g.count);
      }
    };
    draw_all = [triangles](const Range& range) { triangles(range.first, range.count); };
  } else {
    const Rule rule = v.rule == VolumeRule::zfail ? Rule::zfail : Rule::zpass;
    ranges = {{rule, 0, 1}};
    const bool robust = v.build.generator != Generator::standard;
    MeshBuffers* m = frame_meshes_[o];
    if (!m->adjacency_vao) m->build_adjacency();
    // The geometry shader takes the faces with their neighbours as primitives; the vertex
    // shader reads the same from storage, a fixed number of vertices per face.
    if (gs_) {
      glBindVertexArray(m->adjacency_vao.get());
    } else {
      glBindVertexArray(empty_vao_.get());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m->adjacency_positions.get());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, m->adjacency_indices.get());
    }
    const int caps = rule == Rule::zfail       ? glsl::kCapsAll
                     : v.light_caps_everywhere ? glsl::kCapsLight
                                               : glsl::kCapsNone;
    const glm::vec4 eye =  // glsl face_of_side decides a face's side against it
        object_space_point(in_->scene.objects[o], glm::vec4(in_->scene.camera.position, 1.0f));
    programs.each([&](GLuint p) {
      glProgramUniform4fv(p, glsl::kLight, 1, glm::value_ptr(v.object_light));
      glProgramUniform4fv(p, glsl::kEye, 1, glm::value_ptr(eye));
      glProgramUniform4fv(p, glsl::kFarPlane, 1, glm::value_ptr(v.build.far_plane));
      glProgramUniform1i(p, glsl::kRobust, robust);
      glProgramUniform1i(p, glsl::kCaps, caps);
    });
    auto emit = [this, &programs, m, gs = gs_](int mode) {
      programs.each([&](GLuint p) { glProgramUniform1i(p, glsl::kEmit, mode); });
      count_draw([m, gs] {
        if (gs)
          glDrawElements(GL_TRIANGLES_ADJACENCY, m->adjacency_index_count, GL_UNSIGNED_INT,
                         nullptr);
        else
          glDrawArrays(GL_TRIANGLES, 0, m->adjacency_index_count / 6 * glsl::kVertexVolumeCorners);
      });
    };
    draw = [&programs, additive, robust, emit, mirror](const Range& range) {
      if (additive) {
        count_state(programs, true, range.rule, mirror);
        emit(glsl::kEmitWeighted);
        return;
      }
      count_state(programs, false, range.rule, mirror);
      emit(glsl::kEmitPositive);
      if (robust && range.rule == Rule::zfail) {
        count_state(programs, false, range.rule, -mirror);
        emit(glsl::kEmitNegative);
      }
    };
    draw_all = [emit](const Range&) { emit(glsl::kEmitWeighted); };
  }
  // Once per strip of discrete clamping (the fragment test's bounds), or once.
  const std::size_t runs = std::max<std::size_t>(v.strips.size(), 1);
  for (std::size_t r = 0; r < runs; ++r) {
    if (clamps_discrete(in_->options.clamp)) {
      const raster::ScreenStrip strip = v.strips.empty() ? raster::ScreenStrip{} : v.strips[r];
      constexpr float kUnbounded = 1e30f;
      programs.each([&](GLuint p) {
        glProgramUniform2fv(p, glsl::kStripAcross, 1, glm::value_ptr(strip.across));
        glProgramUniform2f(p, glsl::kStripBounds, std::max(strip.lo, -kUnbounded),
                           std::min(strip.hi, kUnbounded));
      });
    }
    for (const Range& range : ranges) {
      if (range.count == 0) continue;
      near_clip(range.rule);
      draw(range);
      if (in_->options.count_fill)
        measure_fill(range.rule == Rule::zpass, [&] { draw_all(range); });
    }
  }
}

void GlBackend::set_viewport_uniform() {
  const auto width = static_cast<float>(in_->options.width);
  const auto height = static_cast<float>(in_->options.height);
  counting_->each([&](GLuint p) { glProgramUniform2f(p, glsl::kViewport, width, height); });
}

void GlBackend::set_per_count(const glm::vec3& log_transmittance) {
  counting_->each([&](GLuint p) {
    glProgramUniform3fv(p, glsl::kPerCount, 1, glm::value_ptr(log_transmittance));
  });
}

void GlBackend::use_counting(const CountPrograms& programs) {
  counting_ = &programs;
  glUseProgram(programs.rest.get());
}

void GlBackend::count_draw(const std::function<void()>& draw) {
  draw();
  glUseProgram(counting_->slivers.get());
  draw();
  glUseProgram(counting_->rest.get());
}

// The pixels a volume's draw touches with the depth test off (CC shadow volumes §4's fill), and
// those that pass the rule's depth test (its stencil writes): occlusion queries over the same
// draw with every write off.
void GlBackend::measure_fill(bool zpass, const std::function<void()>& draw_all) {
  const auto start = std::chrono::steady_clock::now();
  GLboolean colour[4];
  glGetBooleanv(GL_COLOR_WRITEMASK, colour);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glStencilMask(0);
  auto samples = [&](GLenum depth_func) {
    glDepthFunc(depth_func);
    glBeginQuery(GL_SAMPLES_PASSED, fill_query_.get());
    draw_all();
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint64 n = 0;
    glGetQueryObjectui64v(fill_query_.get(), GL_QUERY_RESULT, &n);
    return static_cast<std::uint64_t>(n);
  };
  const std::uint64_t touched = samples(GL_ALWAYS), nearer = samples(GL_GREATER);
  FrameStats& stats = in_->frame.stats;
  stats.fill += touched;
  stats.stencil_writes += zpass ? nearer : touched - nearer;
  glColorMask(colour[0], colour[1], colour[2], colour[3]);
  glStencilMask(0xFF);
  // Not the frame's work: its time comes off the count passes' (its queries wait on the GPU).
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  stats.ms_counts -= ms;
  stats.ms_measuring += ms;
}

VolumeCosts GlBackend::measure_volume_costs() {
  const TypicalVolumes& volumes = typical_volumes();
  std::vector<VolumeVertex> vertices;
  vertices.reserve(volumes.vertices());
  for (std::size_t i = 0; i < volumes.vertices(); ++i)
    vertices.push_back({volumes.triangles[i], volumes.weights[i / 3]});
  const Object buffer = make_buffer(), vao = make_vertex_array();
  glNamedBufferStorage(buffer.get(),
                       static_cast<GLsizeiptr>(vertices.size() * sizeof(VolumeVertex)),
                       vertices.data(), 0);
  bind_volume_vertices(vao.get(), buffer.get());
  glUseProgram(volume_cpu_[0].rest.get());  // the typical volumes have no sides: no slivers
  const glm::mat4 identity(1.0f);           // the triangles are in clip space already
  glUniformMatrix4fv(glsl::kMvp, 1, GL_FALSE, glm::value_ptr(identity));
  glBindVertexArray(vao.get());
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  // Additive counts over an empty depth buffer: every fragment passes z-pass.
  auto best_of_runs = [&](int side, std::uint64_t& fill) {
    const Object counts = make_texture(GL_TEXTURE_2D), depth = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(counts.get(), 1, GL_R32F, side, side);
    glTextureStorage2D(depth.get(), 1, GL_DEPTH32F_STENCIL8, side, side);
    const Object fbo = make_framebuffer();
    glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, counts.get(), 0);
    glNamedFramebufferTexture(fbo.get(), GL_DEPTH_STENCIL_ATTACHMENT, depth.get(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
    glViewport(0, 0, side, side);
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfi(fbo.get(), GL_DEPTH_STENCIL, 0, 0.0f, 0);
    count_state(volume_cpu_[0], true, Rule::zpass, 1);
    double best = INFINITY;
    for (int run = 0; run < 5; ++run) {
      glClearNamedFramebufferfv(fbo.get(), GL_COLOR, 0, zero);
      glFinish();
      const auto start = std::chrono::steady_clock::now();
      glBeginQuery(GL_SAMPLES_PASSED, fill_query_.get());
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size()));
      glEndQuery(GL_SAMPLES_PASSED);
      glFinish();
      best = std::min(
          best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count());
      GLuint64 n = 0;
      glGetQueryObjectui64v(fill_query_.get(), GL_QUERY_RESULT, &n);
      fill = n;
    }
    return best;
  };
  std::uint64_t small_fill = 0, large_fill = 0;
  const double small = best_of_runs(kSmallSide, small_fill);
  const double large = best_of_runs(kLargeSide, large_fill);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDisable(GL_BLEND);
  return volume_costs(small, large, volumes.vertices(), large_fill);
}

// A light's passes keep to its scissor (FramePlan::reach), after their targets are cleared.
void GlBackend::scissor(std::size_t l) {
  const raster::PixelRect& r = in_->plan.reach[l].scissor;
  glEnable(GL_SCISSOR_TEST);
  glScissor(r.x0, in_->options.height - r.y1, r.x1 - r.x0, r.y1 - r.y0);  // rows from the bottom
}

void GlBackend::begin_mask(std::size_t l) {
  Targets& t = *targets_;
  into_light_map_ = false;
  mask_additive_ = settings_.counts == CountTarget::additive ||
                   (settings_.counts == CountTarget::automatic && !unit_weights_);
  if (mask_additive_) {
    const float zero[4] = {0, 0, 0, 0};
    glBindFramebuffer(GL_FRAMEBUFFER, t.count.get());
    glClearNamedFramebufferfv(t.count.get(), GL_COLOR, 0, zero);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  } else {
    glBindFramebuffer(GL_FRAMEBUFFER, t.scene.get());
    glNamedFramebufferDrawBuffers(t.scene.get(), 2, kNone);  // the ids are read (kCountPrelude)
    const GLint no_count = 0;
    glClearNamedFramebufferiv(t.scene.get(), GL_STENCIL, 0, &no_count);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  }
  scissor(l);
  glBindTextureUnit(2, t.ids.get());  // read, not written: stencil or another target
  const int strips = clamps_discrete(in_->options.clamp);
  use_counting(cpu_ ? volume_cpu_[strips] : gs_ ? volume_gpu_[strips] : volume_vs_[strips]);
  set_viewport_uniform();
}

// Kim et al. Eq. 3: each count adds its caster's log transmittance, in float32 with additive
// blending.
void GlBackend::begin_light_map(std::size_t l) {
  Targets& t = *targets_;
  into_light_map_ = true;
  const float zero[4] = {0, 0, 0, 0};
  glBindFramebuffer(GL_FRAMEBUFFER, t.light.get());
  glClearNamedFramebufferfv(t.light.get(), GL_COLOR, 0, zero);
  scissor(l);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBindTextureUnit(2, t.ids.get());
  const int strips = clamps_discrete(in_->options.clamp);
  use_counting(cpu_  ? light_map_cpu_[strips]
               : gs_ ? light_map_gpu_[strips]
                     : light_map_vs_[strips]);
  set_viewport_uniform();
}

struct GlBackend::Batch {
  struct ObjectData {
    glm::mat4 mvp;
    glm::ivec4 mirror;
  };
  struct Command {  // DrawArraysIndirectCommand
    GLuint count, instances, first, base_instance;
  };
  Object vertices = make_buffer(), objects = make_buffer(), commands = make_buffer();
  Object instance_ids = make_buffer(), vao = make_vertex_array();
  GLsizeiptr vertex_bytes = 0, object_bytes = 0, command_bytes = 0;
  GLuint instance_count = 0;
  std::vector<ObjectData> object_data;
  std::vector<GLint> base;                     // per batch slot: its first vertex in `vertices`
  std::vector<Command> draws[2][2], whole[2];  // [zfail][negative sign]; [zfail]
};

void GlBackend::count_volumes(std::size_t l, std::span<const std::uint32_t> objects) {
  if (!batching_ || !cpu_ || clamps_discrete(in_->options.clamp) || objects.size() < 2)
    return FrameBackend::count_volumes(l, objects);
  const FramePlan& plan = in_->plan;
  Batch& b = *batch_;
  const bool additive = mask_additive_ || into_light_map_;
  b.object_data.clear();
  b.base.clear();
  for (auto& by_sign : b.draws)
    for (auto& draws : by_sign) draws.clear();
  for (auto& draws : b.whole) draws.clear();
  // The volumes into one buffer, each object a slot: its draws, by rule and (stencil) by sign.
  GLsizeiptr bytes = 0;
  for (const std::uint32_t o : objects)
    bytes += uploads_[l][o]->vertices * GLsizeiptr(sizeof(VolumeVertex));
  fill_buffer(b.vertices, b.vertex_bytes, nullptr, bytes);
  GLint next = 0;
  for (const std::uint32_t o : objects) {
    const VolumeUpload& up = *uploads_[l][o];
    const auto slot = static_cast<GLuint>(b.object_data.size());
    const int mirror = plan.objects[o].weight_sign;
    b.object_data.push_back({plan.view_proj * plan.objects[o].model, glm::ivec4(mirror)});
    if (up.vertices > 0)
      glCopyNamedBufferSubData(up.buffer.get(), b.vertices.get(), 0,
                               next * GLintptr(sizeof(VolumeVertex)),
                               up.vertices * GLsizeiptr(sizeof(VolumeVertex)));
    // Its z-pass and its z-fail primitives (a volume of one rule has one kind; under rules per
    // part, both).
    if (up.zfail_first > 0) b.whole[0].push_back({GLuint(up.zfail_first), 1, GLuint(next), slot});
    if (up.vertices > up.zfail_first)
      b.whole[1].push_back(
          {GLuint(up.vertices - up.zfail_first), 1, GLuint(next + up.zfail_first), slot});
    for (const VolumeUpload::Group& g : up.groups)  // the stencil: |weight| draws of each
      for (int k = 0; k < std::abs(g.weight); ++k)
        b.draws[g.zfail][(g.weight > 0 ? mirror : -mirror) < 0].push_back(
            {GLuint(g.count), 1, GLuint(next + g.first), slot});
    next += up.vertices;
  }
  fill_buffer(b.objects, b.object_bytes, b.object_data.data(),
              GLsizeiptr(b.object_data.size() * sizeof(Batch::ObjectData)));
  if (b.instance_count < b.object_data.size()) {
    std::vector<GLuint> ids(std::max<std::size_t>(b.object_data.size(), 2 * b.instance_count));
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = GLuint(i);
    b.instance_ids = make_buffer();
    glNamedBufferStorage(b.instance_ids.get(), GLsizeiptr(ids.size() * sizeof(GLuint)), ids.data(),
                         0);
    b.instance_count = GLuint(ids.size());
  }
  bind_volume_vertices(b.vao.get(), b.vertices.get());
  glVertexArrayVertexBuffer(b.vao.get(), 1, b.instance_ids.get(), 0, sizeof(GLuint));
  glVertexArrayAttribIFormat(b.vao.get(), 2, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayBindingDivisor(b.vao.get(), 1, 1);
  glVertexArrayAttribBinding(b.vao.get(), 2, 1);
  glEnableVertexArrayAttrib(b.vao.get(), 2);
  const CountPrograms* pass = counting_;
  use_counting(into_light_map_ ? light_map_batch_ : volume_batch_);
  set_viewport_uniform();
  if (into_light_map_) {  // every object of one call is of one group
    const auto group = static_cast<std::size_t>(plan.objects[objects.front()].glass_group);
    set_per_count(plan.glass[group].log_transmittance);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, b.objects.get());
  glBindVertexArray(b.vao.get());
  auto multi_draw = [&](const std::vector<Batch::Command>& draws) {
    if (draws.empty()) return;
    fill_buffer(b.commands, b.command_bytes, draws.data(),
                GLsizeiptr(draws.size() * sizeof(Batch::Command)));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, b.commands.get());
    count_draw(
        [n = GLsizei(draws.size())] { glMultiDrawArraysIndirect(GL_TRIANGLES, nullptr, n, 0); });
  };
  for (int zfail = 0; zfail < 2; ++zfail) {
    if (b.whole[zfail].empty()) continue;
    const Rule rule = zfail ? Rule::zfail : Rule::zpass;
    near_clip(rule);
    if (additive) {
      count_state(*counting_, true, rule, 1);  // the mirror is each object's, in the vertex shader
      multi_draw(b.whole[zfail]);
    } else {
      for (int negative = 0; negative < 2; ++negative) {
        count_state(*counting_, false, rule, negative ? -1 : 1);
        multi_draw(b.draws[zfail][negative]);
      }
    }
    if (in_->options.count_fill) measure_fill(!zfail, [&] { multi_draw(b.whole[zfail]); });
  }
  use_counting(*pass);
}

void GlBackend::count_volume(std::size_t l, std::size_t o) {
  if (!into_light_map_) return draw_volume(l, o, mask_additive_);
  const FramePlan& plan = in_->plan;
  const auto group = static_cast<std::size_t>(plan.objects[o].glass_group);
  set_per_count(plan.glass[group].log_transmittance);
  draw_volume(l, o, true);
}

void GlBackend::end_counts() {
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_CLIP_DISTANCE0);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);  // the stencil holds the mask until the lit pass reads it
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void GlBackend::read_mask(std::size_t l, SurfaceLayer& layer) {
  Targets& t = *targets_;
  const int w = in_->options.width, h = in_->options.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  std::vector<std::uint8_t>& mask = layer.shadowed[l];
  if (mask_additive_) {
    std::vector<float>& counts = read_counts_;
    counts.resize(pixels);
    glNamedFramebufferReadBuffer(t.count.get(), GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t.count.get());
    glReadnPixels(0, 0, w, h, GL_RED, GL_FLOAT, static_cast<GLsizei>(pixels * sizeof(float)),
                  counts.data());
    flip_rows(counts, w, h, mask, [](float c) -> std::uint8_t { return c != 0.0f; });
  } else {
    std::vector<std::uint8_t>& stencil = read_stencil_;
    stencil.resize(pixels);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t.scene.get());
    glReadnPixels(0, 0, w, h, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels),
                  stencil.data());
    flip_rows(stencil, w, h, mask, [](std::uint8_t c) -> std::uint8_t { return c != 0; });
  }
  const FramePlan& plan = in_->plan;
  if (!plan.reach[l].limited) return;
  if (!depth_read_) {  // the layer's depths, once for all its lights
    std::vector<float>& depth = read_depth_;
    depth.resize(pixels);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t.scene.get());
    glReadnPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT,
                  static_cast<GLsizei>(pixels * sizeof(float)), depth.data());
    flip_rows(depth, w, h, layer_depth_, [](float z) { return z; });
    depth_read_ = true;
  }
  mark_beyond_reach(mask, layer_depth_, plan.inv_view_proj, plan.lights[l],
                    in_->scene.lights[l].range, plan.reach[l], w, h);
}

void GlBackend::read_light_map(std::size_t l, SurfaceLayer& layer) {
  Targets& t = *targets_;
  const int w = in_->options.width, h = in_->options.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  std::vector<glm::vec4>& log_light = read_light_;
  log_light.resize(pixels);
  glNamedFramebufferReadBuffer(t.light.get(), GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.light.get());
  glReadnPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pixels * sizeof(glm::vec4)),
                log_light.data());
  flip_rows(log_light, w, h, layer.transmitted[l],
            [](const glm::vec4& c) { return glm::exp(glm::vec3(c)); });
  for (std::size_t p = 0; p < pixels; ++p)
    if (layer.shadowed[l][p]) layer.transmitted[l][p] = glm::vec3(0.0f);
}

void GlBackend::read_facing(std::size_t l, Layer layer, SurfaceLayer& out) {
  Targets& t = *targets_;
  const int w = in_->options.width, h = in_->options.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(t.facing.get(), GL_COLOR, 1, zero);
  glBindFramebuffer(GL_FRAMEBUFFER, t.facing.get());
  glBindTextureUnit(2, t.ids.get());
  glUseProgram(surface_lit_[gs_ ? 1 : 0].get());
  glUniform1i(glsl::kFacingOnly, GL_TRUE);
  glUniform4fv(glsl::kLight, 1, glm::value_ptr(in_->plan.lights[l]));
  const SceneLight& light = in_->scene.lights[l];
  const shading::Falloff falloff = shading::falloff_of(light.range, light.limited());
  glUniform2f(glsl::kFalloff, falloff.inv_range2, falloff.inverse_square);
  scissor(l);  // as the lit pass: no surface beyond it is within the range
  draw_surfaces(drawn_[static_cast<int>(layer)], [&](std::size_t o) { bind_surface(o); });
  glDisable(GL_SCISSOR_TEST);
  glUniform1i(glsl::kFacingOnly, GL_FALSE);
  std::vector<std::uint8_t>& faces = read_stencil_;
  faces.resize(pixels);
  glNamedFramebufferReadBuffer(t.facing.get(), GL_COLOR_ATTACHMENT1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.facing.get());
  glReadnPixels(0, 0, w, h, GL_RED, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels), faces.data());
  flip_rows(faces, w, h, out.faces_light[l], [](std::uint8_t c) -> std::uint8_t { return c != 0; });
}

// The layer's surfaces again, at equal depth, added where the count is 0.
void GlBackend::light_pass(std::size_t l, Layer layer) {
  const Scene& scene = in_->scene;
  const FramePlan& plan = in_->plan;
  Targets& t = *targets_;
  const bool glass_layer = layer == Layer::glass;
  glNamedFramebufferDrawBuffers(t.scene.get(), 2, kColourOnly);
  glBindFramebuffer(GL_FRAMEBUFFER, t.scene.get());
  if (mask_additive_) {
    glDisable(GL_STENCIL_TEST);
    glBindTextureUnit(0, t.counts.get());
  } else {
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  }
  glBindTextureUnit(1, t.log_light.get());
  glBindTextureUnit(2, t.ids.get());  // read, not written: attachment 0 is off
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glDepthFunc(GL_EQUAL);
  glUseProgram(surface_lit_[gs_ ? 1 : 0].get());
  const SceneLight& light = scene.lights[l];
  const glm::vec3 radiance = light.color * light.intensity;
  glUniform4fv(glsl::kLight, 1, glm::value_ptr(plan.lights[l]));
  glUniform1i(glsl::kCountTexture, mask_additive_);
  glUniform1i(glsl::kLightMap, plan.has_glass());
  glUniform1f(glsl::kSpecular, shading::kSpecular);
  glUniform1f(glsl::kShininess, shading::kShininess);
  const shading::Falloff falloff = shading::falloff_of(light.range, light.limited());
  glUniform2f(glsl::kFalloff, falloff.inv_range2, falloff.inverse_square);
  scissor(l);
  auto lit = [&](std::size_t o) {
    // A transparent surface reflects its opacity's share; the rest passes (the filter pass).
    const glm::vec3 reflected = radiance * (glass_layer ? scene.objects[o].material.opacity : 1.0f);
    glUniform3fv(glsl::kRadiance, 1, glm::value_ptr(reflected));
    bind_surface(o);
  };
  // The objects that receive shadows by the counts; then those that do not, lit whatever the
  // counts say (SceneObject::receives_shadows).
  const std::vector<std::uint32_t>& drawn = drawn_[static_cast<int>(layer)];
  receivers_.clear();
  non_receivers_.clear();
  for (const std::uint32_t o : drawn)
    (plan.objects[o].receives ? receivers_ : non_receivers_).push_back(o);
  draw_surfaces(receivers_, lit);
  if (!non_receivers_.empty()) {
    glDisable(GL_STENCIL_TEST);
    glUniform1i(glsl::kCountTexture, 0);
    glUniform1i(glsl::kLightMap, 0);
    draw_surfaces(non_receivers_, lit);
  }
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glDepthFunc(GL_GREATER);
}

void GlBackend::bind_surface(std::size_t o) {
  const FramePlan& plan = in_->plan;
  const Material& material = in_->scene.objects[o].material;
  const glm::mat4& model = plan.objects[o].model;
  const glm::mat3 normal_matrix(glm::transpose(glm::inverse(glm::dmat3(model))));
  glUniformMatrix4fv(glsl::kModel, 1, GL_FALSE, glm::value_ptr(model));
  glUniformMatrix3fv(glsl::kNormalMatrix, 1, GL_FALSE, glm::value_ptr(normal_matrix));
  glUniform3fv(glsl::kAlbedo, 1, glm::value_ptr(material.color));
  glUniform1ui(glsl::kFirstId, plan.objects[o].first_id);
  const MeshBuffers& m = *frame_meshes_[o];
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, glsl::kFaceNormalsBinding, m.normals.get());
  const bool smooth = frame_normals_[o] != 0, textured = frame_uvs_[o] != 0;
  glUniform1i(glsl::kSmoothNormals, smooth);
  glUniform1i(glsl::kTextured, textured);
  if (smooth || textured) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, glsl::kPositionsBinding, m.positions.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, glsl::kIndicesBinding, m.indices.get());
  }
  if (smooth)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, glsl::kCornerNormalsBinding, frame_normals_[o]);
  if (textured) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, glsl::kUvsBinding, frame_uvs_[o]);
    glBindTextureUnit(glsl::kBaseColorUnit,
                      textures_.at(material.base_color_map.get()).texture.get());
  }
}

// The ambient term of the textured surfaces of a layer (opacity times it on the glass layer),
// where each is the surface left visible: the lit program, without lights or masks.
void GlBackend::ambient_textured(Layer layer) {
  const Scene& scene = in_->scene;
  surfaces_.clear();
  for (const std::uint32_t o : drawn_[static_cast<int>(layer)])
    if (frame_uvs_[o] != 0) surfaces_.push_back(o);
  if (surfaces_.empty()) return;
  Targets& t = *targets_;
  glNamedFramebufferDrawBuffers(t.scene.get(), 2, kColourOnly);
  glBindTextureUnit(2, t.ids.get());  // read, not written: attachment 0 is off
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glDepthFunc(GL_EQUAL);
  glUseProgram(surface_lit_[gs_ ? 1 : 0].get());
  glUniform1i(glsl::kAmbientOnly, GL_TRUE);
  draw_surfaces(surfaces_, [&](std::size_t o) {
    const float share = layer == Layer::glass ? scene.objects[o].material.opacity : 1.0f;
    const glm::vec3 radiance = share * scene.ambient;
    glUniform3fv(glsl::kRadiance, 1, glm::value_ptr(radiance));
    bind_surface(o);
  });
  glUniform1i(glsl::kAmbientOnly, GL_FALSE);
  glDisable(GL_BLEND);
  glDepthFunc(GL_GREATER);
}

// What lies behind the transparent surfaces, seen through every one of them.
void GlBackend::see_through() {
  const FramePlan& plan = in_->plan;
  Targets& t = *targets_;
  glBindFramebuffer(GL_FRAMEBUFFER, t.light.get());
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(t.light.get(), GL_COLOR, 0, zero);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glDepthFunc(GL_GREATER);
  glUseProgram(cover_.get());
  draw_surfaces(transparent_, [&](std::size_t o) {
    const auto group = static_cast<std::size_t>(plan.objects[o].glass_group);
    glUniform3fv(glsl::kPerCount, 1, glm::value_ptr(plan.glass[group].log_transmittance));
  });
  glBindFramebuffer(GL_FRAMEBUFFER, t.scene.get());
  glNamedFramebufferDrawBuffers(t.scene.get(), 2, kColourOnly);
  glDisable(GL_DEPTH_TEST);
  glBlendFunc(GL_ZERO, GL_SRC_COLOR);  // colour *= exp(log transmittance in front)
  glUseProgram(see_through_.get());
  glBindTextureUnit(1, t.log_light.get());
  glBindVertexArray(empty_vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
}

// The colour to sRGB; then the state as the frame found it.
void GlBackend::shade() {
  glBindFramebuffer(GL_FRAMEBUFFER, targets_->resolved.get());
  glDisable(GL_DEPTH_TEST);
  glUseProgram(resolve_.get());
  glBindTextureUnit(0, targets_->color.get());
  glBindVertexArray(empty_vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glEnable(GL_DEPTH_TEST);
  glBindVertexArray(0);
  glUseProgram(0);
  assert(take_error().empty());
}

void GlBackend::read_image(Image& image) {
  const int w = in_->options.width, h = in_->options.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  std::vector<std::uint32_t>& rgba = read_ids_;  // the ids are read already
  rgba.resize(pixels);
  glNamedFramebufferReadBuffer(targets_->resolved.get(), GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, targets_->resolved.get());
  glReadnPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE,
                static_cast<GLsizei>(pixels * sizeof(std::uint32_t)), rgba.data());
  std::vector<std::uint32_t>& rows = read_rows_;
  flip_rows(rgba, w, h, rows, [](std::uint32_t c) { return c; });
  image.width = w;
  image.height = h;
  image.rgba.resize(pixels * 4);
  std::memcpy(image.rgba.data(), rows.data(), pixels * 4);
}

void GlBackend::present() {
  const int w = targets_->width, h = targets_->height;
  glBlitNamedFramebuffer(targets_->resolved.get(), 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT,
                         GL_NEAREST);
}

}  // namespace shadowvol::gl
