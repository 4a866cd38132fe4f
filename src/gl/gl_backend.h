// shadowvol gl: GlBackend, the frame pipeline's verbs in OpenGL 4.5.
//
// Owns: the GPU passes of a frame and the GPU copies of meshes and volumes. Per frame: a depth
// pass that writes face ids and the ambient term; per light, the volumes drawn into the
// stencil buffer (two-sided, wrapping increment and decrement: weights +-1) or into an R32F
// target with additive blending (any integer weight, exact below 2^24), then the scene again,
// added where the count is 0; finally the colour to sRGB. What to draw (matrices, z-pass or z-fail
// per object, CPU volumes and their cache) comes from the pipeline (render/renderer.h) and its
// plan, and the shading constants from render/shading.h, so both backends draw the same volumes
// by the same method.
//
// Volumes come from the CPU (core's VolumeBuffer, uploaded when the cache rebuilds it) or from
// a geometry shader over GL_TRIANGLES_ADJACENCY (GPU Gems 3 §11.3.2), which builds the
// standard or robust volume of each face on the GPU every frame.
//
// Needs an OpenGL 4.5 core context current on the calling thread from create() until it is
// destroyed; Context::create_headless() makes one, the viewer's window another.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/expected.h"
#include "gl/context.h"
#include "gl/objects.h"
#include "render/frame_backend.h"
#include "render/frame_plan.h"

namespace shadowvol::gl {

enum class VolumePath : std::uint8_t {
  cpu,  // core's generators on the CPU (any generator), uploaded when rebuilt
  gpu,  // the geometry shader (standard or robust), every frame
  // The vertex shader (standard or robust; Intel, "Rendering Shadow Volumes"): a volume mesh
  // per mesh, fixed, drawn whole every frame, its vertices extruded or collapsed by the shader
  // as the geometry shader would emit them.
  vertex,
};
std::string_view to_string(VolumePath path);
Expected<VolumePath> parse_volume_path(std::string_view name);

enum class CountTarget : std::uint8_t {
  automatic,  // stencil where every weight is +-1 (a light's volumes), additive otherwise
  stencil,    // 8-bit stencil, two-sided wrap ops; refuses weights other than +-1
  additive,   // R32F colour target, blending ONE + ONE
};
std::string_view to_string(CountTarget target);
Expected<CountTarget> parse_count_target(std::string_view name);

struct GlSettings {
  VolumePath volumes = VolumePath::cpu;
  CountTarget counts = CountTarget::automatic;
};

// Refuses what this backend cannot draw: geometry-shader volumes with the multiplicity
// generator (a shader emits weight +-1 per face: the robust form of the same count).
Expected<void> check_settings(const GlSettings& settings, Generator generator);
// Refuses, besides check_settings', what only the software rasterizer draws: the split-plane
// and pre-filled methods (soft_only) and tile work.
Expected<void> check_frame(const GlSettings& settings, const RenderOptions& options);

// A count pass's pair of programs: `rest` draws a volume's primitives but its slivers with the
// rasterizer's depth, `slivers` only those, keeping their depth (glsl::kCountPrelude). Every
// count draw runs with both, and each uniform is set on both.
struct CountPrograms {
  Object rest, slivers;
  template <class Set>
  void each(Set&& set) const {  // set(program), e.g. with glProgramUniform*
    set(rest.get());
    set(slivers.get());
  }
};

class GlBackend final : public FrameBackend {
 public:
  // Compiles the shaders on the current context. `context`, if given, is owned (and outlives
  // every GL object of the backend).
  static Expected<std::unique_ptr<GlBackend>> create(GlSettings settings,
                                                     std::optional<Context> context = {});
  ~GlBackend() override;

  std::string_view name() const override { return "gl"; }
  // check_frame, and an image no larger than the driver's textures and viewports.
  Expected<void> supports(const RenderOptions& options) const override;
  bool counts_cpu_volumes() const override { return settings_.volumes == VolumePath::cpu; }
  bool can_present() const override { return true; }
  void finish() override;
  VolumeCosts measure_volume_costs() override;

