// The message of the FileError a reader throws, for tests of one-line errors.
#pragma once

#include <string>

#include "base/util/file_error.h"

namespace zs::test {

// The message of the FileError that f throws ("" if none; other exceptions pass).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

}  // namespace zs::test
