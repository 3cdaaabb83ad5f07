// `zsweep mesh info [MESH] [--json]`: counts, topology and validation report;
// for sphere files (molecules, .sph, .sphb) the sphere report of sphere_info.h,
// for triangle surfaces the surface report of surface_info.h.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/option_checks.h"
#include "cli/commands.h"
#include "cli/mesh_source.h"
#include "cli/sphere_info.h"
#include "cli/surface_info.h"
#include "geometry/tets/topology.h"
#include "geometry/tets/validate.h"
#include "geometry/spheres/sphere_io.h"
#include "geometry/triangles/io/surface_reader.h"
#include "render/volume/volume_memory.h"

namespace zs {

namespace {

struct InfoArgs {
  MeshSource src;
  bool json = false;
  double eps = 1e-10;
  MoleculeOptions molecule;
  bool no_waters = false, no_hydrogens = false;

  // --model, --no-waters, --no-hydrogens apply to molecule files only.
  void check_molecule_options() const {
    std::vector<std::string> given;
    if (!molecule.model.empty()) given.push_back("--model");
    if (no_waters) given.push_back("--no-waters");
    if (no_hydrogens) given.push_back("--no-hydrogens");
    const SceneKind kind = is_sphere_file(src.path)    ? SceneKind::Spheres
                           : is_surface_file(src.path) ? SceneKind::Surfaces
                                                       : SceneKind::Volume;
    check_option_scope(given, kind, src.display_name(), false, is_molecule_file(src.path));
  }
};

// What a volume render of this mesh holds (volume_memory.h).
VolumeMemory memory_of(const TetMesh& m, const Topology& t) {
  return estimate_volume_memory(m.num_points(), m.num_tets(), m.has_scalars(), t.num_faces(), m.has_cell_scalars());
}

void print_text(const std::string& name, const TetMesh& m, const Topology& t, const ValidationReport& r,
                double scalar_lo, double scalar_hi, double ms) {
  const Bounds b = bounds_of(m);
  auto line = [](const char* key, const std::string& v) { std::printf("%-27s %s\n", key, v.c_str()); };
  auto n = [](size_t v) { return std::to_string(v); };
  line("mesh:", name);
  line("points:", n(m.num_points()));
  line("tets:", n(m.num_tets()));
  line("faces:", n(t.num_faces()));
  line("boundary faces:", n(t.num_boundary_faces));
  line("interior faces:", n(t.num_faces() - t.num_boundary_faces));
  line("orientation:", n(r.positive_tets) + " positive, " + n(r.negative_tets) + " negative" +
                           (r.positive_tets && r.negative_tets ? " (mixed winding, handled per tet)" : ""));
  char buf[256];
  std::snprintf(buf, sizeof buf, "%zu (|6V| <= %g * longest_edge^3; %zu with a repeated vertex)",
                r.zero_volume_tets, r.zero_volume_eps, r.repeated_index_tets);
  line("zero-volume tets:", buf);
  line("non-finite tets:", n(r.nonfinite_tets));
  line("duplicate points:", n(r.duplicate_points));
  line("unused points:", n(r.unused_points));
  line("non-finite points:", n(r.nonfinite_points));
  line("non-manifold faces:", n(r.nonmanifold_faces));
  line("coincident boundary faces:", n(r.coincident_boundary_faces));
  if (!m.scalar_values().empty()) {
    std::snprintf(buf, sizeof buf, "%s%s, range [%.9g, %.9g], %zu non-finite",
                  m.scalar_name.empty() ? "(unnamed)" : m.scalar_name.c_str(),
                  m.has_cell_scalars() ? " (cell data: one value per tet)" : "", scalar_lo, scalar_hi,
                  r.nonfinite_scalars);
    line("scalar:", buf);
  } else {
    line("scalar:", "none");
  }
  std::snprintf(buf, sizeof buf, "[%.9g, %.9g, %.9g] - [%.9g, %.9g, %.9g]", b.lo.x, b.lo.y, b.lo.z, b.hi.x,
                b.hi.y, b.hi.z);
  line("bounds:", buf);
  std::snprintf(buf, sizeof buf, "%.9g", r.volume);
  line("volume:", buf);
  line("status:", r.clean() ? "clean" : "anomalies counted above");
  for (const std::string& note : m.notes) line("note:", note);
  std::snprintf(buf, sizeof buf, "%.1f ms", ms);
  line("topology + validation:", buf);
  line("render memory:", volume_memory_summary(memory_of(m, t)) + ", plus fragment pools");
}

void print_json(const std::string& name, const TetMesh& m, const Topology& t, const ValidationReport& r,
                double scalar_lo, double scalar_hi) {
  const Bounds b = bounds_of(m);
  nlohmann::json j = {
      {"mesh", name},
      {"points", m.num_points()},
      {"tets", m.num_tets()},
      {"faces", t.num_faces()},
      {"boundary_faces", t.num_boundary_faces},
      {"positive_tets", r.positive_tets},
      {"negative_tets", r.negative_tets},
      {"zero_volume_tets", r.zero_volume_tets},
      {"repeated_index_tets", r.repeated_index_tets},
      {"nonfinite_tets", r.nonfinite_tets},
      {"duplicate_points", r.duplicate_points},
      {"unused_points", r.unused_points},
      {"nonfinite_points", r.nonfinite_points},
      {"nonfinite_scalars", r.nonfinite_scalars},
      {"nonmanifold_faces", r.nonmanifold_faces},
      {"coincident_boundary_faces", r.coincident_boundary_faces},
      {"zero_volume_eps", r.zero_volume_eps},
      {"volume", r.volume},
      {"bounds", {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}}},
      {"scalar", !m.scalar_values().empty()
                     ? nlohmann::json{{"name", m.scalar_name},
                                      {"association", m.has_cell_scalars() ? "cell" : "point"},
                                      {"min", scalar_lo},
                                      {"max", scalar_hi}}
                     : nlohmann::json(nullptr)},
      {"notes", m.notes},
      {"clean", r.clean()},
  };
  const VolumeMemory mem = memory_of(m, t);
  j["render_memory"] = {{"mesh", mem.mesh},         {"topology", mem.topology}, {"topology_build", mem.topology_build},
                        {"per_view", mem.per_view}, {"peak", mem.peak()},       {"bytes_per_tet", mem.bytes_per_tet()}};
  std::cout << j.dump(2) << "\n";
}

}  // namespace

