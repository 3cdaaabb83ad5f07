// `zsweep mesh convert IN OUT`: any readable format to .off, .zsm, .vtu or .node/.ele.
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/mesh_source.h"
#include "geometry/tets/renumber.h"

namespace zs {

void add_mesh_convert_command(CLI::App& mesh) {
  struct Args {
    MeshSource src;
    std::string out;
    bool renumber = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = mesh.add_subcommand("convert", "Convert a mesh between formats (.off, .zsm, .vtu, .node/.ele)");
  args->src.add_options(*cmd, true);
  cmd->add_option("output", args->out, "Output file: .off, .zsm (binary, fastest to load), .vtu or .node/.ele")
      ->required();
  cmd->add_flag("--renumber", args->renumber,
                "Renumber points and tets along a Morton curve (locality: faster topology and set-up for a mesh "
                "whose numbering is scattered; docs/scaling.md)");
  cmd->callback([args] {
    TetMesh m = args->src.load();
    std::string how;
    if (args->renumber) {
      const RenumberStats st = renumber_for_locality(m);
      char b[128];
      std::snprintf(b, sizeof b, ", renumbered (id spread %.1f -> %.1f)", st.spread_before, st.spread_after);
      how = b;
    }
    write_mesh(args->out, m);
    std::printf("wrote %s: %zu points, %zu tets%s\n", args->out.c_str(), m.num_points(), m.num_tets(), how.c_str());
  });
}

}  // namespace zs
