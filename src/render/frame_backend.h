// shadowvol render: FrameBackend, the verbs a backend implements for the frame pipeline.
//
// The pipeline (render/renderer.h) decides what a frame draws and in which order; a backend
// only knows how to draw each step, on the CPU (soft/) or through OpenGL (gl/). Each verb is one
// kind of pass over the frame's targets, so that later passes (a depth pass from a light, an
// occlusion query of a box against a depth target, answered later) are verbs of the same form:
// they name what to draw and into which target, never the sequence around them.
//
// A frame calls begin_frame, then the verbs, all on one thread; between begin_frame and the end
// of the frame the FrameInputs it was given stay alive and unchanged (but for the Frame, which
// the verbs fill).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

#include "core/expected.h"
#include "render/frame.h"
#include "render/frame_plan.h"
#include "render/volume_cache.h"
#include "scene/scene.h"

namespace shadowvol {

// Which surfaces a pass takes: the opaque ones (the frame's first layer), or the transparent
// ones (the glass layer: the nearest transparent surface in front of the opaque one).
enum class Layer : std::uint8_t { opaque, glass };

// What the verbs of one frame read, and the Frame they fill.
struct FrameInputs {
  const Scene& scene;
  const RenderOptions& options;
  const FramePlan& plan;
  // The CPU-built volumes, current for each light from volumes_ready on (where the backend
  // counts CPU volumes, or options.show_volumes asks for them).
  const VolumeCache& volumes;
  Frame& frame;
};

class FrameBackend {
 public:
  virtual ~FrameBackend() = default;
  // "soft" or "gl".
  virtual std::string_view name() const = 0;
  // What this backend cannot draw under these options, as an error a person can act on.
  virtual Expected<void> supports(const RenderOptions& options) const = 0;
  // Whether it counts the volumes of the VolumeCache (else it builds them as it counts).
  virtual bool counts_cpu_volumes() const = 0;
  // Whether it counts its work into FrameStats's depth, counts and split_sampling (the
  // rasterizer's counters, the papers' fill measures).
  virtual bool counts_work() const { return false; }
  // Whether a frame can stay on the device and be shown there (present).
  virtual bool can_present() const { return false; }
  // Waits for the work given so far to end, so that a time taken after it is the work's own.
  virtual void finish() {}
  // CC shadow volumes §3.2.1's v and r on this backend: a typical set of volumes drawn small (10 x
  // 10 pixels: v, per vertex) and large (r, per pixel covered, v's share taken off), best of a few
  // runs. Outside any frame; leaves no state a frame sees.
  virtual VolumeCosts measure_volume_costs() = 0;

  // Sizes the targets for the frame and takes its inputs.
  virtual void begin_frame(const FrameInputs& inputs) = 0;
  // Depth pass from the eye: the layer's surfaces into the depth target, each pixel's face id
  // with them (the glass layer over the opaque layer's depths, without clearing them), drawn in
  // batches: begin_depth, then draw_depth of some objects of the layer, each batch in one draw
  // (any objects, any order, each at most once), then end_depth, after which the target is
  // complete. Occlusion queries may come between the batches.
  virtual void begin_depth(Layer layer) = 0;
  virtual void draw_depth(std::span<const std::uint32_t> objects) = 0;
  virtual void end_depth() = 0;

  // Occlusion queries (GL_ANY_SAMPLES_PASSED): whether any pixel of `triangles` (eye-relative,
  // homogeneous, 3 vertices each, both facings) lies at or in front of the depth target as it
  // stands, without writing anything; where `surfaces_only`, only at pixels that show a surface.
  // Answered now or later (query_ready); query_visible waits for the answer. Queries live until
  // the next begin_frame.
  using QueryId = std::uint32_t;
  virtual QueryId issue_query(std::span<const glm::vec4> triangles, bool surfaces_only) = 0;
  virtual bool query_ready(QueryId query) = 0;
  virtual bool query_visible(QueryId query) = 0;
  // The layer's object and face per pixel, from the depth pass's ids.
  virtual void read_ids(Layer layer, SurfaceLayer& out) = 0;
  // The CPU volumes of `light` are current; rebuilt[o] is 1 where object o's changed.
  virtual void volumes_ready(std::size_t light, const std::vector<std::uint8_t>& rebuilt) = 0;

  // A light's count target: cleared for the opaque casters' signed counts (its shadow mask).
  virtual void begin_mask(std::size_t light) = 0;
  // A light's light intensity map (Kim et al. 2008 §2): cleared, for the groups of transparent
  // casters, each counted and then added by its log transmittance (end_group).
  virtual void begin_light_map(std::size_t light) = 0;
  // Counts the volume of `object` for `light` into the current target by its VolumePlan.
  virtual void count_volume(std::size_t light, std::size_t object) = 0;
  // Counts the volumes of `objects` (none culled) for `light`, each by its own VolumePlan (rule,
  // caps, depth bounds), in as few draws as the backend can: the counts of count_volume of each.
  virtual void count_volumes(std::size_t light, std::span<const std::uint32_t> objects) {
    for (const std::uint32_t o : objects) count_volume(light, o);
  }
  // Into the light map: the counts of group g's volumes times its log transmittance.
  virtual void end_group(std::size_t group) = 0;
  // The current count target (mask or light map) has all its counts.
  virtual void end_counts() {}
  // The mask (count != 0) of the layer for this light, into layer.shadowed[light].
  virtual void read_mask(std::size_t light, SurfaceLayer& layer) = 0;
  // The light that arrives through the transparent casters, into layer.transmitted[light]
  // (0 where the mask shadows).
  virtual void read_light_map(std::size_t light, SurfaceLayer& layer) = 0;
  // The light's contribution to the layer's surfaces where its mask is clear, times what the
  // light map lets through.
  virtual void light_pass(std::size_t light, Layer layer) = 0;
  // RenderOptions::record_facing: which of the layer's surfaces the lit pass takes as facing the
  // light (SurfaceLayer::faces_light), into layer.faces_light[light], zeroed before, by the end of
  // the frame.
  virtual void read_facing(std::size_t light, Layer layer, SurfaceLayer& out) = 0;

  // With transparent casters: the log transmittance of the transparent surfaces in front of the
  // opaque layer, each counted once, which filters what the eye sees behind them.
  virtual void see_through() = 0;
  // The frame's colour: background, ambient, each light's contribution, the glass, into sRGB.
  virtual void shade() = 0;
  // The sRGB image into frame.image.
  virtual void read_image(Image& image) = 0;
  // Shows the last frame drawn without read-back (Renderer::present; can_present).
  virtual void present() {}
};

}  // namespace shadowvol
