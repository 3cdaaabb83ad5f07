// Which files hold a triangle surface, by name and first token: .obj, .ply,
// .stl, and OFF with its keyword (OFF, COFF, NOFF, ... on the first line).
// Our classic tetrahedral .off starts with two counts, never the keyword, so
// the two never clash. Apart from the readers (triangles/io/) so that the tet
// mesh dispatch (tets/io/mesh_io.cpp) can refuse a surface without them.
#pragma once

#include <string>

#include "base/util/file_name.h"  // lower_extension

namespace zs {

// True for a file name a surface reader takes: .obj, .ply, .stl, or a .off
// file whose first token names an OFF surface. Reads nothing otherwise.
bool is_surface_file(const std::string& path);

// The first token of the first line that is neither blank nor a comment.
std::string first_token(const std::string& path);
// Whether a first token is an OFF surface's keyword.
bool off_keyword(const std::string& token);

}  // namespace zs
