#include "geometry/tets/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "geometry/tets/io/off_io.h"
#include "geometry/tets/io/tetgen_io.h"
#include "geometry/tets/io/vtk_io.h"
#include "geometry/tets/io/zsm_io.h"
#include "geometry/triangles/surface_file.h"
#include "base/util/file_error.h"
#include "base/util/file_name.h"
#include "base/util/input_file.h"
#include "base/util/atomic_file.h"

namespace zs {

namespace fs = std::filesystem;

const char* to_string(ScalarAssociation a) {
  switch (a) {
    case ScalarAssociation::Auto: return "auto";
    case ScalarAssociation::Point: return "point";
    case ScalarAssociation::Cell: return "cell";
    case ScalarAssociation::CellToPoint: return "cell_to_point";
  }
  return "auto";
}

bool parse_association(const std::string& s, ScalarAssociation* out) {
  for (ScalarAssociation a : {ScalarAssociation::Auto, ScalarAssociation::Point, ScalarAssociation::Cell,
                              ScalarAssociation::CellToPoint})
    if (s == to_string(a)) {
      *out = a;
      return true;
    }
  return false;
}

namespace {

// A file with one scalar of a fixed association, read with opt.association.
void apply_association(TetMesh& m, const ReadOptions& opt, const std::string& path) {
  const std::string name = m.scalar_name.empty() ? "scalar" : m.scalar_name;
  if (m.has_cell_scalars()) {
    if (opt.association == ScalarAssociation::Point)
      throw FileError(path, "scalar '" + name + "' is cell data, and association is 'point' (use 'cell' or 'cell_to_point')");
    if (opt.association == ScalarAssociation::CellToPoint) average_cell_scalars_onto_points(m);
  } else if (m.has_scalars() && opt.association == ScalarAssociation::Cell) {
    throw FileError(path, "scalar '" + name + "' is point data, and association is 'cell'");
  }
}

}  // namespace

MeshFormat format_of(const std::string& path, const ReadOptions& opt) {
  const std::string e = lower_extension(path);
  if (e == ".off") return MeshFormat::Off;
  if (e == ".zsm") return MeshFormat::Zsm;
  if (e == ".vtu") return MeshFormat::Vtu;
  if (e == ".vtk") return MeshFormat::VtkLegacy;
  if (e == ".node" || e == ".ele") return MeshFormat::TetGen;
  if (!opt.q_path.empty() || e == ".bin" || e == ".xyz" || e == ".x") return MeshFormat::Plot3d;
  return MeshFormat::Unknown;
}

TetMesh read_mesh(const std::string& path, const ReadOptions& opt) {
  require_input_file(path, "a mesh file");
  // Said before any reader runs: the tet OFF reader would otherwise stop at
  // the keyword, and .obj/.ply/.stl be an unknown format.
  if (is_surface_file(path))
    throw FileError(path, "a triangle surface, not a tetrahedral mesh (this command takes tet meshes: .off without "
                          "the OFF keyword, .zsm, .vtu, .vtk, .node/.ele, PLOT3D; render and mesh info take surfaces)");
  const MeshFormat format = format_of(path, opt);
  if (!opt.q_path.empty() && format != MeshFormat::Plot3d)
    throw FileError(path, "a PLOT3D solution file (" + opt.q_path + ") applies to PLOT3D grids only, and this is a " +
                              lower_extension(path) + " mesh");
  if (format == MeshFormat::Off || format == MeshFormat::TetGen || format == MeshFormat::Zsm) {
    // One scalar at most: a name is either it or a mistake.
    TetMesh m = format == MeshFormat::Off   ? read_off(path)
                : format == MeshFormat::Zsm ? read_zsm(path)
                                            : read_tetgen(path);
    const std::string have = m.scalar_name.empty() ? "scalar" : m.scalar_name;
    if (!opt.scalar.empty() && opt.scalar != have)
      throw FileError(path, "no array named '" + opt.scalar + "'; available: " +
                                (m.has_scalars() ? have + " (point)"
                                 : m.has_cell_scalars() ? have + " (cell)"
                                                        : std::string("none")));
    apply_association(m, opt, path);
    return m;
  }
  switch (format) {
    case MeshFormat::Vtu:
    case MeshFormat::VtkLegacy:
      return read_vtk(path, opt);
    case MeshFormat::Plot3d:
      if (opt.q_path.empty())
        throw FileError(path, "PLOT3D grid needs its solution file (--q FILE)");
      return read_plot3d(path, opt);
    case MeshFormat::Off:
    case MeshFormat::Zsm:
    case MeshFormat::TetGen:  // read above
    case MeshFormat::Unknown:
      break;
  }
  throw FileError(path, "unknown mesh format (expected .off, .zsm, .vtu, .vtk, .node/.ele, or PLOT3D with --q)");
}

void write_mesh(const std::string& path, const TetMesh& m) {
  const MeshFormat f = format_of(path);
  if (f == MeshFormat::TetGen) {
    // Two files from one base; write both under temporary names, then rename.
    AtomicFile node(fs::path(path).replace_extension(".node").string());
    AtomicFile ele(fs::path(path).replace_extension(".ele").string());
    try {
      write_tetgen(node.temp_path(), m);
    } catch (const FileError& e) {
      throw FileError(ele.name_final(node.name_final(e.what())));  // name the outputs, not their temporaries
    }
    // write_tetgen wrote <tmpbase>.node and <tmpbase>.ele; the ele temp name
    // differs from AtomicFile's pick, so move it there first.
    fs::rename(fs::path(node.temp_path()).replace_extension(".ele"), ele.temp_path());
    ele.commit();
    node.commit();
    return;
  }
  if (f == MeshFormat::Zsm) return write_zsm(path, m);  // atomic by itself
  AtomicFile out(path);
  if (f != MeshFormat::Off && f != MeshFormat::Vtu)
    throw FileError(path, "cannot write this format (expected .off, .zsm, .vtu or .node/.ele)");
  try {
    if (f == MeshFormat::Off) write_off(out.temp_path(), m);
    else write_vtu(out.temp_path(), m);
  } catch (const FileError& e) {
    throw FileError(out.name_final(e.what()));  // name the output, not its temporary
  }
  out.commit();
}

}  // namespace zs
