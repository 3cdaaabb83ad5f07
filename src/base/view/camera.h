// Camera and the view it induces: the mapping from world points to
// continuous screen coordinates (pixel (i, j) centre at X = i, Y = j, row 0 at
// the top) and view depth, exactly as the scene spec defines the rays:
//   f = normalize(target - eye), r = normalize(f x up), u = r x f.
// Orthographic: the ray through pixel centre (i, j) starts at
//   eye + ((i+.5)/W - .5)·height·W/H·r + (.5 - (j+.5)/H)·height·u, direction f.
// Perspective: origin eye, direction normalize(f + a r + b u) with
//   a = ((i+.5)/W - .5)·2 tan(fov/2)·W/H,  b = (.5 - (j+.5)/H)·2 tan(fov/2).
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

namespace zs {

enum class Projection { Orthographic, Perspective };

struct Camera {
  Projection projection = Projection::Orthographic;
  glm::dvec3 eye{0, 0, 5}, target{0, 0, 0}, up{0, 1, 0};
  double height = 4.0;  // orthographic: world height of the image
  double fov_y = 30.0;  // perspective: vertical field of view, degrees
};

// A point in view space: X, Y continuous pixel coordinates, z the view depth
// along f (orthographic: from the eye plane; perspective: camera-space z, so
// the distance along a ray is z·ray_length_factor(X, Y)).
struct ViewPoint {
  double x, y, z;
};

class View {
 public:
  View(const Camera& cam, uint32_t width, uint32_t height);

  ViewPoint project(const glm::dvec3& p) const;
  // Depth of p along f from the eye (both projections).
  double depth(const glm::dvec3& p) const;
  // Distance along the ray per unit of view depth at pixel coordinates (X, Y):
  // 1 for orthographic, |f + a r + b u| for perspective.
  double ray_length_factor(double X, double Y) const;
  // The ray through pixel coordinates (X, Y) (X = i for the centre of column i).
  void ray(double X, double Y, glm::dvec3* origin, glm::dvec3* dir_unit) const;
  // The same ray parametrised by view depth: the point at depth z is
  // at_zero + z·per_depth.
  void depth_line(double X, double Y, glm::dvec3* at_zero, glm::dvec3* per_depth) const;

  bool perspective() const { return persp_; }
  uint32_t width() const { return w_; }
  uint32_t height() const { return h_; }
  const glm::dvec3& eye() const { return eye_; }
  const glm::dvec3& forward() const { return f_; }
  const glm::dvec3& right() const { return r_; }
  const glm::dvec3& up() const { return u_; }
  // The screen mapping X = sx·a + ox, Y = oy − sy·b, where (a, b) are the
  // camera-plane coordinates along r and u (orthographic: world units from
  // the eye; perspective: a = x/z, b = y/z). Renderers that work in camera
  // space (sphere spans) need it; project() applies it.
  double scale_x() const { return sx_; }
  double scale_y() const { return sy_; }
  double offset_x() const { return ox_; }
  double offset_y() const { return oy_; }

 private:
  bool persp_;
  uint32_t w_, h_;
  glm::dvec3 eye_, f_, r_, u_;
  // Screen mapping: X = sx * a + ox, Y = -sy * b + oy, where (a, b) are the
  // camera-plane coordinates (orthographic: world units; perspective: x/z, y/z).
  double sx_, sy_, ox_, oy_;
};

}  // namespace zs
