// The check every reader makes before it opens a file, so that a missing
// path or a directory is named as such ("d.json: is a directory, not a scene
// file") rather than reported as a format error ("invalid JSON").
#pragma once

#include <filesystem>
#include <string>

#include "base/util/file_error.h"

namespace zs {

// `what`: "a scene file", "an image", ...
inline void require_input_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw FileError(path, "is a directory, not " + what);
  if (!std::filesystem::exists(path, ec)) throw FileError(path, "no such file");
}

}  // namespace zs
