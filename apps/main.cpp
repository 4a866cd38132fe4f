// The shadowvol command line. Thin by design: each subcommand (cmd_*.cpp) parses its arguments,
// calls the library and prints.
#include <string>

#include <CLI/CLI.hpp>

#include "cli.h"

#ifndef SHADOWVOL_VERSION
#error "SHADOWVOL_VERSION is set by CMake"
#endif

int main(int argc, char** argv) {
  using namespace shadowvol::cli;
  CLI::App app{"shadowvol: exact stencil shadow volumes for any mesh, on the GPU and the CPU"};
  app.set_version_flag("--version", std::string("shadowvol ") + SHADOWVOL_VERSION);
  app.require_subcommand(1);
  int exit_code = 0;
  add_inspect_command(app, exit_code);
  add_render_command(app, exit_code);
  add_verify_command(app, exit_code);
  add_view_command(app, exit_code);
  add_bench_command(app, exit_code);
  add_info_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    fail(std::string(e.what()) + " (run with --help for the options)");
    return kUsageError;
  }
  return exit_code;
}
