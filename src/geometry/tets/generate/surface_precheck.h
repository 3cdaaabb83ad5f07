// Checks on surface files before CGAL 5.5's readers see them. Those readers
// allocate by counts in the file (OFF header and face sizes, PLY list sizes)
// and dereference a null pointer on some PLY headers; under a memory budget,
// ASan or plain bad luck that is a crash, not an error (docs/robustness.md,
// finding 5). Each check throws FileError naming the file (and line).
#pragma once

#include <string>

namespace zs {

// ASCII OFF: the header (keyword and counts) against the file size, and each
// face's corner count and indices against the numbers on its line and the
// vertex count. Binary OFF, SKEL and the variants with colours, normals,
// texture coordinates or n dimensions (COFF, NOFF, STOFF, nOFF) are refused.
void precheck_off(const std::string& path);
// Binary STL (a file not starting with "solid"): exactly 84 + 50 * N bytes.
void precheck_stl(const std::string& path);
// PLY header: a property needs an element; element counts within the file
// size; list counts of at most 16 bits; vertex x/y/z float or double;
// vertex and face colours uchar; halfedge source/target uint.
void precheck_ply(const std::string& path);

}  // namespace zs
