// `zsweep render` of a surface scene (src/surface/, docs/shadows.md): the
// same tiles, threads, streaming writers, budget and MPI as the other scenes.
#pragma once

#include <string>

#include "scene/scene_input.h"

namespace zs {

void run_surfaces(SceneInput& in, const std::string& out_path, const std::string& stats_path, int frames,
                  const std::string& compression);

}  // namespace zs
