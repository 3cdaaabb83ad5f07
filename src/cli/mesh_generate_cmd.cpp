// `zsweep mesh generate`: synthetic shapes (TetGen, target tet count), closed
// surfaces (TetGen), implicit solids and grey-level images (CGAL Mesh_3), each
// with a scalar field attached, written through zs::write_mesh.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/option_checks.h"
#include "cli/commands.h"
#include "mesh/generate/cgal_mesher.h"
#include "mesh/generate/scalar_fields.h"
#include "mesh/generate/shape_mesher.h"
#include "mesh/generate/shapes.h"
#include "mesh/generate/surface_io.h"
#include "mesh/generate/tetgen_mesher.h"
#include "mesh/generate/voxel_image.h"
#include "mesh/io/mesh_io.h"

namespace zs {

namespace {

// Options every generator shares.
struct Common {
  std::string out;
  std::string field;
  uint64_t seed = 1;
};

void add_common(CLI::App* cmd, Common& c, const std::string& default_field) {
  c.field = default_field;
  cmd->add_option("-o,--output", c.out, "Output mesh (.off, .vtu or .node/.ele)")->required();
  std::vector<std::string> fields = field_names();
  fields.push_back("none");
  cmd->add_option("--field", c.field, "Scalar field to attach")
      ->check(CLI::IsMember(fields))
      ->capture_default_str();
  cmd->add_option("--seed", c.seed, "Seed for randomised shapes/fields")->capture_default_str();
}

// Fail on a bad output name before spending minutes meshing.
void check_output(const std::string& out) {
  MeshFormat f = format_of(out);
  if (f != MeshFormat::Off && f != MeshFormat::Vtu && f != MeshFormat::TetGen)
    throw std::invalid_argument(out + ": cannot write this format (expected .off, .vtu or .node/.ele)");
}

using Clock = std::chrono::steady_clock;

void finish(TetMesh& m, const Common& c, const std::string& what, Clock::time_point t0,
            const VoxelImage* img = nullptr) {
  if (c.field != "none") apply_field(m, c.field, c.seed, img);
  write_mesh(c.out, m);
  double secs = std::chrono::duration<double>(Clock::now() - t0).count();
  std::cout << c.out << ": " << m.num_points() << " points, " << m.num_tets() << " tets (" << what
            << (c.field != "none" ? ", field " + c.field : std::string()) << ", "
            << std::fixed << std::setprecision(1) << secs << " s)\n";
}

struct SizeOpts {
  std::optional<double> size, facet_angle, facet_size, facet_distance, cell_radius_edge, cell_size;
};

void add_size_opts(CLI::App* cmd, SizeOpts& s, const std::string& size_help) {
  cmd->add_option("--size", s.size, size_help)->check(number_check(positive_range()));
  cmd->add_option("--facet-angle", s.facet_angle, "Min surface facet angle, degrees (default 30)");
  cmd->add_option("--facet-size", s.facet_size, "Surface Delaunay ball radius bound (default --size)");
  cmd->add_option("--facet-distance", s.facet_distance, "Surface approximation error (default --size/4)");
  cmd->add_option("--cell-radius-edge", s.cell_radius_edge, "Tet radius-edge ratio bound (default 2)");
  cmd->add_option("--cell-size", s.cell_size, "Tet circumradius bound (default --size)");
}

Mesh3Criteria criteria(const SizeOpts& s, double default_size, uint64_t seed) {
  Mesh3Criteria c = Mesh3Criteria::from_size(s.size.value_or(default_size));
  if (s.facet_angle) c.facet_angle = *s.facet_angle;
  if (s.facet_size) c.facet_size = *s.facet_size;
  if (s.facet_distance) c.facet_distance = *s.facet_distance;
  if (s.cell_radius_edge) c.cell_radius_edge = *s.cell_radius_edge;
  if (s.cell_size) c.cell_size = *s.cell_size;
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
    cmd->add_option("--tets", opt->target_tets, "Target tet count (lands within ~10%, at most a few reruns)")
        ->check(number_check(whole_range(1, 100000000)))
        ->capture_default_str();
    cmd->add_option("--quality", opt->quality, "Radius-edge ratio bound (TetGen -q)")
        ->check(number_check(real_range(1.1, 100)))
        ->capture_default_str();
    cmd->callback([common, opt] {
      check_output(common->out);
      opt->seed = common->seed;
      auto t0 = Clock::now();
      TetMesh m = mesh_shape(*opt);
      finish(m, *common, opt->shape + ", target " + std::to_string(opt->target_tets), t0);
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
  cmd->add_option("--quality", opt->quality, "Radius-edge ratio bound (TetGen -q; 0 = off)")
      ->check(number_check(real_range(0, 100)))
      ->capture_default_str();
  cmd->add_option("--max-volume", opt->max_volume, "Max tet volume (TetGen -a)")->check(number_check(real_range(0, INFINITY)));
  cmd->add_flag("--preserve-surface", opt->preserve_surface,
                "Keep the input triangles as the boundary, no Steiner points on it (TetGen -Y)");
  cmd->callback([common, in, opt] {
    check_output(common->out);
    auto t0 = Clock::now();
    Plc plc = read_surface(*in);
    TetMesh m;
    try {
      m = tetrahedralize(plc, *opt);
    } catch (const std::runtime_error& e) {
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

}  // namespace

void add_mesh_generate_command(CLI::App& mesh) {
  CLI::App* gen = mesh.add_subcommand("generate", "Generate a tet mesh (TetGen / CGAL Mesh_3) with a scalar field");
  gen->require_subcommand(1);
  add_shape_commands(gen);
  add_surface_command(gen);
  add_implicit_command(gen);
  add_image_command(gen);
}

}  // namespace zs
