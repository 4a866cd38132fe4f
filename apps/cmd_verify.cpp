// shadowvol verify: a frame against the ray-traced reference, per pixel.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "image_file.h"
#include "output_file.h"
#include "render/frame_json.h"
#include "trace/reference.h"
#include "verify/verify.h"

namespace shadowvol::cli {
namespace {

struct VerifyArgs {
  FrameArgs frame{"demo", "auto", "auto", "480x270"};
  std::string diff;
  std::string reference = "embree";
  bool json = false;
};

std::string object_name(const Scene& scene, std::int32_t object) {
  return object >= 0 && static_cast<std::size_t>(object) < scene.objects.size()
             ? scene.objects[static_cast<std::size_t>(object)].name
             : "";
}

int run(const VerifyArgs& args) {
  const auto reference_kind = parse_reference(args.reference);
  if (!reference_kind) return fail(reference_kind.error().message, kVerifyError);
  auto resolved = resolve(args.frame);
  if (!resolved) return fail(resolved.error().message, kVerifyError);
  RenderOptions options = resolved->options;
  options.count_fill = args.json;        // the JSON carries the volumes' fill
  options.record_facing = true;          // compared too: a shading input no mask shows
  const Scene& scene = resolved->scene;  // at --frame
  if (auto ok = check_outputs({args.diff}, {args.frame.scene}); !ok)
    return fail(ok.error().message, kVerifyError);
  auto renderer = make_frame_renderer(*resolved, options);
  if (!renderer) return fail(renderer.error().message, kVerifyError);
  const std::string backend((*renderer)->backend().name());
  StatusLine status;  // on a terminal only: what verify is doing, and how far along
  const Progress progress = [&status](std::string_view doing, float fraction) {
    status.show(std::string(doing) + " " + std::to_string(int(fraction * 100.0f)) + "%");
  };
  status.show("rendering " + scene.name + " on the " + backend + " backend");
  const Frame frame = (*renderer)->render(scene, options);
  auto reference =
      reference_frame(scene, options.width, options.height, *reference_kind, progress);
  if (!reference) return fail(reference.error().message, kVerifyError);
  status.show("comparing");
  const Comparison c = compare(frame, *reference, progress);
  status.clear();
  const bool glass = has_transparent_casters(scene);
  if (c.pixels_compared == 0)  // a comparison of nothing proves nothing
    return fail(
        "nothing to compare: no visible surface faces a light (check the camera and the "
        "lights of " +
            scene.name + ")",
        kVerifyError);
  if (!args.diff.empty())
    if (auto ok = write_png(args.diff, diff_image(frame, c)); !ok)
      return fail(ok.error().message, kVerifyError);
  if (args.json) {
    nlohmann::json out = to_json(options);
    out.update({{"scene", scene.name},
                {"backend", backend},
                {"frame", args.frame.frame},
                {"pixels_compared", c.pixels_compared},
                {"mismatched", c.mismatched},
                {"mismatched_outside_band", c.mismatched_outside_band},
                {"outside_band_near_plane_shadowed", c.outside_band_near_plane_shadowed},
                {"reference", to_string(*reference_kind)},
                {"transparent_casters", glass},
                {"max_light_error", c.max_light_error},
                {"max_light_error_outside_band", c.max_light_error_outside_band}});
    nlohmann::json listed = nlohmann::json::array();
    for (const Mismatch& m : c.outside_band)
      listed.push_back({{"x", m.x},
                        {"y", m.y},
                        {"light", m.light},
                        {"layer", m.glass ? "glass" : "opaque"},
                        {"differs", to_string(m.difference)},
                        {"object", object_name(scene, m.object)},
                        {"reference_object", object_name(scene, m.reference_object)},
                        {"face", m.face},
                        {"reference_face", m.reference_face},
                        {"shadowed", m.shadowed},
                        {"near_plane_shadowed", m.near_plane_shadowed},
                        {"reference_shadowed", m.reference_shadowed}});
    out["outside_band"] = listed;
    out.update(cc_json(frame.stats));
    out.update(nlohmann::json::object({occlusion_json(frame.stats)}));
    std::cout << out.dump(2) << "\n";
  } else {
    char light[160] = "";
    if (glass)
      std::snprintf(light, sizeof light,
                    "; light through transparent casters off by at most %.2g outside the band "
                    "(%.2g allowed; %.2g within it)",
                    c.max_light_error_outside_band, kLightTolerance, c.max_light_error);
    char near[200] = "";
    if (c.outside_band_near_plane_shadowed > 0)
      std::snprintf(near, sizeof near,
                    " (%zu of them where the near plane lies in a shadow, which z-pass counts "
                    "from)",
                    c.outside_band_near_plane_shadowed);
    const std::string versus = *reference_kind == Reference::brute
                                   ? "the brute-force reference"
                                   : "the reference";
    std::printf(
        "%s, %s, %s backend, %dx%d: %zu pixels compared, %zu mismatched, %zu outside the "
        "one-pixel band%s%s: %s %s\n",
        scene.name.c_str(), method_label(options).c_str(), backend.c_str(), options.width,
        options.height, c.pixels_compared, c.mismatched, c.mismatched_outside_band, near, light,
        c.mismatched_outside_band == 0 ? "matches" : "DIFFERS from", versus.c_str());
  }
  return c.mismatched_outside_band == 0 ? 0 : 1;
}

}  // namespace

void add_verify_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<VerifyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "verify", "Render a scene and compare its shadows per pixel with the ray-traced reference");
  add_frame_options(cmd, args->frame);
  add_frame_number_option(cmd, args->frame);
  cmd->add_option("--diff", args->diff, "Write the mismatches over the scene to this PNG");
  cmd->add_option("--reference", args->reference,
                  "embree (the reference, ray traced by Embree) or brute (every ray against "
                  "every triangle in double precision, written apart from it: small scenes)")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "Print one JSON object");
  cmd->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace shadowvol::cli
