// Statistics files: JSON written whole or not at all (AtomicFile).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace zs {

// Writes `j` (2-space indented) to `path`; throws std::runtime_error naming
// the file when it cannot, leaving nothing under that name.
void write_json_file(const std::string& path, const nlohmann::json& j);

}  // namespace zs
