// zsweep: one executable, subcommands registered by src/cli/*_cmd.cpp.
#include <exception>
#include <iostream>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <CLI/CLI.hpp>

#include "app/option_checks.h"
#include "cli/commands.h"
#include "mpi/mpi_env.h"
#include "base/util/temp_registry.h"

int main(int argc, char** argv) {
#if defined(__GLIBC__)
  // Each frame (--frames, benchmarks) allocates and frees the same large
  // buffers. By default glibc hands them back to the kernel and then
  // faults them in again, zeroed, for the next frame, and its adaptive
  // thresholds take several frames to settle. Keep freed memory for reuse
  // instead: this process exits when its frames are done.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
  // Ctrl-C, kill, a closed terminal or a crash: remove the temporaries of
  // unfinished outputs (docs/robustness.md) before dying of the signal.
  zs::install_temp_cleanup();
  CLI::App app{"zsweep: direct volume rendering of tetrahedral meshes (ZSweep lineage)"};
  app.set_version_flag("--version", "zsweep 0.1.0");
  app.require_subcommand(1);

  CLI::App* mesh = app.add_subcommand("mesh", "Inspect, convert and generate tet meshes");
  mesh->require_subcommand(1);
  zs::add_mesh_info_command(*mesh);
  zs::add_mesh_convert_command(*mesh);
  zs::add_mesh_generate_command(*mesh);
  zs::add_render_command(app);
  zs::add_bench_command(app);
  zs::add_compare_command(app);
  zs::add_reference_command(app);
  zs::add_spheres_command(app);
  // Every numeric option, whoever registered it: a word is "not a number".
  zs::check_every_number(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // A usage error: one line like every other error, exit code 2.
    std::cerr << "zsweep: error: " << e.what() << " (see --help)\n";
    return 2;
  } catch (const zs::UsageError& e) {
    // Found after parsing (an option that does not apply to the input): still a usage error.
    if (zs::mpi_active()) return zs::mpi_exit_on_error(e) ? 2 : 0;
    std::cerr << "zsweep: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    // Under `render --mpi` the ranks settle a failure together (src/mpi/mpi_env.h).
    if (zs::mpi_active()) return zs::mpi_exit_on_error(e);
    // Readers and writers already name the file (and line); one line, no trace.
    std::cerr << "zsweep: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
