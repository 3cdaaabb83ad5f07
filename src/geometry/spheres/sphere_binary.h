// `.sphb`: the binary form of a `.sph` list, for sets too large for text.
// All numbers little-endian. Layout (docs/spheres-format.md):
//   offset 0   8 bytes   magic "ZSSPHB1\n"
//   offset 8   uint32    fields per sphere F: 4 (x y z r), 5 (x y z r scalar)
//                        or 8 (x y z r R G B A, colour and opacity in [0, 1])
//   offset 12  uint32    reserved, 0
//   offset 16  uint64    sphere count N (> 0)
//   offset 24  N x F     float32, sphere after sphere
// and nothing after: the file is exactly 24 + 4 N F bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "geometry/spheres/sphere_set.h"

namespace zs {

inline constexpr char kSphbMagic[8] = {'Z', 'S', 'S', 'P', 'H', 'B', '1', '\n'};
inline constexpr size_t kSphbHeaderBytes = 24;

// Readers: the same rules as the text reader (sphere_reader.h): spheres with
// a zero, negative or non-finite radius or a non-finite centre are skipped
// and counted (SphereSet::invalid), a non-finite scalar is kept and counted
// as degenerate. Throw FileError naming the file (and the sphere, numbered
// from 0, for a bad colour): bad magic, a field count other than 4, 5 or 8, a
// reserved field other than 0, a count of 0, a size other than the header's
// (truncated or extra bytes), R, G, B or A outside [0, 1] or not finite, no
// drawable sphere. read_spheres_binary reads the file in chunks, so memory
// holds the set and one chunk, never the whole file.
SphereSet read_spheres_binary(const std::string& path);
SphereSet parse_spheres_binary(std::string_view bytes, const std::string& name);

// Writes 8 fields when the set has RGBA, else 5 when it has a scalar, else 4
// (so a set with both keeps its RGBA, and elements are not written). Values
// are rounded to float32. Through AtomicFile: on any failure (FileError naming
// the file; also a centre or radius beyond float32's range) nothing is left
// under `path`.
void write_spheres_binary(const std::string& path, const SphereSet& s);

// The number of float32 fields per sphere the writers use for s.
unsigned sphere_fields(const SphereSet& s);

}  // namespace zs
