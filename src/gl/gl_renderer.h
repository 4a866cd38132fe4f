// shadowvol gl: GlRenderer, the OpenGL 4.5 backend behind the same interface as the software one.
//
// Owns: the GPU passes of a frame and the GPU copies of meshes and volumes. Per frame: a depth
// pass that writes face ids and the ambient term; per light, the volumes drawn into the
// stencil buffer (two-sided, wrapping increment and decrement: weights +-1) or into an R32F
// target with additive blending (any integer weight, exact below 2^24), then the scene again,
// added where the count is 0; finally the colour to sRGB. Decisions (matrices, z-pass or z-fail
// per object, CPU volumes and their cache, shading constants) come from render/frame_plan.h, so
// both backends draw the same volumes by the same method.
//
// Volumes come from the CPU (core's VolumeBuffer, uploaded when the cache rebuilds it) or from
// a geometry shader over GL_TRIANGLES_ADJACENCY (GPU Gems 3 §11.3.2), which builds the
// standard or robust volume of each face on the GPU every frame.
//
// Needs an OpenGL 4.5 core context current on the calling thread from create() until it is
// destroyed; Context::create_headless() makes one, the viewer's window another.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/expected.h"
#include "gl/context.h"
#include "gl/objects.h"
#include "render/frame_plan.h"
#include "render/renderer.h"

namespace shadowvol::gl {

enum class VolumePath : std::uint8_t {
  cpu,  // core's generators on the CPU (any generator), uploaded when rebuilt
  gpu,  // the geometry shader (standard or robust), every frame
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

class GlRenderer final : public Renderer {
 public:
  // Compiles the shaders on the current context. `context`, if given, is owned (and outlives
  // every GL object of the renderer).
  static Expected<std::unique_ptr<GlRenderer>> create(GlSettings settings,
                                                      std::optional<Context> context = {});
  ~GlRenderer() override;

  Frame render(const Scene& scene, const RenderOptions& options) override;
  std::string_view backend() const override { return "gl"; }

  // Draws the frame and copies it to the context's default framebuffer (the window), with
  // no read-back: Frame::image and the masks stay empty; stats are filled.
  FrameStats present(const Scene& scene, const RenderOptions& options);

  const GlSettings& settings() const { return settings_; }
  void set_settings(const GlSettings& settings) { settings_ = settings; }
  const Info& info() const { return info_; }

 private:
  struct MeshBuffers;
  struct VolumeUpload;
  struct Targets;
  struct Pass;
  GlRenderer() = default;
  Frame draw(const Scene& scene, const RenderOptions& options, bool read_back);
  // Draws the scene's opaque objects, or its transparent ones when `glass`, with the bound
  // program: sets each one's mvp, lets per_object(o) set the rest of its uniforms.
  template <class PerObject>
  void draw_surfaces(const Pass& pass, bool glass, PerObject&& per_object);
  // The ids of the depth pass into the layer's object and face (those of its kind only).
  void read_ids(const Pass& pass, bool glass, SurfaceLayer& layer);
  // Per light: the opaque casters' counts (the mask), the transparent casters' log light map,
  // and the lit pass of the layer's surfaces, against the depth buffer as it stands.
  void light_layer(const Pass& pass, std::size_t light, bool glass_layer, SurfaceLayer& layer);
  MeshBuffers& mesh_buffers(const SceneObject& object);

  std::optional<Context> context_;  // first member: destroyed last
  GlSettings settings_;
  Info info_;
  // [0]: the scene through a vertex shader alone; [1]: through a pass-through geometry shader,
  // to match the depths of geometry-shader volumes (shaders.h).
  Object surface_depth_[2], surface_lit_[2];
  Object volume_cpu_, volume_gpu_, light_map_cpu_, light_map_gpu_, cover_, see_through_,
      background_, resolve_;
  Object empty_vao_;
  std::unique_ptr<Targets> targets_;
  std::unordered_map<const Topology*, std::unique_ptr<MeshBuffers>> meshes_;
  std::vector<std::vector<std::unique_ptr<VolumeUpload>>> uploads_;  // [light][object]
  VolumeCache volumes_;
};

}  // namespace shadowvol::gl
