// The message of what a call throws, for tests of one-line errors.
#pragma once

#include <string>

#include "base/util/file_error.h"

namespace zs::test {

// The message of what `f` throws as E ("" if it throws nothing; other
// exceptions pass).
template <class E, class F>
std::string thrown(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

// The message of the FileError that f throws ("" if none).
template <class F>
std::string error_of(F f) {
  return thrown<FileError>(f);
}

}  // namespace zs::test
