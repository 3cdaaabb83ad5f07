// The mesh arguments shared by every command that loads a mesh:
//   MESH [--q Q] [--scalar NAME] [--association A]; no MESH = the embedded
//   default mesh.
#pragma once

#include <string>

#include "geometry/tets/io/mesh_io.h"

namespace CLI {
class App;
}

namespace zs {

struct MeshSource {
  std::string path;  // empty = embedded default
  ReadOptions opt;
  std::string association;  // --association, parsed by load()

  // Registers the positional MESH (required or optional), --q, --scalar and --association.
  void add_options(CLI::App& cmd, bool required);
  TetMesh load() const;
  // Throws when --q, --scalar or --association is given for an input they do not apply to.
  void check_applies() const;
  std::string display_name() const { return path.empty() ? "<embedded default>" : path; }
};

}  // namespace zs
