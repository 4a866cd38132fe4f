// The shadowvol command line. Thin by design: parses arguments, calls the library, prints.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/topology.h"
#include "core/volume.h"
#include "scene/mesh_io.h"

#ifndef SHADOWVOL_VERSION
#error "SHADOWVOL_VERSION is set by CMake"
#endif

namespace {

using namespace shadowvol;

int fail(const std::string& message) {
  std::cerr << "shadowvol: error: " << message << "\n";
  return 1;
}

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
  const Generator g = resolve_generator(Generator::automatic, r);
  row("generator (auto)",
      std::string(to_string(g)) +
          (r.closed_manifold ? " (silhouette edges, weight 1)" : " (signed edge multiplicities)"));
}

// One status line on stderr, redrawn in place, only when stderr is a terminal: a person waiting
// on a large file sees it move; pipes and logs get nothing.
class StatusLine {
 public:
  StatusLine() : enabled_(isatty(STDERR_FILENO) == 1) {}
  ~StatusLine() { clear(); }
  void show(const std::string& text) {
    if (enabled_) std::cerr << "\r\033[K" << text << std::flush;
  }
  void clear() { show(""); }

 private:
  bool enabled_;
};

int inspect(const std::string& file, bool json, float weld_epsilon) {
  StatusLine status;
  status.show("reading " + file);
  auto loaded = load_mesh(file, [&](float fraction) {
    status.show("reading " + file + " " + std::to_string(static_cast<int>(fraction * 100)) + "%");
  });
  status.clear();
  if (!loaded) return fail(loaded.error().message);
  for (const std::string& w : loaded->warnings) std::cerr << "shadowvol: warning: " << w << "\n";
  status.show("building the topology of " + std::to_string(loaded->mesh.triangle_count()) +
              " triangles");
  const Topology topo = build_topology(loaded->mesh, WeldOptions{weld_epsilon});
  status.clear();
  if (json)
    std::cout << report_json(file, topo.report).dump(2) << "\n";
  else
    print_report(file, topo.report);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"shadowvol: exact stencil shadow volumes for any mesh, on the GPU and the CPU"};
  app.set_version_flag("--version", std::string("shadowvol ") + SHADOWVOL_VERSION);
  app.require_subcommand(1);

  std::string file;
  bool json = false;
  float weld = 0.0f;
  CLI::App* inspect_cmd = app.add_subcommand(
      "inspect", "Print the topology report of a mesh file and the generator auto picks for it");
  inspect_cmd->add_option("FILE", file, "Mesh file (any format assimp reads: OBJ, PLY, glTF, ...)")
      ->required();
  inspect_cmd->add_flag("--json", json, "Print one JSON object instead of a table");
  inspect_cmd->add_option("--weld", weld,
                          "Weld vertices closer than this distance (default 0: exact positions)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (inspect_cmd->parsed()) {
    if (!std::isfinite(weld) || weld < 0.0f)
      return fail("--weld: " + std::to_string(weld) + " is not a distance (a finite number >= 0)");
    return inspect(file, json, weld);
  }
  return 0;
}
