// `zsweep reference` of a volume or sphere scene, in memory: the independent
// ray casters (reference/) on the scene's camera, colours and shading, their
// channels and stats. The command line writes it to a file, the Python module
// returns it. (A surface scene's reference is its renderer's exact mode,
// through SceneJob.)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene_input.h"

namespace zs {

struct ReferenceImage {
  uint32_t width = 0, height = 0;
  std::vector<std::string> names;  // R, G, B, A (volumes); then Z (spheres); then AO (sphere AO scenes)
  std::vector<float> pixels;       // row-major from the top row, names.size() floats per pixel
  nlohmann::json stats;            // the --stats JSON
  std::string summary;             // the one-line report, after "wrote OUT: "
};

// `ao_samples`: sphere AO scenes: 0 traces the scene's directions exactly,
// N > 0 a cosine-weighted Monte Carlo AO with N rays per pixel.
ReferenceImage reference_image(SceneInput& in, uint32_t ao_samples);

}  // namespace zs
