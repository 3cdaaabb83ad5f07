#include "geometry/spheres/generate/pore_balls.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <stdexcept>

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkImageEuclideanDistance.h>
#include <vtkImageInterpolator.h>
#include <vtkImageResize.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include "geometry/spheres/generate/demo_image.h"
#include "geometry/spheres/generate/portable_random.h"
#include "base/util/file_error.h"

namespace zs {

namespace {

constexpr const char* kMember = "data/images/skull_2.9.inr";
constexpr float kThreshold = 2.9f;

struct Ball {
  size_t voxel;
  float radius;  // in voxels of the resized image
};

// Pore voxels -> their distance to the solid, at upsampling f.
std::vector<Ball> maximal_balls(const ScalarImage& img, int f, size_t* dims) {
  vtkNew<vtkImageData> src;
  src->SetDimensions(int(img.nx), int(img.ny), int(img.nz));
  vtkNew<vtkFloatArray> vals;
  vals->SetArray(const_cast<float*>(img.values.data()), vtkIdType(img.values.size()), 1);  // borrowed
  src->GetPointData()->SetScalars(vals);

  vtkNew<vtkImageResize> resize;
  vtkNew<vtkImageInterpolator> linear;
  linear->SetInterpolationModeToLinear();
  resize->SetInterpolator(linear);
  resize->SetInputData(src);
  resize->SetResizeMethodToOutputDimensions();
  const int n[3] = {int(img.nx) * f, int(img.ny) * f, int(img.nz) * f};
  resize->SetOutputDimensions(n[0], n[1], n[2]);
  resize->Update();
  vtkImageData* big = resize->GetOutput();
  const size_t total = size_t(n[0]) * n[1] * n[2];
  vtkDataArray* grey = big->GetPointData()->GetScalars();

  // Feature (0) where solid; the transform measures pore voxels' distance to it.
  vtkNew<vtkImageData> mask;
  mask->SetDimensions(n);
  mask->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* m = static_cast<unsigned char*>(mask->GetScalarPointer());
  for (size_t i = 0; i < total; ++i) m[i] = grey->GetComponent(vtkIdType(i), 0) < kThreshold ? 1 : 0;

  vtkNew<vtkImageEuclideanDistance> edt;
  edt->SetInputData(mask);
  edt->InitializeOn();
  edt->ConsiderAnisotropyOff();  // voxel units; world scale applied later
  edt->SetAlgorithmToSaito();
  edt->Update();
  vtkDataArray* d2 = edt->GetOutput()->GetPointData()->GetScalars();  // squared distances
  std::vector<float> d(total);
  for (size_t i = 0; i < total; ++i) d[i] = m[i] ? float(std::sqrt(d2->GetComponent(vtkIdType(i), 0))) : 0.f;

  std::vector<Ball> balls;
  const long sx = 1, sy = n[0], sz = long(n[0]) * n[1];
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        const size_t i = size_t(x * sx + y * sy + z * sz);
        if (!m[i]) continue;
        bool maximal = true;
        for (int dz = -1; dz <= 1 && maximal; ++dz)
          for (int dy = -1; dy <= 1 && maximal; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int X = x + dx, Y = y + dy, Z = z + dz;
              if ((dx | dy | dz) == 0 || X < 0 || Y < 0 || Z < 0 || X >= n[0] || Y >= n[1] || Z >= n[2]) continue;
              const float step = std::sqrt(float(dx * dx + dy * dy + dz * dz));
              if (d[size_t(X * sx + Y * sy + Z * sz)] >= d[i] + step - 1e-4f) {
                maximal = false;
                break;
              }
            }
        if (maximal) balls.push_back({i, d[i]});
      }
  for (int k = 0; k < 3; ++k) dims[k] = size_t(n[k]);
  return balls;
}

}  // namespace

SphereSet generate_c2(size_t count, uint64_t seed, const std::string& tarball, PoreBallsInfo* info) {
  std::error_code ec;
  if (!std::filesystem::exists(tarball, ec))
    throw FileError(tarball, "not found: C2 needs the 3D images of Debian's libcgal-demo (apt-get install libcgal-demo)");
  const ScalarImage img = parse_inr(read_tar_gz_member(tarball, kMember), tarball + ":" + kMember);
  std::vector<Ball> balls;
  size_t dims[3] = {0, 0, 0};
  int f = 1;
  for (; f <= 12; ++f) {
    balls = maximal_balls(img, f, dims);
    if (balls.size() >= count) break;
  }
  if (balls.size() < count)
    throw std::runtime_error("c2: the skull image yields only " + std::to_string(balls.size()) +
                             " maximal balls even resized 12 times; ask for fewer");
  const size_t found = balls.size();
  if (info) *info = {f, found};
  // The `count` largest; stable, so ties keep voxel order.
  std::stable_sort(balls.begin(), balls.end(), [](const Ball& a, const Ball& b) { return a.radius > b.radius; });
  balls.resize(count);
  const float rmin = balls.empty() ? 0.f : balls.back().radius, rmax = balls.empty() ? 1.f : balls.front().radius;
  const size_t opaque = count / 10;  // the largest tenth

  // A voxel's world position: the resized image spans the original extent.
  const glm::dvec3 world = img.spacing / double(f);
  const double rscale = (world.x + world.y + world.z) / 3.0;
  PortableRandom rng(seed);
  SphereSet s;
  s.centres.reserve(count), s.radii.reserve(count), s.rgba.reserve(count);
  for (size_t k = 0; k < count; ++k) {
    const Ball& b = balls[k];
    const size_t x = b.voxel % dims[0], y = b.voxel / dims[0] % dims[1], z = b.voxel / (dims[0] * dims[1]);
    s.centres.push_back(glm::dvec3(double(x), double(y), double(z)) * world);
    s.radii.push_back(double(b.radius) * rscale);
    const float t = rmax > rmin ? (b.radius - rmin) / (rmax - rmin) : 0.f;
    const double u = rng.uniform();
    const float alpha = k < opaque ? float(0.5 + 0.5 * u) : float(0.02 + 0.13 * u);
    s.rgba.push_back({0.2f + 0.8f * t, 0.4f + 0.2f * t, 1.f - 0.8f * t, alpha});
  }
  s.notes.push_back("c2: skull_2.9.inr resized " + std::to_string(f) + "x, " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
                    std::to_string(dims[2]) + " voxels, " + std::to_string(found) + " maximal balls, kept the " + std::to_string(count) + " largest");
  return s;
}

}  // namespace zs
