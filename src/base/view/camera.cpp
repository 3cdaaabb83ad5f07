#include "base/view/camera.h"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace zs {

View::View(const Camera& cam, uint32_t width, uint32_t height)
    : persp_(cam.projection == Projection::Perspective), w_(width), h_(height), eye_(cam.eye) {
  f_ = glm::normalize(cam.target - cam.eye);
  r_ = glm::normalize(glm::cross(f_, cam.up));
  u_ = glm::cross(r_, f_);
  const double aspect = double(w_) / double(h_);
  // Camera-plane extent of the image: world units (ortho) or tangent (persp).
  const double ext_h = persp_ ? 2.0 * std::tan(cam.fov_y * M_PI / 360.0) : cam.height;
  const double ext_w = ext_h * aspect;
  // a = ((X+.5)/W - .5)·ext_w  =>  X = (a/ext_w + .5)·W - .5
  sx_ = double(w_) / ext_w;
  ox_ = 0.5 * w_ - 0.5;
  // b = (.5 - (Y+.5)/H)·ext_h  =>  Y = (.5 - b/ext_h)·H - .5
  sy_ = double(h_) / ext_h;
  oy_ = 0.5 * h_ - 0.5;
}

double View::depth(const glm::dvec3& p) const { return glm::dot(p - eye_, f_); }

ViewPoint View::project(const glm::dvec3& p) const {
  const glm::dvec3 d = p - eye_;
  const double z = glm::dot(d, f_);
  double a = glm::dot(d, r_), b = glm::dot(d, u_);
  if (persp_) {
    a /= z;
    b /= z;
  }
  return {a * sx_ + ox_, oy_ - b * sy_, z};
}

double View::ray_length_factor(double X, double Y) const {
  if (!persp_) return 1.0;
  const double a = (X - ox_) / sx_, b = (oy_ - Y) / sy_;
  return std::sqrt(1.0 + a * a + b * b);
}

void View::ray(double X, double Y, glm::dvec3* origin, glm::dvec3* dir) const {
  const double a = (X - ox_) / sx_, b = (oy_ - Y) / sy_;
  if (persp_) {
    *origin = eye_;
    *dir = glm::normalize(f_ + a * r_ + b * u_);
  } else {
    *origin = eye_ + a * r_ + b * u_;
    *dir = f_;
  }
}

void View::depth_line(double X, double Y, glm::dvec3* at_zero, glm::dvec3* per_depth) const {
  const double a = (X - ox_) / sx_, b = (oy_ - Y) / sy_;
  if (persp_) {
    *at_zero = eye_;
    *per_depth = f_ + a * r_ + b * u_;  // its component along f is 1
  } else {
    *at_zero = eye_ + a * r_ + b * u_;
    *per_depth = f_;
  }
}

}  // namespace zs
