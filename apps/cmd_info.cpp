// shadowvol info: the OpenGL driver a headless context gets, and the features the backend uses.
#include <cstdio>
#include <iostream>
#include <memory>
#include <utility>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "gl/context.h"

namespace shadowvol::cli {
namespace {

int run(bool json) {
  auto context = gl::Context::create_headless();
  if (!context) return fail("cannot create an OpenGL context: " + context.error().message);
  const gl::Info i = context->info();
  const gl::Features& f = i.features;
  const std::pair<const char*, bool> features[] = {{"depth_clamp", f.depth_clamp},
                                                   {"two_sided_stencil", f.two_sided_stencil},
                                                   {"stencil_wrap", f.stencil_wrap},
                                                   {"geometry_shaders", f.geometry_shaders},
                                                   {"occlusion_queries", f.occlusion_queries},
                                                   {"depth_bounds", f.depth_bounds},
                                                   {"integer_targets", f.integer_targets},
                                                   {"clip_control", f.clip_control}};
  if (json) {
    nlohmann::json out{{"vendor", i.vendor},
                       {"renderer", i.renderer},
                       {"version", i.version},
                       {"fallbacks", f.fallbacks}};
    for (const auto& [name, has] : features) out["features"][name] = has;
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("OpenGL   %s\nrenderer %s\nvendor   %s\n", i.version.c_str(), i.renderer.c_str(),
              i.vendor.c_str());
  for (const auto& [name, has] : features) std::printf("  %-18s %s\n", name, has ? "yes" : "no");
  for (const std::string& line : f.fallbacks) std::printf("fallback: %s\n", line.c_str());
  return 0;
}

}  // namespace

void add_info_command(CLI::App& app, int& exit_code) {
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "info", "The OpenGL driver a headless context gets, and the features the backend uses");
  cmd->add_flag("--json", *json, "Print one JSON object");
  cmd->callback([json, &exit_code] { exit_code = run(*json); });
}

}  // namespace shadowvol::cli