void add_mesh_info_command(CLI::App& mesh) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = mesh.add_subcommand("info", "Print counts, face topology and a validation report");
  args->src.add_options(*cmd, false);
  cmd->add_flag("--json", args->json, "Print the report as JSON");
  CLI::Option* eps = cmd->add_option("--zero-volume-eps", args->eps, "Relative epsilon for zero-volume tets (|6V| <= eps*L^3)")
      ->capture_default_str()
      ->check(number_check(real_range(0, INFINITY)));
  cmd->add_option("--model", args->molecule.model, "Molecule files: the MODEL to read (its number; default: the first)");
  cmd->add_flag("--no-waters", args->no_waters, "Molecule files: leave out water molecules");
  cmd->add_flag("--no-hydrogens", args->no_hydrogens, "Molecule files: leave out hydrogen atoms");
  cmd->callback([args, eps] {
    args->src.check_applies();
    args->check_molecule_options();
    if (is_sphere_file(args->src.path)) {
      if (eps->count())
        throw UsageError(args->src.path + ": --zero-volume-eps applies to tet meshes only, and this is a sphere set");
      MoleculeOptions m = args->molecule;
      m.waters = !args->no_waters;
      m.hydrogens = !args->no_hydrogens;
      return print_sphere_info(args->src.path, args->json, m);
    }
    if (is_surface_file(args->src.path)) {
      if (eps->count())
        throw UsageError(args->src.path + ": --zero-volume-eps applies to tet meshes only, and this is a triangle surface");
      return print_surface_info(args->src.path, args->json);
    }
    const TetMesh m = args->src.load();
    const auto t0 = std::chrono::steady_clock::now();
    const Topology topo = build_topology(m);
    const ValidationReport rep = validate(m, topo, args->eps);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (double s : m.scalar_values())
      if (std::isfinite(s)) lo = std::min(lo, s), hi = std::max(hi, s);
    if (args->json)
      print_json(args->src.display_name(), m, topo, rep, lo, hi);
    else
      print_text(args->src.display_name(), m, topo, rep, lo, hi, ms);
  });
}

}  // namespace zs
