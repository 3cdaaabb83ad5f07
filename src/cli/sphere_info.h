// `zsweep mesh info` for sphere files (.pdb/.ent/.sph/.sphb): counts, bounds and
// radius range instead of the tet report.
#pragma once

#include <string>

namespace zs {

void print_sphere_info(const std::string& path, bool json);

}  // namespace zs