  void begin_frame(const FrameInputs& inputs) override;
  void begin_depth(Layer layer) override;
  void draw_depth(std::span<const std::uint32_t> objects) override;
  void end_depth() override;
  // GL_ANY_SAMPLES_PASSED_CONSERVATIVE queries, a pool of them reused frame to frame.
  QueryId issue_query(std::span<const glm::vec4> triangles, bool surfaces_only) override;
  bool query_ready(QueryId query) override;
  bool query_visible(QueryId query) override;
  void read_ids(Layer layer, SurfaceLayer& out) override;
  void volumes_ready(std::size_t light, const std::vector<std::uint8_t>& rebuilt) override;
  void begin_mask(std::size_t light) override;
  void begin_light_map(std::size_t light) override;
  void count_volume(std::size_t light, std::size_t object) override;
  // CPU volumes over the whole image (no strips): those of one rule in one multi-draw (per sign
  // of the weight, into the stencil), each object's transform from a storage buffer; else one by
  // one.
  void count_volumes(std::size_t light, std::span<const std::uint32_t> objects) override;
  void set_batching(bool on) { batching_ = on; }
  void end_group(std::size_t) override {}  // each count adds its group's log transmittance
  void end_counts() override;
  void read_mask(std::size_t light, SurfaceLayer& layer) override;
  void read_light_map(std::size_t light, SurfaceLayer& layer) override;
  void light_pass(std::size_t light, Layer layer) override;
  // The lit program again, into a target of its own, with only its test of the face's side.
  void read_facing(std::size_t light, Layer layer, SurfaceLayer& out) override;
  void see_through() override;
  void shade() override;
  void read_image(Image& image) override;
  // Copies the last frame to the context's default framebuffer (the window).
  void present() override;

  const GlSettings& settings() const { return settings_; }
  void set_settings(const GlSettings& settings) { settings_ = settings; }
  const Info& info() const { return info_; }

 private:
  struct MeshBuffers;
  struct VolumeUpload;
  struct Targets;
  GlBackend() = default;
  // Draws the layer's objects with the bound program: sets each one's mvp, lets per_object(o)
  // set the rest of its uniforms.
  template <class PerObject>
  void draw_surfaces(std::span<const std::uint32_t> objects, PerObject&& per_object);
  // Draws the volume of object o for the light into the bound target, additively or into the
  // stencil.
  void draw_volume(std::size_t light, std::size_t o, bool additive);
  // Adds the fill and the stencil writes of one draw of a volume (draw_all: every primitive
  // once) into the frame's stats (RenderOptions::count_fill).
  void measure_fill(bool zpass, const std::function<void()>& draw_all);
  void use_counting(const CountPrograms& programs);  // binds its `rest`
  // Runs draw with counting_'s `rest`, then with its `slivers`.
  void count_draw(const std::function<void()>& draw);
  // The light map's log transmittance per count, of the caster being counted.
  void set_per_count(const glm::vec3& log_transmittance);
  // The count programs' viewport uniform (strips, slivers: glsl::kCountPrelude).
  void set_viewport_uniform();
  void scissor(std::size_t light);  // enables the scissor test on the light's reach
  MeshBuffers& mesh_buffers(const SceneObject& object);

