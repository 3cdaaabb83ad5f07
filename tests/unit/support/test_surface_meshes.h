// Small triangle meshes shared by the surface tests (the reader, the
// projection, the shadow map and the surface renderer): the unit cube as six
// OFF quads, read back through read_surface, a square hung over a ground, and
// a perspective camera.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "base/view/camera.h"
#include "geometry/triangles/io/surface_reader.h"
#include "support/test_paths.h"

namespace zs::test {

inline void write_text(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

// The unit cube [0, 1]³ as six quads, counter-clockwise from outside.
inline const char* const kCubeQuads =
    "OFF\n8 6 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";

// kCubeQuads written to the test's scratch directory and read back, with
// point normals.
inline TriangleMesh cube() {
  const auto dir = scratch_dir();
  write_text(dir / "cube.off", kCubeQuads);
  TriangleMesh m = read_surface((dir / "cube.off").string());
  compute_point_normals(m);
  return m;
}

// A square occluder of side 1 at height 1 (surface 0) over the ground square
// [-3, 3]² at y = 0 (surface 1), both facing up; no point normals.
inline TriangleMesh square_over_ground() {
  TriangleMesh m;
  m.points = {{-0.5, 1, -0.5}, {0.5, 1, -0.5}, {0.5, 1, 0.5}, {-0.5, 1, 0.5},   // occluder
              {-3, 0, -3},     {3, 0, -3},     {3, 0, 3},     {-3, 0, 3}};       // ground
  m.tris = {{0, 2, 1}, {0, 3, 2}, {4, 6, 5}, {4, 7, 6}};
  m.surface = {0, 0, 1, 1};
  return m;
}

// A perspective camera from `eye` looking at `target`, `fov_y` degrees high.
inline Camera perspective_camera(const glm::dvec3& eye, const glm::dvec3& target, double fov_y) {
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = eye;
  cam.target = target;
  cam.fov_y = fov_y;
  return cam;
}

}  // namespace zs::test
