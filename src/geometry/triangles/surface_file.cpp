#include "geometry/triangles/surface_file.h"
#include "base/util/file_name.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

namespace zs {

std::string first_token(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int n = 0; n < 64 && std::getline(in, line); ++n) {
    size_t i = line.find_first_not_of(" \t\r");
    if (i == std::string::npos || line[i] == '#') continue;
    const size_t j = line.find_first_of(" \t\r", i);
    return line.substr(i, j == std::string::npos ? std::string::npos : j - i);
  }
  return "";
}

bool off_keyword(const std::string& tok) { return tok.size() >= 3 && tok.compare(tok.size() - 3, 3, "OFF") == 0; }

bool is_surface_file(const std::string& path) {
  const std::string e = lower_extension(path);
  if (e == ".obj" || e == ".ply" || e == ".stl") return true;
  return e == ".off" && off_keyword(first_token(path));
}

}  // namespace zs