  std::optional<Context> context_;  // first member: destroyed last
  GlSettings settings_;
  int max_image_side_ = 0;  // the driver's: textures, framebuffers and viewports
  Info info_;
  // [0]: the scene through a vertex shader alone; [1]: through a pass-through geometry shader,
  // to match the depths of geometry-shader volumes (shaders.h).
  Object surface_depth_[2], surface_lit_[2];
  // The count passes' programs: [0] over the whole image, [1] with the strips' fragment test.
  CountPrograms volume_cpu_[2], volume_gpu_[2], light_map_cpu_[2], light_map_gpu_[2];
  CountPrograms volume_vs_[2], light_map_vs_[2];
  Object cover_, see_through_, background_, resolve_, query_;
  CountPrograms volume_batch_, light_map_batch_;  // count_volumes' (kVolumeBatchVertex)
  Object depth_batch_;                            // draw_depth's (kSurfaceBatchVertex)
  // The frame's meshes in one vertex and one index buffer, for draw_depth's multi-draws: per
  // mesh its base vertex and first index; remade when the meshes change.
  struct SceneGeometry;
  std::unique_ptr<SceneGeometry> geometry_;
  std::uint64_t mesh_serial_ = 0;
  void make_scene_geometry();
  // count_volumes' storage: the volumes copied into one buffer, per object its transform and
  // mirror, the draws, and the object index per instance (0, 1, 2, ...).
  struct Batch;
  std::unique_ptr<Batch> batch_;
  bool batching_ = true;
  Object empty_vao_;
  Object fill_query_ = make_query(GL_SAMPLES_PASSED);
  std::unique_ptr<Targets> targets_;
  std::unordered_map<const Topology*, std::unique_ptr<MeshBuffers>> meshes_;
  // Material::base_color_map as textures (sRGB, bilinear, repeating), kept while in use.
  struct GlTexture {
    std::shared_ptr<const Texture> source;
    Object texture;
    bool used = false;
  };
  std::unordered_map<const Texture*, GlTexture> textures_;
  // Per-corner attributes (SceneObject::shading, SceneObject::uvs) as storage buffers, by their
  // source, kept while in use; per object of the frame, its buffers (0: flat; no texture).
  struct CornerBuffer {
    std::shared_ptr<const void> source;
    Object buffer;
    bool used = false;
  };
  std::unordered_map<const void*, CornerBuffer> corner_buffers_;
  std::vector<GLuint> frame_normals_, frame_uvs_;
  CornerBuffer& corner_buffer(const std::shared_ptr<const void>& source);
  void object_attributes(const SceneObject& object);  // appends to frame_normals_, frame_uvs_
  // Per object: the lit program's uniforms and buffers of its surface (not the light's).
  void bind_surface(std::size_t object);
  // The ambient term of the layer's textured surfaces, which the depth pass left out.
  void ambient_textured(Layer layer);
  std::vector<std::vector<std::unique_ptr<VolumeUpload>>> uploads_;  // [light][object]

  std::vector<Object> queries_;  // the pool; the frame's are [0, queries_used_)
  std::size_t queries_used_ = 0;
  Object query_vao_ = make_vertex_array();

  // The frame being drawn.
  const FrameInputs* in_ = nullptr;
  std::vector<MeshBuffers*> frame_meshes_;  // per object
  bool cpu_ = true;  // volumes built on the CPU (else in the geometry or the vertex shader)
  bool gs_ = false;  // in the geometry shader, whose light caps the surfaces pass through too
  bool unit_weights_ = true;     // every opaque caster's CPU volume of the light has weights +-1
  bool mask_additive_ = false;   // the light's mask counts into the R32F target, not the stencil
  const CountPrograms* counting_ = nullptr;  // the count pass's programs (use_counting)
  bool into_light_map_ = false;  // count_volume adds into the light map
  Layer layer_ = Layer::opaque;  // of the depth pass begun
  // The depth pass's depths read back, rows from the top (for the lights' ranges), since it began.
  bool depth_read_ = false;
  std::vector<float> read_depth_, layer_depth_;
  // Per layer, the objects its depth pass drew (what its colour and lit passes draw); and every
  // transparent object (what is seen through).
  std::vector<std::uint32_t> drawn_[2], transparent_;
  std::vector<std::uint32_t> receivers_, non_receivers_;  // of a lit pass's layer
  std::vector<std::uint32_t> surfaces_;                   // of ambient_textured
  // Read-back scratch, kept between frames.
  std::vector<std::uint32_t> read_ids_, read_rows_;
  std::vector<float> read_counts_;
  std::vector<std::uint8_t> read_stencil_;
  std::vector<glm::vec4> read_light_;
};

}  // namespace shadowvol::gl
