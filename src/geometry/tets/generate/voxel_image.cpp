#include "geometry/tets/generate/voxel_image.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <CGAL/Image_3.h>

#include "geometry/tets/io/stdio_capture.h"
#include "base/util/file_error.h"

namespace zs {

double VoxelImage::sample(const glm::dvec3& p) const {
  glm::dvec3 g = (p - origin) / spacing;
  auto split = [](double x, size_t n, size_t& i0, double& f) {
    x = std::clamp(x, 0.0, static_cast<double>(n - 1));
    i0 = std::min(static_cast<size_t>(x), n > 1 ? n - 2 : 0);
    f = n > 1 ? x - static_cast<double>(i0) : 0.0;
  };
  size_t i, j, k;
  double fx, fy, fz;
  split(g.x, nx, i, fx);
  split(g.y, ny, j, fy);
  split(g.z, nz, k, fz);
  const size_t i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, ny - 1), k1 = std::min(k + 1, nz - 1);
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  double c00 = lerp(at(i, j, k), at(i1, j, k), fx), c10 = lerp(at(i, j1, k), at(i1, j1, k), fx);
  double c01 = lerp(at(i, j, k1), at(i1, j, k1), fx), c11 = lerp(at(i, j1, k1), at(i1, j1, k1), fx);
  return lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz);
}

VoxelImage read_voxel_image(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw FileError(path, "no such file");
  CGAL::Image_3 img;
  bool ok;
  {
    StdioCapture quiet(2);  // ImageIO explains failures on stderr; we say one line
    ok = img.read(path);
  }
  if (!ok) throw FileError(path, "cannot read 3D image (expected .inr/.inr.gz, .hdr, ...)");
  return voxel_image_from(img, path);
}

VoxelImage voxel_image_from(const CGAL::Image_3& img, const std::string& path) {
  if (img.image()->vdim != 1) throw FileError(path, "image has vector voxels; expected one value per voxel");
  VoxelImage v;
  v.nx = img.xdim();
  v.ny = img.ydim();
  v.nz = img.zdim();
  if (v.nx == 0 || v.ny == 0 || v.nz == 0) throw FileError(path, "image is empty");
  v.spacing = {img.vx(), img.vy(), img.vz()};
  v.origin = {img.tx(), img.ty(), img.tz()};
  v.values.resize(v.nx * v.ny * v.nz);
  size_t n = 0;
  for (size_t k = 0; k < v.nz; ++k)
    for (size_t j = 0; j < v.ny; ++j)
      for (size_t i = 0; i < v.nx; ++i) v.values[n++] = img.value(i, j, k);
  return v;
}

}  // namespace zs
