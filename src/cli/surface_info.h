// `zsweep mesh info` for triangle surfaces (.obj/.ply/.stl, OFF with the
// keyword): counts, closed solids and bounds instead of the tet report.
#pragma once

#include <string>

namespace zs {

void print_surface_info(const std::string& path, bool json);

}  // namespace zs
