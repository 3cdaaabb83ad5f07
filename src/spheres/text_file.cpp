#include "spheres/text_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mesh/mesh_error.h"

namespace zs {

std::string read_text_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw MeshError(path, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshError(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw MeshError(path, "read error");
  return ss.str();
}

}  // namespace zs
