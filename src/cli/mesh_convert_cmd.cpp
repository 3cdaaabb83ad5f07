// `zsweep mesh convert IN OUT`: any readable format to .off, .zsm, .vtu or .node/.ele.
#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/mesh_source.h"

namespace zs {

void add_mesh_convert_command(CLI::App& mesh) {
  struct Args {
    MeshSource src;
    std::string out;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = mesh.add_subcommand("convert", "Convert a mesh between formats (.off, .zsm, .vtu, .node/.ele)");
  args->src.add_options(*cmd, true);
  cmd->add_option("output", args->out, "Output file: .off, .zsm (binary, fastest to load), .vtu or .node/.ele")
      ->required();
  cmd->callback([args] {
    const TetMesh m = args->src.load();
    write_mesh(args->out, m);
    std::printf("wrote %s: %zu points, %zu tets\n", args->out.c_str(), m.num_points(), m.num_tets());
  });
}

}  // namespace zs
