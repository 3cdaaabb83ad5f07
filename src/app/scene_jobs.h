// The kinds of SceneJob (app/scene_job.h), one file each.
#pragma once

#include <memory>

#include "app/scene_job.h"

namespace zs {

std::unique_ptr<SceneJob> make_volume_job(SceneInput& in);
std::unique_ptr<SceneJob> make_sphere_job(SceneInput& in, bool no_culling);
std::unique_ptr<SceneJob> make_surface_job(SceneInput& in);
// A volume with the scene's spheres or surfaces inside it (mixed_job.cpp).
std::unique_ptr<SceneJob> make_mixed_job(SceneInput& in, bool no_culling);

}  // namespace zs
