// shadowvol soft: SoftBackend, the frame pipeline's verbs on the tile rasterizer (src/raster),
// threads from oneTBB. Deterministic: the same frame at any thread count.
//
// Owns: the frame's targets in memory (depth with face ids, signed counts, the tiles' depth
// bounds), the count passes of every VolumeRule (z-pass, z-fail, per tile by split planes with
// the sampler's choice of plane, the ZP+ pre-fill), and the shading. Its targets are memory, so
// a frame is always read back: read_mask, read_light_map and read_ids take what the passes left,
// and the light passes are folded into shade, which lights each pixel from its masks at once.
//
// Transparent casters (Kim, Kim & Turk 2008): each group of transparent casters of one material
// is counted on its own (exact integer surface counts, light caps included) and added into a
// float32 log light intensity map as count * log(transmittance); the light that arrives is exp
// of the map. The picture is the opaque layer seen through every transparent surface in front of
// it (counted per group the same way, along the eye's rays), plus the nearest one's reflection.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "raster/raster.h"
#include "render/frame_backend.h"
#include "render/renderer.h"
#include "soft/split_sampler.h"

namespace shadowvol::soft {

class SoftBackend final : public FrameBackend {
 public:
  std::string_view name() const override { return "soft"; }
  Expected<void> supports(const RenderOptions&) const override { return {}; }
  bool counts_cpu_volumes() const override { return true; }
  bool counts_work() const override { return true; }
  VolumeCosts measure_volume_costs() override;

  void begin_frame(const FrameInputs& inputs) override;
  void begin_depth(Layer layer) override;
  void draw_depth(std::span<const std::uint32_t> objects) override;
  void end_depth() override;
  QueryId issue_query(std::span<const glm::vec4> triangles, bool surfaces_only) override;
  bool query_ready(QueryId) override { return true; }  // answered when issued
  bool query_visible(QueryId query) override { return answers_[query] != 0; }
  void read_ids(Layer layer, SurfaceLayer& out) override;
  void volumes_ready(std::size_t, const std::vector<std::uint8_t>&) override {}
  // Counts are zero after each read; a light's passes keep to its scissor (FramePlan::reach).
  void begin_mask(std::size_t light) override;
  void begin_light_map(std::size_t light) override;
  void count_volume(std::size_t light, std::size_t object) override;
  // Volumes counted by z-pass or z-fail over the whole image go into one draw per rule (each
  // triangle kept to its volume's depth bounds) unless batching is off: the same counts.
  void count_volumes(std::size_t light, std::span<const std::uint32_t> objects) override;
  void set_batching(bool on) { batching_ = on; }
  void end_group(std::size_t group) override;
  void read_mask(std::size_t light, SurfaceLayer& layer) override;
  void read_light_map(std::size_t light, SurfaceLayer& layer) override;
  void end_counts() override;
  void light_pass(std::size_t, Layer) override {}                  // in shade
  void read_facing(std::size_t, Layer, SurfaceLayer&) override {}  // shade records it
  void see_through() override;
  void shade() override;
  void read_image(Image&) override {}  // shade writes it

 private:
  // Triangles (3 clip-space vertices each) and their weights, grouped by a key per triangle:
  // those of keys [first, last) are together, in order. Triangles whose keys already run in
  // order (a volume counted whole: its sides, then its caps) are viewed where they lie, which
  // must outlive the view; others are copied into order, stably.
  struct Grouped {
    std::span<const glm::vec4> tris;
    std::span<const std::int32_t> weights;
    std::vector<std::size_t> offsets;    // key k's are [offsets[k], offsets[k + 1])
    std::vector<glm::vec4> sorted_tris;  // the copies, kept between frames
    std::vector<std::int32_t> sorted_weights;
    std::vector<std::size_t> cursor;  // where the next of key k goes, while copying

    void group(std::span<const glm::vec4> triangles, std::span<const std::int32_t> triangle_weights,
               std::span<const std::uint32_t> keys, std::size_t key_count);
    std::span<const glm::vec4> triangles_of(std::size_t first, std::size_t last) const {
      return tris.subspan(3 * offsets[first], 3 * (offsets[last] - offsets[first]));
    }
    std::span<const std::int32_t> weights_of(std::size_t first, std::size_t last) const {
      return weights.subspan(offsets[first], offsets[last] - offsets[first]);
    }
  };

