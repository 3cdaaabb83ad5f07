// The part of space a scene keeps: the intersection of half-spaces
// n·x + d <= 0 (a scene's "clip" planes and "crop" box, docs/scene.md).
// Convex, so a line keeps one interval of itself; renderers cut their
// segments to it exactly (the volume's segments keep their scalar linear),
// and the planes' cut faces add nothing of their own. Moving a plane changes
// no mesh data.
#pragma once

#include <array>
#include <vector>

#include <glm/vec3.hpp>

namespace zs {

struct ClipPlane {
  glm::dvec3 n;  // not zero
  double d;      // keeps n·x + d <= 0
};

struct ClipRegion {
  std::vector<ClipPlane> planes;

  bool empty() const { return planes.empty(); }
  // The six planes keeping [lo, hi] (lo <= hi on each axis).
  void add_box(const glm::dvec3& lo, const glm::dvec3& hi);
  // The kept parameters of the line p + t·w: [*t0, *t1], each ±inf where no
  // plane bounds it; false (and *t0 > *t1) when the line keeps nothing.
  bool interval(const glm::dvec3& p, const glm::dvec3& w, double* t0, double* t1) const;
  // Whether the convex hull of the points keeps nothing of positive volume:
  // every point on or outside one plane.
  bool excludes(const glm::dvec3* pts, int n) const;
};

}  // namespace zs
