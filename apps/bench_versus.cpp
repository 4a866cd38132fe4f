#include "bench_versus.h"

#include <chrono>
#include <cstdio>
#include <sstream>
#include <vector>

#include "backend/backend.h"
#include "gl/gl_backend.h"
#include "trace/embree_baseline.h"

namespace shadowvol {
namespace {

std::string format(const char* pattern, auto... values) {
  char line[512];
  std::snprintf(line, sizeof line, pattern, values...);
  return line;
}

// A ratio with its goal: "0.42x (goal <= 0.5: met)".
std::string against(double ratio, const char* goal_sign, double goal) {
  const bool met = goal_sign[0] == '<' ? ratio <= goal : ratio >= goal;
  return format("%.2fx (goal %s %g: %s)", ratio, goal_sign, goal, met ? "met" : "not met");
}

}  // namespace

Expected<Baselines> parse_baselines(const std::string& text) {
  Baselines b;
  std::istringstream in(text);
  for (std::string name; std::getline(in, name, ',');) {
    if (name == "embree")
      b.embree = true;
    else if (name == "gl")
      b.gl = true;
    else
      return make_error("unknown baseline '" + name + "': expected embree, gl or embree,gl");
  }
  if (!b.any()) return make_error("name a baseline: embree, gl or embree,gl");
  return b;
}

Expected<ClassicGl> classic_gl(const RenderOptions& options) {
  ClassicGl classic;
  classic.options = options;
  classic.options.method = Method::zfail;
  auto made =
      make_renderer(Backend::gl, {gl::VolumePath::cpu, gl::CountTarget::stencil}, classic.options);
  if (!made) return made.error();
  classic.renderer = std::move(made->renderer);
  classic.note = dynamic_cast<const gl::GlBackend&>(classic.renderer->backend()).info().renderer;
  return classic;
}

MeasuredFrame measured(const FrameTiming& timing) {
  const double n = timing.frames;
  const FrameStats& s = timing.total;
  return {timing.frame_ms, timing.first_frame_ms, s.ms_depth / n, (s.ms_volumes + s.ms_counts) / n,
          s.ms_shade / n};
}

Expected<void> versus_embree(const Scene& scene, const RenderOptions& options, int frames,
                             bool animate, Renderer& renderer, const MeasuredFrame& ours,
                             Versus& versus) {
  auto embree = EmbreeBaseline::create();
  if (!embree) return embree.error();
  // With the BVH rebuilt every frame: Embree ray casting, and the hybrid.
  double bvh = 0, primary = 0, shadow = 0;
  double depth = 0, points_ms = 0, hybrid_shadow = 0;
  std::uint64_t shadowed = 0;
  Frame frame;
  std::vector<glm::vec4> points;
  for (int f = 0; f <= frames; ++f) {  // frame 0 warms up
    const Scene moved = animate ? scene_at_frame(scene, f) : Scene{};
    const Scene& s = animate ? moved : scene;
    double build_ms = 0.0;
    if (auto ok = (*embree)->build(s, build_ms); !ok) return ok.error();
    const EmbreeFrame e = (*embree)->trace(s, options.width, options.height);
    // The hybrid: our depth pass (a whole frame drawn, its depth pass's time taken), the points
    // rebuilt from it, Embree's shadow rays from them over the BVH just built.
    renderer.render(s, options, frame);
    const auto start = std::chrono::steady_clock::now();
    visible_points(s, options.width, options.height, frame.object, frame.face, points);
    const double rebuilt_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const double rays_ms = (*embree)->shadow_rays(s, points, shadowed);
    if (f == 0) continue;
    bvh += build_ms, primary += e.ms_primary, shadow += e.ms_shadow;
    depth += frame.stats.ms_depth, points_ms += rebuilt_ms, hybrid_shadow += rays_ms;
    versus.embree_built.push_back(build_ms + e.ms_primary + e.ms_shadow);
    versus.hybrid_built.push_back(build_ms + rays_ms);
  }
  for (double* x : {&bvh, &primary, &shadow, &depth, &points_ms, &hybrid_shadow}) *x /= frames;
  const double built = bvh + primary + shadow;
  const double vc = ours.volumes_counts_ms;
  nlohmann::json& j = versus.json;
  j["embree"] = {{"bvh_build_ms", bvh},
                 {"primary_ms", primary},
                 {"shadow_ms", shadow},
                 {"frame_bvh_built_ms", built}};
  j["hybrid"] = {{"depth_ms", depth},
                 {"points_ms", points_ms},
                 {"bvh_build_ms", bvh},
                 {"shadow_ms", hybrid_shadow}};
  nlohmann::json& r = j["ratios"];
  r["frame_over_embree_built"] = ours.frame_ms / built;
  r["volumes_counts_over_hybrid_shadow_built"] = vc / (bvh + hybrid_shadow);
  versus.text += format(
      "%-16s embree, BVH rebuilt (dynamic, medium quality): BVH %.2f + primary %.2f + shadow %.2f "
      "ms; hybrid: our depth %.2f + points %.2f + BVH %.2f + shadow %.2f ms\n",
      "", bvh, primary, shadow, depth, points_ms, bvh, hybrid_shadow);
  versus.text +=
      format("%-16s frame / embree's, BVH built%s: %s\n", "", animate ? " (animated)" : "",
             against(ours.frame_ms / built, "<=", animate ? 1.0 : 0.5).c_str());
  versus.text +=
      format("%-16s volumes + counts / hybrid's BVH + shadow rays%s: %s\n", "",
             animate ? " (animated)" : "", against(vc / (bvh + hybrid_shadow), "<=", 0.5).c_str());
  if (animate) return {};  // a moving caster's BVH cannot be kept
  // With the BVH kept (static): built once at high quality, untimed; the rays alone, timed, the
  // hybrid's from the points of the last frame (the scene stands still).
  double kept_build = 0, kept_primary = 0, kept_shadow = 0, kept_hybrid = 0;
  if (auto ok = (*embree)->build(scene, kept_build, EmbreeBaseline::Bvh::kept); !ok)
    return ok.error();
  for (int f = 0; f <= frames; ++f) {
    const EmbreeFrame e = (*embree)->trace(scene, options.width, options.height);
    const double rays_ms = (*embree)->shadow_rays(scene, points, shadowed);
    if (f == 0) continue;
    kept_primary += e.ms_primary, kept_shadow += e.ms_shadow, kept_hybrid += rays_ms;
    versus.embree_kept.push_back(e.ms_primary + e.ms_shadow);
    versus.hybrid_kept.push_back(rays_ms);
  }
  for (double* x : {&kept_primary, &kept_shadow, &kept_hybrid}) *x /= frames;
  const double kept = kept_primary + kept_shadow;
  j["embree"].update({{"kept_bvh_build_ms", kept_build},
                      {"kept_primary_ms", kept_primary},
                      {"kept_shadow_ms", kept_shadow},
                      {"frame_bvh_kept_ms", kept}});
  j["hybrid"]["kept_shadow_ms"] = kept_hybrid;
  r["frame_over_embree_kept"] = ours.frame_ms / kept;
  r["volumes_counts_over_hybrid_shadow_kept"] = vc / kept_hybrid;
  versus.text += format(
      "%-16s embree, BVH kept (high quality, built once in %.2f ms): primary %.2f + shadow %.2f "
      "ms; hybrid: shadow %.2f ms\n",
      "", kept_build, kept_primary, kept_shadow, kept_hybrid);
  versus.text += format("%-16s frame / embree's, BVH kept: %s\n", "",
                        against(ours.frame_ms / kept, "<=", 1.0).c_str());
  versus.text += format("%-16s volumes + counts / hybrid's shadow rays, BVH kept: %s\n", "",
                        against(vc / kept_hybrid, "<=", 0.5).c_str());
  return {};
}

void versus_gl(const MeasuredFrame& ours, const FrameTiming& gl, const std::string& device,
               Versus& versus) {
  const MeasuredFrame classic = measured(gl);
  versus.gl = gl.ms_per_frame;
  versus.json["gl_classic"] = {{"device", device},
                               {"frame_ms", classic.frame_ms},
                               {"depth_ms", classic.depth_ms},
                               {"volumes_counts_ms", classic.volumes_counts_ms},
                               {"shade_ms", classic.shade_ms}};
  nlohmann::json& r = versus.json["ratios"];
  r["gl_frame_over_frame"] = classic.frame_ms / ours.frame_ms;
  r["shade_over_gl_shade"] = ours.shade_ms / classic.shade_ms;
  versus.text += format(
      "%-16s gl classic (CPU volumes, z-fail, stencil; %s): %.2f ms a frame (depth %.2f, volumes "
      "+ counts %.2f, shade %.2f)\n",
      "", device.c_str(), classic.frame_ms, classic.depth_ms, classic.volumes_counts_ms,
      classic.shade_ms);
  versus.text += format("%-16s gl classic frame / frame: %s; shade / gl's: %s\n", "",
                        against(classic.frame_ms / ours.frame_ms, ">=", 15.0).c_str(),
                        against(ours.shade_ms / classic.shade_ms, "<=", 1.0).c_str());
}

void versus_cold(const MeasuredFrame& ours, Versus& versus) {
  versus.json["ratios"]["first_frame_over_frame"] = ours.first_frame_ms / ours.frame_ms;
  versus.text += format("%-16s first (cold) frame %.2f ms / frame: %s\n", "", ours.first_frame_ms,
                        against(ours.first_frame_ms / ours.frame_ms, "<=", 1.5).c_str());
}

std::vector<PlotPanel> versus_panels(const std::string& scene, const FrameTiming& ours,
                                     const Versus& versus) {
  const glm::vec3 ours_color{0.80f, 0.33f, 0.10f}, built{0.15f, 0.35f, 0.75f},
      kept{0.45f, 0.70f, 0.95f}, gl_color{0.30f, 0.60f, 0.25f};
  std::vector<double> volumes_counts;
  for (const FrameStats& s : ours.stats_per_frame)
    volumes_counts.push_back(s.ms_volumes + s.ms_counts);
  std::vector<PlotPanel> panels;
  const auto panel = [&](std::string title, std::vector<PlotSeries> series) {
    std::erase_if(series, [](const PlotSeries& s) { return s.values.empty(); });
    if (series.size() > 1)
      panels.push_back({scene + ": " + std::move(title), std::move(series), {}});
  };
  // Frames against Embree ray casting; volumes and counts against the hybrid's shadow rays.
  panel("frame vs Embree, ms", {{"shadowvol", ours_color, ours.ms_per_frame},
                                {"baseline, BVH built", built, versus.embree_built},
                                {"baseline, BVH kept", kept, versus.embree_kept}});
  panel("shadows vs hybrid, ms", {{"shadowvol", ours_color, volumes_counts},
                                  {"baseline, BVH built", built, versus.hybrid_built},
                                  {"baseline, BVH kept", kept, versus.hybrid_kept}});
  panel("frame vs gl, ms",
        {{"shadowvol", ours_color, ours.ms_per_frame}, {"gl classic", gl_color, versus.gl}});
  return panels;
}

}  // namespace shadowvol
