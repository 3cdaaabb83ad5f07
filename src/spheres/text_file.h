// Reads a whole file into memory for the sphere readers, which parse text.
#pragma once

#include <string>

namespace zs {

// Throws MeshError naming the file when it cannot be opened or read.
std::string read_text_file(const std::string& path);

}  // namespace zs
