#include "cli/mesh_source.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <stdexcept>

#include "app/option_checks.h"
#include "geometry/tets/default_mesh.h"
#include "geometry/spheres/sphere_io.h"
#include "geometry/triangles/io/surface_reader.h"
#include "base/util/file_error.h"

namespace zs {

void MeshSource::add_options(CLI::App& cmd, bool required) {
  auto* o = cmd.add_option("mesh", path,
                           "Mesh file: .off, .zsm, .vtu, .vtk, .node/.ele, or a PLOT3D grid (*xyz.bin) with --q"
                           " (mesh info also reads sphere files: .pdb, .ent, .cif, .mmcif (.gz), .sph, .sphb)");
  if (required) o->required();
  cmd.add_option("--q", opt.q_path, "PLOT3D solution (q) file for a PLOT3D grid");
  cmd.add_option("--scalar", opt.scalar,
                 "Point or cell array to use (VTK), or PLOT3D function: density, velocity-magnitude, pressure, ...");
  cmd.add_option("--association", association,
                 "Where the scalar lives: auto (as stored; default), point, cell, or cell_to_point (cell data "
                 "averaged onto the points)");
}

TetMesh MeshSource::load() const {
  check_applies();
  ReadOptions o = opt;
  if (!association.empty() && !parse_association(association, &o.association))
    throw UsageError("--association must be auto, point, cell or cell_to_point");
  return path.empty() ? default_mesh() : read_mesh(path, o);
}

void MeshSource::check_applies() const {
  if (opt.scalar.empty() && opt.q_path.empty() && association.empty()) return;
  const char* o = !opt.scalar.empty() ? "--scalar" : !association.empty() ? "--association" : "--q";
  if (path.empty()) throw UsageError(std::string(o) + " applies to a mesh file, not the embedded default mesh");
  if (is_sphere_file(path)) throw UsageError(path + ": " + o + " applies to tet meshes only, and this is a sphere set");
  if (is_surface_file(path))
    throw UsageError(path + ": " + o + " applies to tet meshes only, and this is a triangle surface");
  const MeshFormat f = format_of(path);
  if (!opt.q_path.empty() && f != MeshFormat::Plot3d && f != MeshFormat::Unknown)
    throw UsageError(path + ": --q applies to PLOT3D grids only, and this is a " +
                     std::filesystem::path(path).extension().string() + " mesh");
}

}  // namespace zs
