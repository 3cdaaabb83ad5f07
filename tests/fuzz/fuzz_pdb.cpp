// libFuzzer target: the PDB atom reader (parse_pdb). Errors it reports
// (FileError, one line naming the input) are expected outcomes; any other
// exception, crash, leak or sanitizer report is a finding, and so is an
// accepted set that breaks the readers' contract (fuzz_sphere_check.h). An
// accepted set is then rendered small, culling on and off (fuzz_sphere_check.h).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_sphere_check.h"
#include "base/util/file_error.h"
#include "geometry/spheres/molecule_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const zs::SphereSet set = zs::parse_pdb(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.pdb");
    zs::fuzz::check_spheres(set);
    zs::fuzz::render_spheres_small(set);
  } catch (const zs::FileError&) {
  }
  return 0;
}
