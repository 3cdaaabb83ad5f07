// The one exception type readers and writers throw. Its message is the single
// line the CLI prints: "FILE:LINE: what" (LINE only for text formats).
#pragma once

#include <stdexcept>
#include <string>

namespace zs {

class FileError : public std::runtime_error {
 public:
  FileError(const std::string& file, const std::string& what)
      : std::runtime_error(file + ": " + what) {}
  // A message that already begins with its file ("FILE: what").
  explicit FileError(const std::string& message) : std::runtime_error(message) {}
  FileError(const std::string& file, size_t line, const std::string& what)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + what) {}
};

}  // namespace zs
