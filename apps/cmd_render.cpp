// shadowvol render: a scene with exact shadows to a PNG, and optionally the pictures of what the
// passes did (the count passes' work per tile, the light that reaches each surface).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "image_file.h"
#include "output_file.h"
#include "plot.h"
#include "render/frame_json.h"
#include "render/frame_outputs.h"
#include "render/heatmap.h"
#include "render/light_map.h"

namespace shadowvol::cli {
namespace {

struct RenderArgs {
  FrameArgs frame{"demo", "auto", "auto", "960x540"};
  std::string out = "shadowvol.png";
  bool stats = false;
  bool json = false;
  bool show_volumes = false;
  int frames = 1;
  std::string heatmap;    // PNG of the count passes' work per tile; soft backend
  std::string light_map;  // PNG of the light that reaches each surface
  std::string mask;       // per light a grey PNG: lit, shadowed, facing away or nothing
  std::string depth;      // PFM of the view depth
  std::string ids;        // PNG of the object ids
  int samples = 1;        // per pixel of the picture (--out)
};

// F.png for one light, F-L.png for light L of several.
std::string mask_path(const std::string& path, std::size_t light, std::size_t lights) {
  if (lights == 1) return path;
  const std::filesystem::path p(path);
  return (p.parent_path() /
          (p.stem().string() + "-" + std::to_string(light) + p.extension().string()))
      .string();
}

void print_stats(const FrameStats& s, const RenderOptions& options, bool counts_work) {
  std::printf(
      "  depth %.1f ms, volumes %.1f ms, counts %.1f ms, shade %.1f ms, read-back %.1f ms\n",
      s.ms_depth, s.ms_volumes, s.ms_counts, s.ms_shade, s.ms_readback);
  std::printf(
      "  %zu triangles, %zu volume primitives, objects by z-pass %d, by z-fail %d, by a split "
      "plane %d, volumes built %d, reused %d\n",
      s.triangles, s.volume_primitives, s.objects_zpass, s.objects_zfail, s.objects_split,
      s.volumes_built, s.volumes_reused);
  if (s.ms_volume_builds > 0)
    std::printf("  volume builds %.1f ms, of which %.1f ms beside the depth pass (hidden)\n",
                s.ms_volume_builds, s.ms_volumes_hidden);
  if (s.parts_zpass > 0)
    std::printf(
        "  parts of z-fail objects counted by z-pass (their own spheres miss the near "
        "plane's shadow): %d\n",
        s.parts_zpass);
  using ull = unsigned long long;
  if (options.cull != Cull::none)
    std::printf(
        "  culling %.1f ms: %d light views, %llu queries, casters culled in shadow %d, for "
        "unseen shadows %d, sub-objects culled %d\n",
        s.ms_cull, s.light_views, ull(s.cull_queries), s.casters_culled_in_shadow,
        s.casters_culled_unseen, s.sub_objects_culled);
  if (options.occlusion != Occlusion::none)
    std::printf(
        "  occlusion culling (%s): %llu nodes visited, %llu queries (%llu waited for), objects "
        "culled %d, drawn %d; volumes culled %d, drawn %d; BVH %s %.1f ms, shadow queries %.1f "
        "ms\n",
        std::string(to_string(options.occlusion)).c_str(), ull(s.nodes_visited), ull(s.queries),
        ull(s.queries_waited), s.objects_culled, s.objects_drawn, s.volumes_culled, s.volumes_drawn,
        s.bvh_rebuilt > 0 ? "built" : "refit", s.ms_bvh, s.ms_occlusion);
  if (clamps_continuous(options.clamp))
    std::printf(
        "  continuous clamping: %d volumes clamped (%llu overlapping pairs, %llu sort "
        "interchanges, %llu intervals merged as V > R; v %.3g ms per vertex, r %.3g ms per pixel, "
        "measured at start)\n",
        s.volumes_clamped, ull(s.clamp_pairs), ull(s.clamp_swaps), ull(s.intervals_merged_by_cost),
        s.volume_costs.ms_per_vertex, s.volume_costs.ms_per_pixel);
  if (clamps_discrete(options.clamp))
    std::printf("  discrete clamping: %d slice%s, %llu slice queries, %d volumes in no slice\n",
                options.slices, options.slices == 1 ? "" : "s", ull(s.slice_queries),
                s.volumes_clamped_away);
  if (options.clamp != Clamp::none) std::printf("  clamping %.1f ms in all\n", s.ms_clamp);
  if (s.volumes_out_of_range > 0 || s.scissor_pixels_saved > 0)
    std::printf(
        "  light ranges: %d volumes of casters beyond a light's range not built, %llu pixels "
        "outside the lights' scissors (over all lights)\n",
        s.volumes_out_of_range, ull(s.scissor_pixels_saved));
  std::printf("  %llu volume segments drawn", ull(s.volume_segments));
  if (s.fill > 0 || s.stencil_writes > 0)
    std::printf(", fill %llu pixels, stencil writes %llu", ull(s.fill), ull(s.stencil_writes));
  std::printf("\n");
  if (counts_work)
    std::printf(
        "  depth pass: %llu triangles in, %llu culled (back faces of closed parts, outside the "
        "view or zero area), %llu tiles touched, %llu pixels processed\n",
        ull(s.depth.triangles_in), ull(s.depth.triangles_culled), ull(s.depth.tiles_touched),
        ull(s.depth.pixels_processed));
  if (counts_work)
    std::printf(
        "  count pass: %llu triangles in, %llu clipped, %llu left out of a block row by hi-z, "
        "%llu tiles touched, %llu skipped by hi-z or depth bounds, %llu pixels processed, %llu "
        "count updates\n",
        ull(s.counts.triangles_in), ull(s.counts.triangles_clipped),
        ull(s.counts.block_rows_skipped), ull(s.counts.tiles_touched), ull(s.counts.tiles_skipped),
        ull(s.counts.pixels_processed), ull(s.counts.count_updates));
  if (s.split_sampling.triangles_in > 0)
    std::printf(
        "  split-plane sampling: %llu triangles in, %llu tiles touched, %llu skipped, %llu "
        "samples processed, %llu counted\n",
        ull(s.split_sampling.triangles_in), ull(s.split_sampling.tiles_touched),
        ull(s.split_sampling.tiles_skipped), ull(s.split_sampling.pixels_processed),
        ull(s.split_sampling.count_updates));
}

int run(const RenderArgs& args) {
  if (args.frames < 1)
    return fail("--frames: " + std::to_string(args.frames) + " is not a positive count");
  auto resolved = resolve(args.frame);
  if (!resolved) return fail(resolved.error().message);
  const Scene& scene = resolved->scene;
  RenderOptions options = resolved->options;
  options.show_volumes = args.show_volumes;
  options.tile_work = !args.heatmap.empty();
  options.count_fill = args.stats || args.json;
  std::vector<std::string> outputs{args.out, args.depth, args.ids, args.heatmap, args.light_map};
  if (!args.mask.empty())
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
      outputs.push_back(mask_path(args.mask, l, scene.lights.size()));
  if (auto ok = check_outputs(outputs, {args.frame.scene}); !ok) return fail(ok.error().message);
  const auto side = samples_side(args.samples, options.width, options.height);
  if (!side) return fail("--samples: " + side.error().message);
  auto renderer = make_frame_renderer(*resolved, options);
  if (!renderer) return fail(renderer.error().message);
  // The supersampled picture: the last frame once more, at k times the size.
  RenderOptions sampled = options;
  sampled.width *= *side, sampled.height *= *side;
  sampled.count_fill = sampled.tile_work = false;
  if (auto ok = (*renderer)->backend().supports(sampled); !ok)
    return fail("--samples: " + ok.error().message);

  Frame frame;
  StatusLine status;
  for (int i = 0; i < args.frames; ++i) {
    if (args.frames > 1)
      status.show("frame " + std::to_string(i + 1) + " of " + std::to_string(args.frames));
    (*renderer)->render(scene_at_frame(scene, i), options, frame);
  }
  Image picture = frame.image;
  if (*side > 1) {
    status.show(std::to_string(args.samples) + " samples per pixel");
    Frame samples;
    (*renderer)->render(scene_at_frame(scene, args.frames - 1), sampled, samples);
    picture = resolve_samples(samples.image, *side);
  }
  status.clear();
  std::FILE* said = args.json ? stderr : stdout;
  if (auto ok = write_png(args.out, picture); !ok) return fail(ok.error().message);
  std::fprintf(
      said, "wrote %s (%s, %dx%d, %s, %s%s)\n", args.out.c_str(), scene.name.c_str(), picture.width,
      picture.height, method_label(options).c_str(),
      std::string((*renderer)->backend().name()).c_str(),
      *side > 1 ? (", " + std::to_string(args.samples) + " samples per pixel").c_str() : "");
  const Scene last = scene_at_frame(scene, args.frames - 1);
  if (!args.mask.empty()) {
    for (std::size_t l = 0; l < last.lights.size(); ++l) {
      const std::string path = mask_path(args.mask, l, last.lights.size());
      if (auto ok = write_png(path, shadow_mask(last, frame, l)); !ok)
        return fail(ok.error().message);
      std::fprintf(said,
                   "wrote %s (light %zu's shadow mask: 255 lit, 0 in shadow, 128 facing away "
                   "or no surface)\n",
                   path.c_str(), l);
    }
  }
  if (!args.depth.empty()) {
    if (auto ok = write_pfm(args.depth, view_depth(last, frame)); !ok)
      return fail(ok.error().message);
    std::fprintf(said, "wrote %s (depth along the view axis, scene units; +inf: no surface)\n",
                 args.depth.c_str());
  }
  if (!args.ids.empty()) {
    if (auto ok = write_png(args.ids, object_ids(frame)); !ok) return fail(ok.error().message);
    std::fprintf(said, "wrote %s (object index + 1 in 24 bits, red the low byte; 0: none)\n",
                 args.ids.c_str());
  }
  if (options.tile_work) {
    const Heatmap map = tile_work_heatmap(frame);
    if (auto ok = write_png(args.heatmap, labelled_heatmap(map)); !ok)
      return fail(ok.error().message);
    std::fprintf(args.json ? stderr : stdout,
                 "wrote %s (pixels processed | pixels updated per tile; brightest: %.1f passes "
                 "per pixel)\n",
                 args.heatmap.c_str(), map.passes_at_top);
  }
  if (!args.light_map.empty()) {
    const Image map = light_map_image(scene_at_frame(scene, args.frames - 1), frame);
    if (auto ok = write_png(args.light_map, map); !ok) return fail(ok.error().message);
    std::fprintf(args.json ? stderr : stdout,
                 "wrote %s (the light that reaches each surface, all lights at full = white)\n",
                 args.light_map.c_str());
  }
  if (args.stats && !args.json)
    print_stats(frame.stats, options, (*renderer)->backend().counts_work());
  if (args.json) {  // the last frame's figures, for scripts
    const FrameStats& s = frame.stats;
    nlohmann::json out = to_json(options);
    out.update({{"scene", scene.name},
                {"backend", std::string((*renderer)->backend().name())},
                {"frames", args.frames},
                {"depth_ms", s.ms_depth},
                {"volumes_ms", s.ms_volumes},
                {"counts_ms", s.ms_counts},
                {"shade_ms", s.ms_shade},
                {"readback_ms", s.ms_readback},
                {"triangles", s.triangles},
                {"volume_primitives", s.volume_primitives}});
    out.update(cc_json(s));
    out.update(nlohmann::json::object({occlusion_json(s)}));
    if ((*renderer)->backend().counts_work()) out["count_pass"] = to_json(s.counts);
    std::cout << out.dump(2) << "\n";
  }
  return 0;
}

}  // namespace

void add_render_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene with exact shadows to a PNG");
  add_frame_options(cmd, args->frame);
  add_frame_number_option(cmd, args->frame);
  cmd->add_option("--out", args->out, "PNG file to write")->capture_default_str();
  cmd->add_flag("--stats", args->stats, "Print the frame's timings and counters");
  cmd->add_flag("--json", args->json,
                "Print the last frame's timings and counters as one JSON object (CC shadow "
                "volumes' among them: casters culled, volume segments, queries, fill)");
  cmd->add_flag("--show-volumes", args->show_volumes,
                "Draw the shadow volumes' edges over the image (one colour per light)");
  cmd->add_option("--heatmap", args->heatmap,
                  "Also write a PNG of the count passes' work per 8x8 tile: pixels processed and "
                  "pixels updated, over the scene (soft backend)");
  cmd->add_option("--light-map", args->light_map,
                  "Also write a PNG of the light intensity map: the light that reaches each "
                  "surface through the casters (coloured where they are transparent)");
  cmd->add_option("--mask", args->mask,
                  "Also write each light's shadow mask, an 8-bit grey PNG (F.png for one light, "
                  "F-L.png for light L of several): 255 lit, 0 in shadow, 128 where the surface "
                  "faces away from the light or there is none");
  cmd->add_option("--depth", args->depth,
                  "Also write the depth along the view axis (scene units) as a PFM; +infinity "
                  "where no surface is seen");
  cmd->add_option("--ids", args->ids,
                  "Also write a PNG of the object seen at each pixel: its index + 1 in 24 bits "
                  "(red the low byte), 0 where none");
  cmd->add_option("--samples", args->samples,
                  "Samples per pixel of the picture (--out): 1, 4, 9, 16, 25, 36, 49 or 64, a k x "
                  "k grid in each pixel; masks, depth and ids stay exact at the pixel centres")
      ->capture_default_str();
  cmd->add_option("--frames", args->frames,
                  "Render frames 0 .. N-1 of the scene's animation; write the last")
      ->capture_default_str();
  cmd->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace shadowvol::cli
