#include "geometry/spheres/sphere_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "geometry/spheres/molecule_reader.h"
#include "geometry/spheres/sphere_binary.h"
#include "geometry/spheres/sphere_reader.h"
#include "geometry/spheres/sphere_writer.h"
#include "base/util/file_error.h"
#include "base/util/file_name.h"

namespace zs {

bool is_sphere_file(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".sph" || e == ".sphb" || is_molecule_file(path);
}

SphereSet read_sphere_file(const std::string& path, const MoleculeOptions& molecule) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw FileError(path, "no such file");
  const std::string e = lower_extension(path);
  if (e == ".sph") return read_spheres(path);
  if (e == ".sphb") return read_spheres_binary(path);
  if (is_molecule_file(path)) return read_molecule(path, molecule);
  throw FileError(path, "unknown sphere format (expected .pdb, .ent, .cif, .mmcif (each also .gz), .sph or .sphb)");
}

void write_spheres(const std::string& path, const SphereSet& s) {
  const std::string e = lower_extension(path);
  if (e == ".sph") return write_spheres_text(path, s);
  if (e == ".sphb") return write_spheres_binary(path, s);
  throw FileError(path, "unknown sphere output format (expected .sph or .sphb)");
}

}  // namespace zs
