// shadowvol inspect: the topology report of a mesh file, and what each generator makes of it.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "core/topology.h"
#include "core/volume.h"
#include "scene/mesh_io.h"

namespace shadowvol::cli {
namespace {

nlohmann::json report_json(const std::string& file, const TopologyReport& r) {
  return {
      {"file", file},
      {"input_vertices", r.input_vertices},
      {"vertices", r.vertices},
      {"triangles", r.triangles},
      {"edges", r.edges},
      {"boundary_edges", r.boundary_edges},
      {"nonmanifold_edges", r.nonmanifold_edges},
      {"inconsistent_edges", r.inconsistent_edges},
      {"degenerate_triangles", r.degenerate_triangles},
      {"components", r.components},
      {"closed_manifold", r.closed_manifold},
      {"parts_wound_outwards", r.parts_wound_outwards},
      {"generator", std::string(to_string(resolve_generator(Generator::automatic, r)))},
  };
}

void print_report(const std::string& file, const TopologyReport& r) {
  auto row = [](const char* name, const std::string& value) {
    std::printf("  %-22s %s\n", name, value.c_str());
  };
  std::printf("%s\n", file.c_str());
  row("vertices", std::to_string(r.vertices) + " welded from " + std::to_string(r.input_vertices));
  row("triangles", std::to_string(r.triangles));
  row("edges", std::to_string(r.edges));
  row("boundary edges", std::to_string(r.boundary_edges));
  row("non-manifold edges", std::to_string(r.nonmanifold_edges));
  row("inconsistent edges", std::to_string(r.inconsistent_edges));
  row("degenerate triangles", std::to_string(r.degenerate_triangles));
  row("components", std::to_string(r.components));
  row("closed 2-manifold", r.closed_manifold ? "yes" : "no");
  row("parts wound outwards", std::to_string(r.parts_wound_outwards) +
                                  " (closed: the depth pass leaves out their back faces)");
  const Generator g = resolve_generator(Generator::automatic, r);
  row("generator (auto)",
      std::string(to_string(g)) +
          (r.closed_manifold ? " (silhouette edges, weight 1)" : " (signed edge multiplicities)"));
}

// "x,y,z,w" -> a homogeneous light, or an error naming what is wrong.
Expected<glm::vec4> parse_light(const std::string& text) {
  glm::vec4 light(0.0f);
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 4; ++i) {
    if (i > 0 && (p == end || *p++ != ','))
      return make_error("--light: '" + text + "' is not four numbers x,y,z,w");
    const auto [next, ec] = std::from_chars(p, end, light[i]);
    if (ec != std::errc()) return make_error("--light: '" + text + "' is not four numbers x,y,z,w");
    p = next;
  }
  if (p != end) return make_error("--light: '" + text + "' has more than four numbers");
  if (auto ok = check_light(light); !ok) return make_error("--light: " + ok.error().message);
  return light;
}

// What each generator makes of the mesh under one light.
struct VolumeStats {
  Generator generator;
  std::size_t side_quads = 0;
  std::int64_t unit_quads = 0;  // sum of |weight|: the draws a +-1 stencil backend needs
  int max_weight = 0;
  std::size_t light_caps = 0, dark_caps = 0;
};

std::vector<VolumeStats> volume_stats(const Topology& topo, const glm::vec4& light) {
  std::vector<VolumeStats> out;
  VolumeScratch scratch;
  VolumeBuffer volume;
  for (Generator g : {Generator::standard, Generator::robust, Generator::multiplicity}) {
    if (!check_generator(g, topo.report, "").ok()) continue;
    build_volume(topo, light, {g, true}, scratch, volume);
    VolumeStats s{g};
    s.side_quads = volume.sides.size();
    for (std::int32_t w : volume.sides.weights) {
      s.unit_quads += std::abs(w);
      s.max_weight = std::max(s.max_weight, std::abs(w));
    }
    s.light_caps = volume.light_caps.size();
    s.dark_caps = volume.dark_caps.size();
    out.push_back(s);
  }
  return out;
}

int inspect(const std::string& file, bool json, float weld_epsilon,
            const std::optional<glm::vec4>& light) {
  StatusLine status;
  status.show("reading " + file);
  auto loaded = load_mesh(file, [&](float fraction) {
    status.show("reading " + file + " " + std::to_string(static_cast<int>(fraction * 100)) + "%");
  });
  status.clear();
  if (!loaded) return fail(loaded.error().message);
  for (const std::string& w : loaded->warnings) warn(w);
  status.show("building the topology of " + std::to_string(loaded->mesh.triangle_count()) +
              " triangles");
  const Topology topo = build_topology(loaded->mesh, WeldOptions{weld_epsilon});
  status.clear();
  std::vector<VolumeStats> volumes;
  if (light) volumes = volume_stats(topo, *light);
  if (json) {
    nlohmann::json out = report_json(file, topo.report);
    if (light) {
      out["light"] = {light->x, light->y, light->z, light->w};
      for (const VolumeStats& v : volumes)
        out["volumes"][std::string(to_string(v.generator))] = {{"side_quads", v.side_quads},
                                                               {"unit_weight_quads", v.unit_quads},
                                                               {"max_weight", v.max_weight},
                                                               {"light_caps", v.light_caps},
                                                               {"dark_caps", v.dark_caps}};
    }
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  print_report(file, topo.report);
  if (light) {
    std::printf("\nvolumes under the %s light (%g, %g, %g, %g)\n",
                light->w == 0.0f ? "directional" : "point", light->x, light->y, light->z, light->w);
    std::printf("  %-13s %11s %17s %11s %11s %10s\n", "generator", "side quads", "as +-1 quads",
                "max |w|", "light caps", "dark caps");
    for (const VolumeStats& v : volumes)
      std::printf("  %-13s %11zu %17lld %11d %11zu %10zu\n",
                  std::string(to_string(v.generator)).c_str(), v.side_quads,
                  static_cast<long long>(v.unit_quads), v.max_weight, v.light_caps, v.dark_caps);
  }
  return 0;
}

struct InspectArgs {
  std::string file;
  bool json = false;
  float weld = 0.0f;
  std::string light;
};

int run(const InspectArgs& args) {
  if (!std::isfinite(args.weld) || args.weld < 0.0f)
    return fail("--weld: " + std::to_string(args.weld) +
                " is not a distance (a finite number >= 0)");
  std::optional<glm::vec4> light;
  if (!args.light.empty()) {
    auto parsed = parse_light(args.light);
    if (!parsed) return fail(parsed.error().message);
    light = *parsed;
  }
  return inspect(args.file, args.json, args.weld, light);
}

}  // namespace

void add_inspect_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<InspectArgs>();
  CLI::App* cmd = app.add_subcommand(
      "inspect", "Print the topology report of a mesh file and the generator auto picks for it");
  cmd->add_option("FILE", args->file, "Mesh file (any format assimp reads: OBJ, PLY, glTF, ...)")
      ->required();
  cmd->add_flag("--json", args->json, "Print one JSON object instead of a table");
  cmd->add_option("--weld", args->weld,
                  "Weld vertices closer than this distance (default 0: exact positions)");
  cmd->add_option("--light", args->light,
                  "Also build the shadow volumes for this light, x,y,z,w in the mesh's space "
                  "(w = 1 point light, w = 0 directional), and count what each generator makes");
  cmd->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace shadowvol::cli
