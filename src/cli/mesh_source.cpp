#include "cli/mesh_source.h"

#include <CLI/CLI.hpp>

#include "mesh/default_mesh.h"

namespace zs {

void MeshSource::add_options(CLI::App& cmd, bool required) {
  auto* o = cmd.add_option("mesh", path,
                           "Mesh file: .off, .vtu, .vtk, .node/.ele, or a PLOT3D grid (*xyz.bin) with --q"
                           " (mesh info also reads sphere files: .pdb, .ent, .sph)");
  if (required) o->required();
  cmd.add_option("--q", opt.q_path, "PLOT3D solution (q) file for a PLOT3D grid");
  cmd.add_option("--scalar", opt.scalar,
                 "Point array to use (VTK), or PLOT3D function: density, velocity-magnitude, pressure, ...");
}

TetMesh MeshSource::load() const { return path.empty() ? default_mesh() : read_mesh(path, opt); }

}  // namespace zs
