// A 3D image from Debian's libcgal-demo data (the tarball
// /usr/share/doc/libcgal-dev/data.tar.gz), read straight out of the tarball:
// gzip through zlib, the tar headers and the INRIMAGE-4 format by hand.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace zs {

inline constexpr const char* kCgalDemoData = "/usr/share/doc/libcgal-dev/data.tar.gz";

struct ScalarImage {
  size_t nx = 0, ny = 0, nz = 0;
  glm::dvec3 spacing{1.0};
  std::vector<float> values;  // x fastest
};

// The bytes of one member of a .tar.gz; throws FileError naming the tarball
// when it cannot be read or has no such member.
std::string read_tar_gz_member(const std::string& tarball, const std::string& member);

// An INRIMAGE-4 image (256-byte-multiple text header "#INRIMAGE-4#{ ...
// ##}\n", then raw voxels): scalar (VDIM=1) float 32/64 bits or unsigned
// fixed 8/16 bits, CPU decm (little-endian) or sun/sgi (big-endian). Throws
// FileError naming `name` otherwise.
ScalarImage parse_inr(const std::string& bytes, const std::string& name);

}  // namespace zs
