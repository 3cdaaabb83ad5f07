#include "bench/bench_inputs.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include <unistd.h>

#include "scene/scene.h"
#include "geometry/spheres/sphere_io.h"
#include "geometry/triangles/io/surface_reader.h"
#include "base/util/atomic_file.h"
#include "base/util/file_error.h"

namespace zs {

namespace fs = std::filesystem;

namespace {

// What a bare file is, when the volume renderer cannot take it ("" when it can).
std::string non_volume_file(const std::string& path) {
  if (is_sphere_file(path)) return "a sphere set";
  if (is_surface_file(path)) return "a surface mesh";
  return "";
}

void check_exists(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw FileError(path, "no such file");
}

std::string sanitize(std::string s) {
  for (char& c : s)
    if (c == ',' || c == '/' || c == '\\' || c == '"' || static_cast<unsigned char>(c) < 0x20) c = '_';
  return s;
}

}  // namespace

void check_volume_inputs(const std::vector<std::string>& inputs, const std::string& bench, bool allow_default) {
  const std::string takes = "; " + bench + " measures tet meshes (volume scenes)";
  for (const std::string& input : inputs) {
    if (allow_default && input == "default") continue;
    if (input.size() > 5 && input.compare(input.size() - 5, 5, ".json") == 0) {
      const Scene s = load_scene(input);  // throws naming the file
      if (s.kind == SceneKind::Spheres) throw FileError(input, "a sphere scene" + takes);
      if (s.kind == SceneKind::Surfaces) throw FileError(input, "a surface scene" + takes);
      if (s.mesh_path.empty()) continue;
      const std::string what = non_volume_file(s.mesh_path);
      if (!what.empty()) throw FileError(input, "its mesh " + s.mesh_path + " is " + what + takes);
      check_exists(s.mesh_path);
      continue;
    }
    check_exists(input);
    const std::string what = non_volume_file(input);
    if (!what.empty()) throw FileError(input, what + takes);
  }
}

std::vector<std::string> bench_row_names(const std::vector<std::string>& inputs) {
  std::vector<std::string> base;
  std::map<std::string, int> stems;
  for (const std::string& in : inputs) {
    base.push_back(sanitize(in == "default" ? in : fs::path(in).stem().string()));
    ++stems[base.back()];
  }
  for (size_t i = 0; i < inputs.size(); ++i)
    if (stems[base[i]] > 1 && inputs[i] != "default") base[i] = sanitize(fs::path(inputs[i]).filename().string());
  // The same file name twice (two directories, or one file given twice): the
  // later ones get -2, -3, ... avoiding every other input's name.
  const std::set<std::string> all(base.begin(), base.end());
  std::set<std::string> used;
  std::vector<std::string> names;
  for (const std::string& b : base) {
    std::string n = b;
    for (int k = 2; used.count(n); ++k) {
      n = b + "-" + std::to_string(k);
      if (all.count(n)) n = b;  // keep looking
    }
    used.insert(n);
    names.push_back(n);
  }
  return names;
}

void check_bench_outputs(const std::string& csv, const std::string& plots_dir) {
  if (!csv.empty()) AtomicFile(csv).check_writable();
  if (plots_dir.empty()) return;
  // The directory, or the nearest ancestor that exists (where it would be made).
  fs::path p = plots_dir;
  std::error_code ec;
  while (!p.empty() && !fs::exists(p, ec)) p = p.parent_path();
  if (p.empty()) p = ".";
  const bool is_it = p == fs::path(plots_dir);
  if (!fs::is_directory(p, ec))
    throw FileError(plots_dir, is_it ? "cannot write plots: not a directory"
                                     : "cannot create the plots directory: " + p.string() + " is not a directory");
  if (::access(p.c_str(), W_OK | X_OK) != 0)
    throw FileError(plots_dir, std::string(is_it ? "cannot write plots: " : "cannot create the plots directory: ") +
                                   std::strerror(errno));
}

}  // namespace zs
