// The ambient-occlusion "atmosphere" (spheres digest §2.4.4): directions from
// repeated subdivision of an octahedron, every edge split at its midpoint
// and the new vertex projected onto the unit sphere. Level s holds
// 2 + 4^(s+1) directions (6, 18, 66, 258, 1026, ...).
//
// Order: every coarser set is a prefix of every finer one (a map built for a
// direction is reused when the count grows), and directions come in opposite
// pairs, d[2i+1] = −d[2i] exactly (a normal sees at most one of a pair).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace zs {

// Whether n is 2 + 4^(s+1) for some level s >= 0.
bool valid_direction_count(uint64_t n);

// The first n directions (n must be a valid count; throws otherwise, naming
// the valid ones).
std::vector<glm::dvec3> ao_directions(uint32_t n);

}  // namespace zs
