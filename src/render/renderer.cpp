#include "render/renderer.h"

#include <cassert>
#include <chrono>
#include <ranges>
#include <utility>

#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include "render/volume_overlay.h"

namespace shadowvol {
namespace {

using Clock = std::chrono::steady_clock;

// Empties the stats for a new frame, keeping the per-object lists' storage.
void reset(FrameStats& stats) {
  std::vector<int> zfail_lights = std::move(stats.zfail_lights);
  std::vector<int> culled_lights = std::move(stats.culled_lights);
  stats = {};
  stats.zfail_lights = std::move(zfail_lights);
  stats.culled_lights = std::move(culled_lights);
}

// Sizes the layer's per-light masks (and light, with transparent casters; and which surfaces
// face each light, where recorded) in place: a copy would touch every page twice, and a frame of
// the same size allocates nothing.
void size_layer(SurfaceLayer& layer, std::size_t lights, std::size_t pixels, bool glass,
                bool facing) {
  layer.shadowed.resize(lights);
  for (std::vector<std::uint8_t>& mask : layer.shadowed) mask.resize(pixels);
  layer.transmitted.resize(glass ? lights : 0);
  for (std::vector<glm::vec3>& light : layer.transmitted) light.resize(pixels);
  layer.faces_light.resize(facing ? lights : 0);
  for (std::vector<std::uint8_t>& faces : layer.faces_light) faces.assign(pixels, 0);
}

// Sizes a frame's per-pixel buffers side by side: at a new size each page's first touch is a
// page fault, which the cores then take at once rather than one after another in the passes.
void size_frame(Frame& frame, std::size_t lights, std::size_t pixels, bool glass, bool facing) {
  tbb::parallel_invoke([&] { frame.object.resize(pixels); }, [&] { frame.face.resize(pixels); },
                       [&] { frame.image.rgba.resize(4 * pixels); },
                       [&] { size_layer(frame, lights, pixels, glass, facing); });
}

// An object that does not receive shadows (SceneObject::receives_shadows) gets every light
// that reaches it: its pixels' masks are cleared, and all the light arrives through the
// transparent casters.
void clear_non_receivers(const FramePlan& plan, std::size_t light, SurfaceLayer& layer) {
  std::vector<std::uint8_t>& mask = layer.shadowed[light];
  for (std::size_t p = 0; p < mask.size(); ++p) {
    const std::int32_t o = layer.object[p];
    if (o < 0 || plan.objects[static_cast<std::size_t>(o)].receives) continue;
    mask[p] = 0;
    if (!layer.transmitted.empty()) layer.transmitted[light][p] = glm::vec3(1.0f);
  }
}

// Runs one step of the frame and adds its time into `into`, the backend's work included.
template <class Step>
void timed(FrameBackend& backend, double& into, Step&& step) {
  backend.finish();
  const auto start = Clock::now();
  step();
  backend.finish();
  into += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

// The update manager's builds of one frame: every light's changed volumes, on a worker thread,
// while the depth pass runs (RenderOptions::overlap_volumes).
struct Renderer::Builds {
  tbb::task_group group;
  bool ahead = false;  // the frame's volumes are built here, not per light after the depth pass
  bool joined = true;
  FrameStats stats;  // the builds' own: built and reused
  Clock::time_point start, end, depth_start, depth_end;

  // Waits for them (once) and adds their stats, and how long they ran beside the depth pass.
  void join(FrameStats& into) {
    if (joined) return;
    group.wait();
    joined = true;
    into.volumes_built += stats.volumes_built;
    into.volumes_reused += stats.volumes_reused;
    const auto ms = [](Clock::duration d) {
      return std::chrono::duration<double, std::milli>(d).count();
    };
    into.ms_volume_builds += ms(end - start);
    into.ms_volumes_hidden +=
        std::max(0.0, ms(std::min(end, depth_end) - std::max(start, depth_start)));
  }
};

Renderer::Renderer(std::unique_ptr<FrameBackend> backend) : backend_(std::move(backend)) {
  assert(backend_);
}

void Renderer::render(const Scene& scene, const RenderOptions& options, Frame& frame) {
  draw(scene, options, frame, true);
}

Frame Renderer::render(const Scene& scene, const RenderOptions& options) {
  Frame frame;
  draw(scene, options, frame, true);
  return frame;
}

void Renderer::present(const Scene& scene, const RenderOptions& options, Frame& frame) {
  assert(backend_->can_present());
  draw(scene, options, frame, false);
  backend_->present();
}

void Renderer::draw(const Scene& scene, const RenderOptions& options, Frame& frame,
                    bool read_back) {
  assert(check_options(options).ok());
  assert(backend_->supports(options).ok());
  FrameStats& stats = frame.stats;
  reset(stats);
  plan_frame(scene, options, plan_, stats);
  // A backend whose targets are memory fills the frame whatever is asked.
  read_back = read_back || !backend_->can_present();
  const FrameInputs in{scene, options, plan_, volumes_, frame};
  // The update manager: every light's changed volumes built on a worker thread while the depth
  // pass runs, where the plan's volumes stand from here on.
  const bool cpu_volumes = backend_->counts_cpu_volumes() || options.show_volumes;
  Builds builds;
  builds.ahead = options.overlap_volumes && cpu_volumes && options.cull == Cull::none &&
                 options.clamp == Clamp::none && !culls_shadows(options.occlusion) &&
                 !scene.lights.empty();
  builds.joined = !builds.ahead;
  if (builds.ahead)
    builds.group.run([&] {
      builds.start = Clock::now();
      for (std::size_t l = 0; l < scene.lights.size(); ++l)
        volumes_.update(scene, plan_, l, builds.stats);
      builds.end = Clock::now();
    });
  const std::size_t pixels = static_cast<std::size_t>(options.width) * options.height;
  const std::size_t lights = scene.lights.size();
  const bool glass = plan_.has_glass();

  // Continuous clamping weighs each interval by the backend's costs, measured once, at start.
  if (clamps_continuous(options.clamp) && !costs_.measured())
    costs_ = backend_->measure_volume_costs();
  stats.volume_costs = costs_;
  if (read_back && frame.object.size() != pixels)
    size_frame(frame, lights, pixels, glass, options.record_facing);
  backend_->begin_frame(in);
  // The scene BVH made current for this frame's boxes, where occlusion culling walks it.
  if (options.occlusion != Occlusion::none) occlusion_.begin_frame(plan_, stats);
  // A layer: its depth pass over the depth target as it stands (the opaque one front to back by
  // occlusion culling, where asked), its ids, then per light its shadows and light.
  auto draw_layer = [&](Layer layer, SurfaceLayer& out) {
    const bool opaque = layer == Layer::opaque;
    if (opaque) builds.depth_start = Clock::now();
    timed(*backend_, stats.ms_depth, [&] {
      if (opaque && culls_eye(options.occlusion))
        return occlusion_.depth_pass(plan_, *backend_, stats);
      all_.clear();
      for (std::uint32_t o = 0; o < scene.objects.size(); ++o)
        if (plan_.transparent(o) != opaque) all_.push_back(o);
      backend_->begin_depth(layer);
      backend_->draw_depth(all_);
      backend_->end_depth();
      if (opaque) stats.objects_drawn += static_cast<int>(all_.size());
    });
    if (opaque) builds.depth_end = Clock::now();
    for (std::size_t o = 0; o < scene.objects.size(); ++o)
      if (plan_.transparent(o) != opaque &&
          !(opaque && culls_eye(options.occlusion) && !occlusion_.drawn()[o]))
        stats.triangles += scene.objects[o].mesh->triangle_count();
    // Culling by occlusion and discrete clamping take the opaque layer's ids (their visible
    // samples) even for a frame shown on the device.
    const bool ids = opaque && CcShadowVolumes::needs_ids(options);
    if (read_back || ids) {
      timed(*backend_, stats.ms_readback, [&] { backend_->read_ids(layer, out); });
      size_layer(out, lights, pixels, glass, read_back && options.record_facing);
    }
    if (opaque && (options.cull != Cull::none || options.clamp != Clamp::none)) {
      backend_->finish();
      cc_.apply(scene, options, plan_, ids ? &out : nullptr, costs_, backend_->counts_cpu_volumes(),
                stats);
    }
    // The shadow volumes' hierarchical culling, on the finished opaque depth: where transparent
    // casters are drawn later, a surface of theirs may receive in front of the background.
    if (opaque && culls_shadows(options.occlusion)) {
      backend_->finish();
      for (std::size_t l = 0; l < lights; ++l)
        occlusion_.cull_volumes(plan_, l, *backend_, !glass, stats);
    }
    for (std::size_t l = 0; l < lights; ++l) light_layer(in, l, layer, out, read_back, builds);
  };
  draw_layer(Layer::opaque, frame);
  if (glass) {
    timed(*backend_, stats.ms_depth, [&] { backend_->see_through(); });  // a surface pass
    draw_layer(Layer::glass, frame.glass);
  } else {
    frame.glass.object.clear();
    frame.glass.face.clear();
    frame.glass.shadowed.clear();
    frame.glass.transmitted.clear();
    frame.glass.faces_light.clear();
  }
  // A frame without count passes still joins.
  if (!builds.joined) timed(*backend_, stats.ms_volumes, [&] { builds.join(stats); });
  timed(*backend_, stats.ms_shade, [&] { backend_->shade(); });
  if (read_back) {
    timed(*backend_, stats.ms_readback, [&] { backend_->read_image(frame.image); });
    if (options.show_volumes) overlay_volumes(frame.image, scene, plan_, volumes_);
  }
}

void Renderer::light_layer(const FrameInputs& in, std::size_t l, Layer layer, SurfaceLayer& out,
                           bool read_back, Builds& builds) {
  FrameStats& stats = in.frame.stats;
  const bool cpu = backend_->counts_cpu_volumes();
  timed(*backend_, stats.ms_volumes, [&] {
    builds.join(stats);  // they read the plan's volumes: done before the depth bounds are written
    plan_depth_bounds(plan_, l);
    if (!(cpu || in.options.show_volumes)) return backend_->volumes_ready(l, none_rebuilt_);
    if (builds.ahead && layer == Layer::opaque)  // built beside the depth pass
      return backend_->volumes_ready(l, volumes_.rebuilt(l));
    const auto start = Clock::now();
    const std::vector<std::uint8_t>& rebuilt = volumes_.update(in.scene, plan_, l, stats);
    stats.ms_volume_builds +=
        std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    backend_->volumes_ready(l, rebuilt);
  });
  // Counts the volumes of the objects `which` takes, those not culled, in one call.
  auto count = [&](auto&& objects, auto&& which) {
    counted_.clear();
    for (const std::size_t o : objects) {
      const VolumePlan& v = plan_.volume(l, o);
      if (v.culled || !which(o)) continue;
      stats.volume_segments += v.segments();
      ++stats.volumes_drawn;
      if (cpu) stats.volume_primitives += volumes_.volume(l, o).primitive_count();
      counted_.push_back(static_cast<std::uint32_t>(o));
    }
    backend_->count_volumes(l, counted_);
  };
  // The opaque casters' counts: the shadow mask.
  timed(*backend_, stats.ms_counts, [&] {
    backend_->begin_mask(l);
    count(std::views::iota(std::size_t{0}, plan_.objects.size()),
          [&](std::size_t o) { return !plan_.transparent(o); });
    backend_->end_counts();
  });
  if (read_back) timed(*backend_, stats.ms_readback, [&] { backend_->read_mask(l, out); });
  const bool clear = read_back && plan_.any_non_receiver;
  if (clear && !plan_.has_glass()) clear_non_receivers(plan_, l, out);
  // The transparent casters' light intensity map (Kim et al. Eq. 3), a group of one material at
  // a time: each count adds the group's log transmittance.
  if (plan_.has_glass()) {
    timed(*backend_, stats.ms_counts, [&] {
      backend_->begin_light_map(l);
      for (std::size_t g = 0; g < plan_.glass.size(); ++g) {
        count(plan_.glass[g].members, [](std::size_t) { return true; });
        backend_->end_group(g);
      }
      backend_->end_counts();
    });
    if (read_back) timed(*backend_, stats.ms_readback, [&] { backend_->read_light_map(l, out); });
  }
  if (clear && plan_.has_glass()) clear_non_receivers(plan_, l, out);
  timed(*backend_, stats.ms_shade, [&] { backend_->light_pass(l, layer); });
  if (read_back && in.options.record_facing)
    timed(*backend_, stats.ms_readback, [&] { backend_->read_facing(l, layer, out); });
}

}  // namespace shadowvol
