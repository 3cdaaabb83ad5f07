// The four test sets of sphere-rendering studies (C1-C4 of Table 4 in the
// 2012 thesis the seed cites), rebuilt synthetically; C2 comes from a real
// image and lives in pore_balls.h (it needs VTK). Every sphere has an RGBA.
// The same (count, seed) gives the same set on every platform
// (portable_random.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "geometry/spheres/sphere_set.h"

namespace zs {

enum class SphereTestSet { C1, C2, C3, C4 };
bool parse_sphere_test_set(const std::string& s, SphereTestSet* out);  // "c1".."c4", any case
const char* to_string(SphereTestSet t);
// The thesis's sizes: 1,000,000, 2,463,048, 8,000,000 and 27,000,000.
size_t default_sphere_count(SphereTestSet t);

// C1: sparse spheres over the cube [-50, 50]^3 (70%) and a dense Gaussian
// cluster at its centre (30%, sigma 5); mostly opaque (80%), the rest
// translucent (alpha 0.2-0.6).
SphereSet generate_c1(size_t count, uint64_t seed);

// C3: many small separate clusters (2,000 spheres each, at least one) of
// radius 2.5 on a jittered grid of pitch 10, so neighbouring clusters are at
// least 2.7 apart; spheres in the outer quarter of the set's extent (max-norm
// from its centre) are translucent (alpha 0.1-0.4), the others opaque.
SphereSet generate_c3(size_t count, uint64_t seed);

// C4: one block-shaped cluster, a jittered n x n x m lattice of pitch 1
// (300^3 for 27 M; the last layer partly filled when count is not a cube).
// Background spheres are blue-grey and translucent (alpha 0.1-0.3, 5%
// opaque); within 8 blobs (radius 0.12 n, centres inside the block) the
// spheres are red (4 blobs) or green (4 blobs) and highly translucent
// (alpha 0.02-0.08). Radii 0.5-0.7, so neighbours overlap.
SphereSet generate_c4(size_t count, uint64_t seed);

}  // namespace zs
