// libFuzzer target: the mmCIF path of the molecule reader (parse_molecule,
// MoleculeFormat::Mmcif: gemmi's CIF parser and its structure builder, then
// our spheres). Errors it reports (FileError, one line naming the input) are
// expected outcomes; any other exception (gemmi's runtime_error or
// out_of_range must have been turned into FileError), crash, leak or
// sanitizer report is a finding, and so is an accepted set that breaks the
// readers' contract (fuzz_sphere_check.h). An accepted set is then rendered
// small, culling on and off.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_sphere_check.h"
#include "base/util/file_error.h"
#include "geometry/spheres/molecule_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const zs::SphereSet set = zs::parse_molecule(std::string_view(reinterpret_cast<const char*>(data), size),
                                                 "fuzz.cif", zs::MoleculeFormat::Mmcif);
    zs::fuzz::check_spheres(set);
    zs::fuzz::render_spheres_small(set);
  } catch (const zs::FileError&) {
  }
  return 0;
}
