#include "spheres/sphere_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "util/file_error.h"
#include "spheres/pdb_reader.h"
#include "spheres/sphere_reader.h"

namespace zs {

namespace {

std::string lower_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

}  // namespace

bool is_sphere_file(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".pdb" || e == ".ent" || e == ".sph";
}

SphereSet read_sphere_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw FileError(path, "no such file");
  const std::string e = lower_extension(path);
  if (e == ".sph") return read_spheres(path);
  if (e == ".pdb" || e == ".ent") return read_pdb(path);
  throw FileError(path, "unknown sphere format (expected .pdb, .ent or .sph)");
}

}  // namespace zs
