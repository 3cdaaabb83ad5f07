// libFuzzer target: the plain sphere list reader (parse_spheres, .sph). Errors it reports
// (FileError, one line naming the input) are expected outcomes; any other
// exception, crash, leak or sanitizer report is a finding, and so is an
// accepted set that breaks the readers' contract (fuzz_sphere_check.h). There
// is no sphere renderer yet to go past the parser into.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_sphere_check.h"
#include "util/file_error.h"
#include "spheres/sphere_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    zs::fuzz::check_spheres(zs::parse_spheres(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.sph"));
  } catch (const zs::FileError&) {
  }
  return 0;
}
