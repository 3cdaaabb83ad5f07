// zsweep's own binary tet mesh, .zsm (docs/mesh.md, "The .zsm format"):
// exactly what a TetMesh holds, in sections laid out as they are in memory
// (64-byte aligned, little-endian), each with an XXH3 checksum, so a load
// is a few large reads straight into the mesh's arrays.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "geometry/tets/tet_mesh.h"

namespace zs {

inline constexpr char kZsmMagic[8] = {'Z', 'S', 'W', 'M', 'E', 'S', 'H', '\0'};
inline constexpr uint32_t kZsmVersion = 1;
inline constexpr size_t kZsmHeaderBytes = 192;

// Every error is a FileError naming the file: not a .zsm, a newer version,
// truncated, a checksum mismatch, a header whose counts or sections do not
// fit the file (refused before anything is allocated), a vertex index out of
// range.
TetMesh read_zsm(const std::string& path);
// The same from bytes in memory; `name` is used in error messages.
TetMesh parse_zsm(std::string_view bytes, const std::string& name);
// Through a temporary beside `path`, renamed on success (atomic_file.h).
void write_zsm(const std::string& path, const TetMesh& m);

}  // namespace zs
