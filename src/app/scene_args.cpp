#include "app/scene_args.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include <CLI/CLI.hpp>

#include "geometry/spheres/sphere_io.h"
#include "geometry/triangles/io/surface_reader.h"

namespace zs {

const std::vector<NumberOption>& scene_number_options() {
  static const std::vector<NumberOption> table = {
      {"--threads", whole_range(1, 1024)},
      {"--width", whole_range(1, 1 << 20)},
      {"--height", whole_range(1, 1 << 20)},
      {"--memory-budget", positive_range(1.7e13)},  // MiB; bytes stay below 2^64
      {"--early-termination", real_range(0, 255)},
      {"--max-list-length", whole_range(0, 4294967295.0)},
      {"--tile-size", whole_range(8, 4096)},
  };
  return table;
}

const NumberRange& scene_number_range(const std::string& option) {
  for (const NumberOption& o : scene_number_options())
    if (option == o.option) return o.range;
  throw std::logic_error("no range for " + option);
}

void SceneArgs::add_options(CLI::App& cmd, bool engine_knobs) {
  auto range = [](const char* o) { return number_check(scene_number_range(o)); };
  cmd.add_option("input", input, "Scene .json, or a mesh (automatic camera and transfer function)");
  cmd.add_option("--threads", threads, "Threads (default: every core); images are identical for any count")
      ->check(range("--threads"));
  cmd.add_option("--q", opt.q_path, "PLOT3D solution file (PLOT3D grid input)");
  cmd.add_option("--scalar", opt.scalar, "Point or cell array, or PLOT3D function (mesh file input)");
  cmd.add_option("--association", association,
                 "Where the scalar lives (mesh file input): auto (as stored; default), point, cell, or "
                 "cell_to_point (cell data averaged onto the points)");
  cmd.add_option("--width", width, "Override image width")->check(range("--width"));
  cmd.add_option("--height", height, "Override image height")->check(range("--height"));
  cmd.add_option("--projection", projection, "Automatic camera: orthographic (default) or perspective");
  cmd.add_option("--memory-budget", memory_budget_mb, "Memory budget in MiB (default: half of physical memory)")
      ->check(range("--memory-budget"));
  cmd.add_option("--model", molecule.model, "Molecule files: the MODEL to read (its number; default: the first)");
  cmd.add_flag("--no-waters", molecule.no_waters, "Molecule files: leave out water molecules");
  cmd.add_flag("--no-hydrogens", molecule.no_hydrogens, "Molecule files: leave out hydrogen atoms");
  if (!engine_knobs) return;
  cmd.add_option("--scan", scan, "Scan strategy: span (default), bbox (same image, slower), bconvert");
  cmd.add_option("--variant", variant, "B-Convert variant (with --scan bconvert): truncate, round, dilate, dda3d, runlength");
  cmd.add_option("--integrator", integrator, "exact, linear, preintegrated or taylor2");
  cmd.add_option("--precision", precision,
                 "Exact integrator's kernel: double (default) or single (faster; error bound in docs/accuracy.md)");
  cmd.add_option("--early-termination", early_termination, "Stop a pixel below t/510 transmittance (t in 8-bit levels)")
      ->check(range("--early-termination"));
  cmd.add_option("--max-list-length", max_list_length, "Force compositing when a pixel list grows past this (0: never)")
      ->check(range("--max-list-length"));
  cmd.add_option("--tile-size", tile_size, "Screen tile size in pixels (default 64); the image does not depend on it")
      ->check(range("--tile-size"));
}

void SceneArgs::check_before_load() const {
  check();
  // A scene's kind is known once it is loaded; a missing file is the reader's to report.
  std::error_code ec;
  if (input.empty() || input.ends_with(".json") || !std::filesystem::is_regular_file(input, ec)) return;
  const SceneKind kind = is_sphere_file(input)    ? SceneKind::Spheres
                         : is_surface_file(input) ? SceneKind::Surfaces
                                                  : SceneKind::Volume;
  check_option_scope(given(), kind, input, python, is_molecule_file(input));
  const MeshFormat f = format_of(input);
  if (kind == SceneKind::Volume && !opt.q_path.empty() && f != MeshFormat::Plot3d && f != MeshFormat::Unknown)
    throw UsageError(input + ": " + option_name("--q", python) + " applies to PLOT3D grids only, and this is a " +
                     std::filesystem::path(input).extension().string() + " mesh");
}

ReadOptions SceneArgs::read_options() const {
  ReadOptions o = opt;
  if (!association.empty()) parse_association(association, &o.association);  // checked by check()
  return o;
}

SceneInput SceneArgs::load() const {
  check_before_load();  // before any file is read
  SceneInput in = load_scene_input(input, read_options(), molecule);
  apply(in);
  return in;
}

std::vector<std::string> SceneArgs::given() const {
  std::vector<std::string> g = also_given;
  auto add = [&](bool set, const char* name) {
    if (set) g.push_back(name);
  };
  add(!opt.q_path.empty(), "--q");
  add(!opt.scalar.empty(), "--scalar");
  add(!association.empty(), "--association");
  add(!scan.empty(), "--scan");
  add(!variant.empty(), "--variant");
  add(!integrator.empty(), "--integrator");
  add(!precision.empty(), "--precision");
  add(early_termination >= 0, "--early-termination");
  add(max_list_length >= 0, "--max-list-length");
  add(!molecule.model.empty(), "--model");
  add(molecule.no_waters, "--no-waters");
  add(molecule.no_hydrogens, "--no-hydrogens");
  return g;
}

RenderSettings SceneArgs::check() const {
  auto name = [&](const std::string& o) { return option_name(o, python); };
  if (!projection.empty() && projection != "perspective" && projection != "orthographic")
    throw UsageError(name("--projection") + " must be orthographic or perspective");
  RenderSettings knobs;
  ScalarAssociation a;
  if (!association.empty() && !parse_association(association, &a))
    throw UsageError(name("--association") + " must be auto, point, cell or cell_to_point");
  if (!scan.empty() && !parse_scan_strategy(scan, &knobs.scan))
    throw UsageError(name("--scan") + " must be bbox, bconvert or span");
  if (!variant.empty() && !parse_bconvert_variant(variant, &knobs.bconvert_variant))
    throw UsageError(name("--variant") + " must be truncate, round, dilate, dda3d or runlength");
  if (!integrator.empty() && !parse_integrator(integrator, &knobs.integrator))
    throw UsageError(name("--integrator") + " must be exact, linear, preintegrated or taylor2");
  if (!precision.empty() && precision != "double" && precision != "single")
    throw UsageError(name("--precision") + " must be double or single");
  return knobs;
}

void SceneArgs::apply(SceneInput& in, const std::string& input_name) const {
  const RenderSettings knobs = check();
  const std::string who = !input_name.empty() ? input_name : !input.empty() ? input : "the default scene";
  auto name = [&](const std::string& o) { return option_name(o, python); };
  // Options that do not apply to this input would be ignored without a word.
  check_option_scope(given(), in.scene.kind, who, python,
                     in.scene.kind == SceneKind::Spheres && is_molecule_file(in.scene.spheres.path));
  const bool bare_mesh = !input.empty() && in.scene.kind == SceneKind::Volume && in.scene.mesh_path == input;
  const char* mesh_opt = !opt.scalar.empty() ? "scalar" : !association.empty() ? "association"
                         : !opt.q_path.empty()  ? "q"
                                                : nullptr;
  if (mesh_opt && !bare_mesh)
    throw UsageError(who + ": " + name("--" + std::string(mesh_opt)) + " applies to a mesh file; " +
                     (in.scene.mesh_path.empty() ? std::string("this scene has none")
                                                 : "a scene names it as mesh." + std::string(mesh_opt)));
  if (!projection.empty() && in.scene.has_camera)
    throw UsageError(who + ": " + name("--projection") +
                             " applies to the automatic camera, and this scene has its own");
  Projection p = projection == "perspective" ? Projection::Perspective : Projection::Orthographic;
  RenderSettings& rs = in.scene.settings;
  if (width) rs.width = width;
  if (height) rs.height = height;
  if (!scan.empty()) rs.scan = knobs.scan;
  if (!variant.empty()) rs.bconvert_variant = knobs.bconvert_variant;
  if (!integrator.empty()) rs.integrator = knobs.integrator;
  if (!precision.empty()) rs.single_precision = precision == "single";
  // Knobs that only matter beside another setting (the scene's or an option's).
  if (!variant.empty() && rs.scan != ScanStrategy::BConvert)
    throw UsageError(who + ": " + name("--variant") + " applies to the bconvert scan, and the scan is " +
                             to_string(rs.scan));
  if (!precision.empty() && rs.integrator != Integrator::Exact)
    throw UsageError(who + ": " + name("--precision") + " applies to the exact integrator, and the integrator is " +
                             to_string(rs.integrator));
  if (memory_budget_mb > 0) rs.memory_budget_bytes = uint64_t(memory_budget_mb * 1048576.0);
  if (early_termination >= 0) rs.early_termination = early_termination;
  if (max_list_length >= 0) rs.max_list_length = uint32_t(max_list_length);
  if (tile_size) rs.tile_size = tile_size;
  rs.threads = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  rs.progress = true;
  // Surfaces are framed in perspective unless told otherwise.
  if (projection.empty() && in.scene.kind == SceneKind::Surfaces) p = Projection::Perspective;
  finish_scene(in, p);
}

}  // namespace zs
