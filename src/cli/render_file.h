// `zsweep render`'s output path, shared with `zsweep reference` (whose
// surface scenes render in exact mode): a loaded scene rendered through its
// SceneJob into an image file (streamed by tiles, across MPI ranks with
// --mpi), its --stats JSON and the one-line summary.
#pragma once

#include <string>

#include "scene/scene_input.h"

namespace zs {

void render_to_file(SceneInput& in, const std::string& out_path, const std::string& stats_path, int frames,
                    const std::string& compression, bool no_culling);

}  // namespace zs