  const FrameInputs* in_ = nullptr;  // the frame being drawn
  raster::Target target_;
  SplitPlaneSampler split_sampler_;
  // Kept between frames: no reallocation. Under a split plane, a key per triangle (its part and
  // whether only z-fail counts it) and the triangles grouped by it.
  std::vector<glm::vec4> tris_, prefill_tris_;
  std::vector<std::int32_t> weights_, prefill_weights_;
  std::vector<std::uint32_t> ids_;           // a depth batch's id per triangle
  std::vector<raster::FaceCull> face_cull_;  // and what facing of it is left out, if any
  std::vector<glm::vec4> clip_vertices_;     // a depth batch's vertices in clip space
  std::vector<std::uint32_t> indices_;       // and its triangles' indices into them
  // count_volumes: the volumes of one rule (z-pass, z-fail), each triangle with its bounds.
  struct Batch {
    std::vector<glm::vec4> tris;
    std::vector<std::int32_t> weights;
    std::vector<raster::DepthBounds> bounds;
    void clear() { tris.clear(), weights.clear(), bounds.clear(); }
  };
  Batch batches_[2];
  bool batching_ = true;
  std::vector<std::uint8_t> answers_;  // per query of the frame: visible
  Layer layer_ = Layer::opaque;        // of the depth pass begun
  std::vector<std::uint32_t> keys_, prefill_keys_;
  std::vector<std::uint32_t> prefill_parts_;  // the pre-fill's input: each triangle's part
  std::vector<glm::vec4> prefill_apexes_;     // and its scratch
  Grouped volume_groups_, prefill_groups_;
  std::vector<glm::vec3> log_light_, eye_log_;
  std::vector<float> opaque_depth_;  // with transparent casters: the opaque layer's depths
  // RenderOptions::tile_work_per_object: the frame's total (the target's tile work moves into it
  // and into the object's share after each volume).
  std::vector<raster::TileWork> total_work_, shadow_work_;
  // Per object the frame shows: its faces' unit normals, eye-relative (shade); for an object
  // with shading normals (SceneObject::shading) or a texture (SceneObject::uvs), its faces'
  // corners too, eye-relative, 3 per face, to interpolate at each pixel, and the normals.
  std::vector<std::uint8_t> seen_;
  std::vector<std::vector<glm::vec3>> normals_;
  struct FaceCorners {
    std::vector<glm::vec3> corners, normals;  // normals: with shading normals only
    const float* offsets = nullptr;           // the object's, per corner (shading normals)
    const glm::vec2* uvs = nullptr;           // the object's, per corner (a texture)
  };
  std::vector<FaceCorners> face_corners_;
  // One row of pixels being shaded, an array per component (shade_row), all in one block: a
  // thread that shades for the first time allocates once per row, not once per component.
  struct ShadeRow {
    // The normal shaded with and the face's own (both on the side the eye sees), the terminator
    // offset, the albedo, the depth, and the colour.
    std::span<float> nx, ny, nz, fx, fy, fz, offset, ar, ag, ab, z, r, g, b;
    std::vector<std::uint8_t> faces;  // per pixel: faces the light (unless the layer keeps it)
    ShadeRow() = default;
    ShadeRow(const ShadeRow&) = delete;  // its spans point into its own block
    ShadeRow& operator=(const ShadeRow&) = delete;
    void resize(std::size_t n) {
      std::span<float>* const components[] = {&nx, &ny, &nz, &fx, &fy, &fz, &offset,
                                              &ar, &ag, &ab, &z,  &r,  &g,  &b};
      block.resize(n * std::size(components));
      for (std::size_t k = 0; k < std::size(components); ++k)
        *components[k] = std::span<float>(block).subspan(k * n, n);
      faces.resize(n);
    }
    glm::vec3 color(int x) const {
      const auto i = static_cast<std::size_t>(x);
      return {r[i], g[i], b[i]};
    }

   private:
    std::vector<float> block;
  };
  // Lights row y of `layer` (its depths `depth`) into out's r, g, b; `lights_at` eye-relative.
  // Where the layer records which surfaces face each light (faces_light), into it.
  void shade_row(const Scene& scene, const glm::mat4& inv_vp, std::span<const glm::vec4> lights_at,
                 SurfaceLayer& layer, std::span<const float> depth, int y, ShadeRow& out) const;
  // Per thread, kept between frames: the rows of the opaque and the glass layer being shaded.
  struct ShadeRows {
    ShadeRow surface, through;
  };
  tbb::enumerable_thread_specific<ShadeRows> shade_rows_;
  std::vector<glm::vec4> lights_at_;  // eye-relative light positions (w = 1) or directions (0)
};

// A Renderer (the frame pipeline) on this backend.
Renderer soft_renderer();

}  // namespace shadowvol::soft
