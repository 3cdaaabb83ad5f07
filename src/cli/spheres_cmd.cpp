// `zsweep spheres convert IN OUT` and `zsweep spheres generate c1..c4`:
// sphere sets between .pdb/.sph/.sphb, and the C1-C4 test sets.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <CLI/CLI.hpp>

#include "app/option_checks.h"
#include "cli/commands.h"
#include "geometry/spheres/generate/demo_image.h"
#include "geometry/spheres/generate/pore_balls.h"
#include "geometry/spheres/generate/test_sets.h"
#include "geometry/spheres/sphere_io.h"
#include "base/util/atomic_file.h"
#include "base/util/file_error.h"

namespace zs {

namespace {

// Fails on an output name the writers cannot take before any long work.
void check_output(const std::string& out) {
  std::string e = std::filesystem::path(out).extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (e != ".sph" && e != ".sphb") throw FileError(out, "unknown sphere output format (expected .sph or .sphb)");
  AtomicFile(out).check_writable();
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void add_convert(CLI::App& spheres) {
  struct Args {
    std::string in, out;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = spheres.add_subcommand("convert", "Convert a sphere set (.pdb/.ent/.sph/.sphb to .sph/.sphb)");
  cmd->add_option("input", args->in, "Input: .pdb, .ent, .sph or .sphb")->required();
  cmd->add_option("output", args->out, "Output: .sph (text) or .sphb (binary float32)")->required();
  cmd->callback([args] {
    check_output(args->out);
    const SphereSet s = read_sphere_file(args->in);
    write_spheres(args->out, s);
    std::printf("wrote %s: %zu spheres (%zu invalid skipped)\n", args->out.c_str(), s.size(), s.invalid);
  });
}

void add_generate(CLI::App& spheres) {
  struct Args {
    std::string set, out;
    size_t count = 0;
    uint64_t seed = 1;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = spheres.add_subcommand("generate", "Generate the sphere test sets C1-C4 (RGBA spheres)");
  cmd->add_option("set", args->set, "c1 (1 M, sparse + central cluster), c2 (2,463,048 maximal balls of a real image's "
                                    "pores), c3 (8 M in small clusters), c4 (27 M in one block)")
      ->required();
  cmd->add_option("--count", args->count, "Number of spheres (default: the set's full size)")->check(number_check(whole_range(1, INFINITY)));
  cmd->add_option("--seed", args->seed, "Random seed (same seed, same set)");
  cmd->add_option("-o,--output", args->out, "Output: .sph or .sphb")->required();
  cmd->callback([args] {
    SphereTestSet t;
    if (!parse_sphere_test_set(args->set, &t))
      throw UsageError("unknown sphere test set '" + args->set + "' (expected c1, c2, c3 or c4)");
    check_output(args->out);
    const size_t n = args->count ? args->count : default_sphere_count(t);
    const auto t0 = std::chrono::steady_clock::now();
    SphereSet s;
    switch (t) {
      case SphereTestSet::C1: s = generate_c1(n, args->seed); break;
      case SphereTestSet::C2: s = generate_c2(n, args->seed, kCgalDemoData); break;
      case SphereTestSet::C3: s = generate_c3(n, args->seed); break;
      case SphereTestSet::C4: s = generate_c4(n, args->seed); break;
    }
    const double gen = seconds_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    write_spheres(args->out, s);
    const double wr = seconds_since(t1);
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(args->out, ec);
    std::printf("wrote %s: %s, %zu spheres, %.1f MB (generated in %.2f s, written in %.2f s)\n", args->out.c_str(),
                to_string(t), s.size(), double(bytes) / 1e6, gen, wr);
    for (const std::string& note : s.notes) std::printf("note: %s\n", note.c_str());
  });
}

}  // namespace

void add_spheres_command(CLI::App& app) {
  CLI::App* spheres = app.add_subcommand("spheres", "Convert and generate sphere sets");
  spheres->require_subcommand(1);
  add_convert(*spheres);
  add_generate(*spheres);
}

}  // namespace zs
