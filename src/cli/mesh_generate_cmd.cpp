// `zsweep mesh generate`: synthetic shapes (TetGen, target tet count), closed
// surfaces (TetGen), implicit solids and grey-level images (CGAL Mesh_3), hex
// grids split into tets (no mesher, for meshes at scale), each with a scalar
// field attached, written through zs::write_mesh.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/option_checks.h"
#include "cli/commands.h"
#include "geometry/tets/generate/cgal_mesher.h"
#include "geometry/tets/generate/grid_mesh.h"
#include "geometry/tets/generate/scalar_fields.h"
#include "geometry/tets/generate/shape_mesher.h"
#include "geometry/tets/generate/shapes.h"
#include "geometry/tets/generate/surface_io.h"
#include "geometry/tets/generate/tetgen_mesher.h"
#include "geometry/tets/generate/voxel_image.h"
#include "geometry/tets/io/mesh_io.h"

namespace zs {

namespace {

// A number check with a readable message (CLI11's PositiveNumber and Range
// write DBL_MAX out in 300 digits): v in [lo, hi], or (lo, hi] when lo_open;
// NaN and infinities never pass. `also_zero` admits 0 as an "off" value.
CLI::Validator number_in(double lo, double hi, bool lo_open, const std::string& what, bool also_zero = false) {
  return CLI::Validator(
      [=](std::string& v) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        if (v.empty() || *end != '\0') return "'" + v + "' is not a number";
        if (also_zero && x == 0) return {};
        if (!std::isfinite(x) || (lo_open ? !(x > lo) : !(x >= lo)) || !(x <= hi))
          return v + " is out of range: must be " + what;
        return {};
      },
      what);
}

// Options every generator shares.
struct Common {
  std::string out;
  std::string field;
  uint64_t seed = 1;
};

void add_common(CLI::App* cmd, Common& c, const std::string& default_field) {
  c.field = default_field;
  cmd->add_option("-o,--output", c.out, "Output mesh (.off, .zsm, .vtu or .node/.ele)")->required();
  std::vector<std::string> fields = field_names();
  fields.push_back("none");
  cmd->add_option("--field", c.field, "Scalar field to attach")
      ->check(CLI::IsMember(fields))
      ->capture_default_str();
  cmd->add_option("--seed", c.seed,
                  "Seed for random choices (blob shape, fields, Mesh_3, grid jitter): same seed, same mesh")
      ->capture_default_str();
}

// Fail on a bad output name before spending minutes meshing.
void check_output(const std::string& out) {
  MeshFormat f = format_of(out);
  if (f != MeshFormat::Off && f != MeshFormat::Zsm && f != MeshFormat::Vtu && f != MeshFormat::TetGen)
    throw std::invalid_argument(out + ": cannot write this format (expected .off, .zsm, .vtu or .node/.ele)");
}

using Clock = std::chrono::steady_clock;

// Applies the field, writes, and says how long each took: at 100 M tets
// (grid) the write is most of the time.
void finish(TetMesh& m, const Common& c, const std::string& what, Clock::time_point t0,
            const VoxelImage* img = nullptr) {
  if (c.field != "none") apply_field(m, c.field, c.seed, img);
  const Clock::time_point t1 = Clock::now();
  write_mesh(c.out, m);
  const double gen = std::chrono::duration<double>(t1 - t0).count();
  const double wr = std::chrono::duration<double>(Clock::now() - t1).count();
  std::cout << c.out << ": " << m.num_points() << " points, " << m.num_tets() << " tets (" << what
            << (c.field != "none" ? ", field " + c.field : std::string()) << ", " << std::fixed
            << std::setprecision(2) << "generated in " << gen << " s, written in " << wr << " s)\n";
}

// "target 1000, +1.2 %": the count against the --tets asked for.
std::string target_summary(const ShapeMeshReport& r) {
  char b[64];
  std::snprintf(b, sizeof b, "target %zu, %+.1f %%", r.target, 100 * r.error());
  return b;
}

std::string target_miss(const ShapeMeshOptions& o, const ShapeMeshReport& r) {
  char b[256];
  if (r.at_floor)
    std::snprintf(b, sizeof b, "%s: %zu tets, %+.0f %% over --tets %zu: the shape needs about that many at --quality %g",
                  o.shape.c_str(), r.tets, 100 * r.error(), r.target, o.quality);
  else
    std::snprintf(b, sizeof b,
                  "%s: %zu tets, %+.0f %% off --tets %zu (the closest of %d TetGen runs; small targets come in steps)",
                  o.shape.c_str(), r.tets, 100 * r.error(), r.target, r.runs);
  return b;
}

struct SizeOpts {
  std::optional<double> size, facet_angle, facet_size, facet_distance, cell_radius_edge, cell_size;
  size_t max_points = Mesh3Criteria().max_points;
};

void add_size_opts(CLI::App* cmd, SizeOpts& s, const std::string& size_help) {
  // Mesh_3 does not terminate for angles above 30 degrees or radius-edge
  // ratios below 2.
  const CLI::Validator positive = number_in(0, INFINITY, true, "a positive number");
  cmd->add_option("--size", s.size, size_help)->check(positive);
  cmd->add_option("--facet-angle", s.facet_angle, "Min surface facet angle, degrees (default 30)")
      ->check(number_in(0, 30, true, "in (0, 30]"));
  cmd->add_option("--facet-size", s.facet_size, "Surface Delaunay ball radius bound (default --size)")->check(positive);
  cmd->add_option("--facet-distance", s.facet_distance, "Surface approximation error (default --size/4)")
      ->check(positive);
  cmd->add_option("--cell-radius-edge", s.cell_radius_edge, "Tet radius-edge ratio bound (default 2)")
      ->check(number_in(2, INFINITY, false, "at least 2"));
  cmd->add_option("--cell-size", s.cell_size, "Tet circumradius bound (default --size)")->check(positive);
  cmd->add_option("--max-points", s.max_points,
                  "Refuse sizes that need more points, stop refining there (bounds time and memory)")
      ->check(number_in(4, 1e8, false, "in [4, 100000000]"))
      ->capture_default_str();
}

Mesh3Criteria criteria(const SizeOpts& s, double default_size, uint64_t seed) {
  Mesh3Criteria c = Mesh3Criteria::from_size(s.size.value_or(default_size));
  if (s.facet_angle) c.facet_angle = *s.facet_angle;
  if (s.facet_size) c.facet_size = *s.facet_size;
  if (s.facet_distance) c.facet_distance = *s.facet_distance;
  if (s.cell_radius_edge) c.cell_radius_edge = *s.cell_radius_edge;
  if (s.cell_size) c.cell_size = *s.cell_size;
  c.max_points = s.max_points;
  c.seed = seed;
  return c;
}

void add_shape_commands(CLI::App* gen) {
  for (const ShapeInfo& info : shape_catalog()) {
    CLI::App* cmd = gen->add_subcommand(info.name, "TetGen mesh: " + info.description);
    auto common = std::make_shared<Common>();
    auto opt = std::make_shared<ShapeMeshOptions>();
    opt->shape = info.name;
    add_common(cmd, *common, "radial");
    cmd->add_option("--tets", opt->target_tets,
                    "Target tet count: within 10% from 1500 up (reruns TetGen, at most 16 times); the summary says by how much")
        ->check(number_in(1, 1e8, false, "in [1, 100000000]"))
        ->capture_default_str();
    cmd->add_option("--quality", opt->quality, "Radius-edge ratio bound (TetGen -q)")
        ->check(number_in(1.1, 100, false, "in [1.1, 100]"))
        ->capture_default_str();
    cmd->callback([common, opt] {
      check_output(common->out);
      opt->seed = common->seed;
      auto t0 = Clock::now();
      ShapeMeshReport rep;
      TetMesh m = mesh_shape(*opt, &rep);
      finish(m, *common, opt->shape + ", " + target_summary(rep), t0);
      if (std::abs(rep.error()) > opt->tolerance) std::cerr << "zsweep: warning: " << target_miss(*opt, rep) << "\n";
    });
  }
}

void add_surface_command(CLI::App* gen) {
  CLI::App* cmd = gen->add_subcommand("surface", "TetGen mesh of the volume inside a closed triangle surface");
  auto common = std::make_shared<Common>();
  auto in = std::make_shared<std::string>();
  auto opt = std::make_shared<TetgenOptions>();
  cmd->add_option("input", *in, "Closed surface (.off, .stl, .ply, .obj)")->required();
  add_common(cmd, *common, "distance");
  // TetGen's refinement is only guaranteed to stop for ratios from ~1.1.
  cmd->add_option("--quality", opt->quality, "Radius-edge ratio bound (TetGen -q; 0 = off)")
      ->check(number_in(1.1, 100, false, "0 (off) or in [1.1, 100]", true))
      ->capture_default_str();
  cmd->add_option("--max-volume", opt->max_volume, "Max tet volume (TetGen -a; 0 = none)")
      ->check(number_in(0, INFINITY, false, "0 (none) or a positive number"));
  cmd->add_option("--max-tets", opt->max_tets,
                  "Refuse a --max-volume that needs more tets, stop TetGen near there (bounds time and memory)")
      ->check(number_in(4, 1e9, false, "in [4, 1000000000]"))
      ->capture_default_str();
  cmd->add_flag("--preserve-surface", opt->preserve_surface,
                "Keep the input triangles as the boundary, no Steiner points on it (TetGen -Y)");
  cmd->callback([common, in, opt] {
    check_output(common->out);
    auto t0 = Clock::now();
    Plc plc = read_surface(*in);
    TetMesh m;
    try {
      m = tetrahedralize(plc, *opt);
    } catch (const std::exception& e) {  // TetGen's failures and the work bound alike
      throw std::runtime_error(*in + ": " + e.what());
    }
    finish(m, *common, "surface " + *in, t0);
  });
}

void add_implicit_command(CLI::App* gen) {
  CLI::App* cmd = gen->add_subcommand("implicit", "CGAL Mesh_3 mesh of an implicit solid");
  auto common = std::make_shared<Common>();
  auto name = std::make_shared<std::string>();
  auto sizes = std::make_shared<SizeOpts>();
  std::vector<std::string> names;
  for (const ImplicitShape& s : implicit_catalog()) names.push_back(s.name);
  cmd->add_option("shape", *name, "Implicit solid")->required()->check(CLI::IsMember(names));
  add_common(cmd, *common, "distance");
  add_size_opts(cmd, *sizes, "Element size for facets and cells (default 0.1; solids are ~2 across)");
  cmd->callback([common, name, sizes] {
    check_output(common->out);
    auto t0 = Clock::now();
    TetMesh m = mesh_implicit(*find_implicit(*name), criteria(*sizes, 0.1, common->seed));
    finish(m, *common, "implicit " + *name, t0);
  });
}

void add_image_command(CLI::App* gen) {
  CLI::App* cmd = gen->add_subcommand("image", "CGAL Mesh_3 mesh of a grey-level 3D image iso-region");
  auto common = std::make_shared<Common>();
  auto in = std::make_shared<std::string>();
  auto iso = std::make_shared<double>(0.0);
  auto below = std::make_shared<bool>(false);
  auto sizes = std::make_shared<SizeOpts>();
  cmd->add_option("input", *in, "3D image (.inr, .inr.gz)")->required();
  cmd->add_option("--iso", *iso, "Iso-value bounding the solid")->required();
  cmd->add_flag("--below", *below, "Mesh where the value is below --iso (default: above)");
  add_common(cmd, *common, "image");
  add_size_opts(cmd, *sizes, "Element size (default 2 voxels)");
  cmd->callback([common, in, iso, below, sizes] {
    check_output(common->out);
    auto t0 = Clock::now();
    VoxelImage img = read_voxel_image(*in);
    const double voxel = std::max({img.spacing.x, img.spacing.y, img.spacing.z});
    TetMesh m = mesh_gray_image(*in, *iso, !*below, criteria(*sizes, 2 * voxel, common->seed));
    finish(m, *common, "image " + *in, t0, &img);
  });
}

void add_grid_command(CLI::App* gen) {
  CLI::App* cmd =
      gen->add_subcommand("grid", "Box of NX x NY x NZ cubes, 5 or 6 tets each (no mesher: 100 M tets in seconds)");
  auto common = std::make_shared<Common>();
  auto cells = std::make_shared<std::string>();
  auto opt = std::make_shared<GridMeshOptions>();
  cmd->add_option("--cells", *cells, "Cells per axis: N (N^3 cubes) or NX,NY,NZ; the longest axis spans [-1, 1]")
      ->required()
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            try {
              parse_grid_cells(v);
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
            return {};
          },
          "N or NX,NY,NZ"));
  add_common(cmd, *common, "gaussians");
  cmd->add_option("--split", opt->split, "Tets per cube: 5 (alternating by parity) or 6 (around the main diagonal)")
      ->check(CLI::Validator(
          [](std::string& v) { return v == "5" || v == "6" ? "" : "must be 5 or 6, not '" + v + "'"; }, "5 or 6"))
      ->capture_default_str();
  char range[32];
  std::snprintf(range, sizeof range, "in [0, %g]", kMaxGridJitter);
  cmd->add_option("--jitter", opt->jitter, "Move interior nodes by up to this many cell sizes per axis (from --seed)")
      ->check(number_in(0, kMaxGridJitter, false, range))
      ->capture_default_str();
  cmd->callback([common, cells, opt] {
    check_output(common->out);
    auto t0 = Clock::now();
    opt->cells = parse_grid_cells(*cells);
    opt->seed = common->seed;
    TetMesh m = make_grid_mesh(*opt);
    const auto [nx, ny, nz] = opt->cells;
    std::ostringstream what;
    what << "grid " << nx << "x" << ny << "x" << nz << ", " << opt->split << " tets per cube";
    if (opt->jitter > 0) what << ", jitter " << opt->jitter;
    finish(m, *common, what.str(), t0);
  });
}

}  // namespace

void add_mesh_generate_command(CLI::App& mesh) {
  CLI::App* gen =
      mesh.add_subcommand("generate", "Generate a tet mesh (TetGen / CGAL Mesh_3 / hex grid) with a scalar field");
  gen->require_subcommand(1);
  add_shape_commands(gen);
  add_surface_command(gen);
  add_implicit_command(gen);
  add_image_command(gen);
  add_grid_command(gen);
}

}  // namespace zs
