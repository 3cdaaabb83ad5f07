// libFuzzer target: the binary sphere list reader (parse_spheres_binary,
// .sphb). As for fuzz_sphere.cpp: FileError is an expected outcome, anything
// else (crash, other exception, an accepted set breaking
// fuzz_sphere_check.h) is a finding; an accepted set is rendered small,
// culling on and off.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_sphere_check.h"
#include "geometry/spheres/sphere_binary.h"
#include "base/util/file_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const zs::SphereSet set =
        zs::parse_spheres_binary(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.sphb");
    zs::fuzz::check_spheres(set);
    zs::fuzz::render_spheres_small(set);
  } catch (const zs::FileError&) {
  }
  return 0;
}
