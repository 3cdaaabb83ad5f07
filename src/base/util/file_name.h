// A file name's extension as the readers dispatch on it.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace zs {

// The extension in lower case, with its dot ("" when none): ".vtu", ".off".
inline std::string lower_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

}  // namespace zs
