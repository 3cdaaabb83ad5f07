// The three kinds of SceneJob (app/scene_job.h), one file each.
#pragma once

#include <memory>

#include "app/scene_job.h"

namespace zs {

std::unique_ptr<SceneJob> make_volume_job(SceneInput& in);
std::unique_ptr<SceneJob> make_sphere_job(SceneInput& in, bool no_culling);
std::unique_ptr<SceneJob> make_surface_job(SceneInput& in);

}  // namespace zs
