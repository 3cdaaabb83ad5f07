// The binary sphere list .sphb and the sphere writers (src/geometry/spheres/).
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "geometry/spheres/generate/portable_random.h"
#include "geometry/spheres/sphere_binary.h"
#include "geometry/spheres/sphere_io.h"
#include "geometry/spheres/sphere_reader.h"
#include "geometry/spheres/sphere_writer.h"
#include "support/file_error_of.h"
#include "support/test_paths.h"
#include "base/util/file_error.h"

namespace zs {
namespace {

using test::error_of;

// A .sphb image by hand, independent of the writer.
std::string sphb(uint32_t fields, uint64_t count, const std::vector<float>& values, uint32_t reserved = 0) {
  std::string b("ZSSPHB1\n", 8);
  auto put = [&](const void* p, size_t n) { b.append(static_cast<const char*>(p), n); };  // the host is little-endian
  put(&fields, 4), put(&reserved, 4), put(&count, 8);
  put(values.data(), values.size() * 4);
  return b;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Random floats of every kind of magnitude, colours in [0, 1].
SphereSet random_float_set(size_t n, bool rgba, bool scalar) {
  PortableRandom rng(42);
  SphereSet s;
  auto f = [&] { return double(float(rng.uniform(-1, 1) * std::pow(10.0, rng.uniform(-30, 30)))); };
  for (size_t i = 0; i < n; ++i) {
    s.centres.push_back({f(), f(), f()});
    s.radii.push_back(double(float(std::fabs(f()) + 1e-30)));
    if (scalar) s.scalars.push_back(f());
    if (rgba) s.rgba.push_back({float(rng.uniform()), float(rng.uniform()), float(rng.uniform()), float(rng.uniform())});
  }
  if (scalar) s.scalar_name = "scalar";
  return s;
}

bool same_floats(const SphereSet& a, const SphereSet& b) {
  if (a.size() != b.size() || a.rgba.size() != b.rgba.size() || a.scalars.size() != b.scalars.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a.centres[i] != b.centres[i] || a.radii[i] != b.radii[i]) return false;
    if (a.has_rgba() && a.rgba[i] != b.rgba[i]) return false;
    if (a.has_scalars() && std::memcmp(&a.scalars[i], &b.scalars[i], 8) != 0) return false;
  }
  return true;
}

TEST(SphereBinary, ReadsTheDocumentedLayout) {
  const SphereSet s = parse_spheres_binary(sphb(8, 2, {1, 2, 3, 0.5f, 1, 0, 0.25f, 0.5f, -1, -2, -3, 2, 0, 1, 1, 1}), "a.sphb");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.centres[1], glm::dvec3(-1, -2, -3));
  EXPECT_EQ(s.radii[0], 0.5);
  EXPECT_EQ(s.rgba[0], glm::vec4(1, 0, 0.25f, 0.5f));
  const SphereSet t = parse_spheres_binary(sphb(5, 1, {1, 2, 3, 4, 9}), "a.sphb");
  EXPECT_EQ(t.scalars, std::vector<double>{9.0});
  EXPECT_EQ(t.scalar_name, "scalar");
  const SphereSet u = parse_spheres_binary(sphb(4, 1, {1, 2, 3, 4}), "a.sphb");
  EXPECT_FALSE(u.has_rgba() || u.has_scalars());
}

TEST(SphereBinary, InvalidSpheresSkippedLikeTheTextReader) {
  const float inf = INFINITY, nan = NAN;
  const SphereSet s = parse_spheres_binary(
      sphb(5, 6, {0, 0, 0, 1, nan, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1, inf, 0, 0, 1, 1, 0, 0, 0, nan, 1, 5, 5, 5, 2, 3}), "a.sphb");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.invalid, 4u);
  EXPECT_EQ(s.degenerate, 1u);
  EXPECT_EQ(s.centres[1], glm::dvec3(5, 5, 5));
}

TEST(SphereBinary, ErrorsNameTheFile) {
  EXPECT_EQ(error_of([] { parse_spheres_binary("ZSSPHB2\n0000000000000000", "a.sphb"); }),
            "a.sphb: not a .sphb file (it does not start with \"ZSSPHB1\\n\")");
  EXPECT_EQ(error_of([] { parse_spheres_binary("ZSS", "a.sphb"); }),
            "a.sphb: not a .sphb file (it does not start with \"ZSSPHB1\\n\")");
  EXPECT_EQ(error_of([] { parse_spheres_binary(sphb(4, 1, {}).substr(0, 20), "a.sphb"); }),
            "a.sphb: truncated: 20 bytes, shorter than the 24-byte header");
  EXPECT_EQ(error_of([] { parse_spheres_binary(sphb(6, 1, {1, 2, 3, 4, 5, 6}), "a.sphb"); }),
            "a.sphb: field count 6 in the header (expected 4, 5 or 8)");
  EXPECT_EQ(error_of([] { parse_spheres_binary(sphb(4, 1, {1, 2, 3, 4}, 7), "a.sphb"); }),
            "a.sphb: reserved header field is 7 (expected 0)");
  EXPECT_EQ(error_of([] { parse_spheres_binary(sphb(4, 0, {}), "a.sphb"); }), "a.sphb: no spheres (the header's count is 0)");
  EXPECT_EQ(error_of([] { parse_spheres_binary(sphb(4, 2, {1, 2, 3, 4, 5, 6, 7}), "a.sphb"); }),
            "a.sphb: truncated: the header says 2 spheres of 4 floats (56 bytes), the file has 52 bytes");
  // A count whose byte size overflows 64 bits is "truncated", not a wrap-around.
  EXPECT_EQ(error_of([] { parse_spheres_binary(sphb(8, ~0ull / 4, {1, 2, 3, 4}), "a.sphb"); }).substr(0, 40),
            "a.sphb: truncated: the header says 46116");
  EXPECT_EQ(error_of([] { parse_spheres_binary(sphb(4, 1, {1, 2, 3, 4}) + "x", "a.sphb"); }),
            "a.sphb: 1 bytes after the 1 spheres the header announces");
  EXPECT_EQ(error_of([] { parse_spheres_binary(sphb(8, 2, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 1.5f, 0, 1}), "a.sphb"); }),
            "a.sphb: sphere 1: G 1.5 is not in [0, 1]");
  EXPECT_EQ(error_of([] { parse_spheres_binary(sphb(4, 1, {0, 0, 0, -1}), "a.sphb"); }),
            "a.sphb: no drawable spheres: all 1 have a zero, negative or non-finite radius or a non-finite centre");
}

TEST(SphereBinary, FileRoundTripIsBitExactAndMatchesTheMemoryReader) {
  const auto dir = test::scratch_dir();
  for (unsigned fields : {4u, 5u, 8u}) {
    const SphereSet s = random_float_set(70000, fields == 8, fields == 5);  // more than one read chunk
    const std::string path = (dir / ("r" + std::to_string(fields) + ".sphb")).string();
    write_spheres(path, s);
    EXPECT_EQ(std::filesystem::file_size(path), 24 + 70000ull * fields * 4);
    const SphereSet back = read_sphere_file(path);
    EXPECT_TRUE(same_floats(s, back)) << fields;
    EXPECT_TRUE(same_floats(back, parse_spheres_binary(slurp(path), path))) << fields;
    // Through text and back to binary: the same bytes.
    const std::string text = (dir / ("r" + std::to_string(fields) + ".sph")).string();
    write_spheres(text, back);
    const std::string again = (dir / ("again" + std::to_string(fields) + ".sphb")).string();
    write_spheres(again, read_sphere_file(text));
    EXPECT_EQ(slurp(path), slurp(again)) << fields;
  }
}

TEST(SphereBinary, TruncatedAndExtraBytesOnDisk) {
  const auto dir = test::scratch_dir();
  const std::string path = (dir / "t.sphb").string();
  write_spheres(path, random_float_set(10, true, false));
  std::filesystem::resize_file(path, 24 + 9 * 32 + 5);
  EXPECT_EQ(error_of([&] { read_spheres_binary(path); }),
            path + ": truncated: the header says 10 spheres of 8 floats (344 bytes), the file has 317 bytes");
  std::filesystem::resize_file(path, 24 + 10 * 32 + 8);
  EXPECT_EQ(error_of([&] { read_spheres_binary(path); }), path + ": 8 bytes after the 10 spheres the header announces");
}

TEST(SphereWriter, TextIsShortAndExact) {
  SphereSet s;
  s.centres = {{0.1, double(0.1f), 1e300}};
  s.radii = {0.5};
  s.rgba = {{0.1f, 0.f, 1.f, 0.25f}};
  EXPECT_EQ(format_spheres_text(s), "# x y z r R G B A\n0.1 0.1 1e+300 0.5 0.1 0 1 0.25\n");
  const SphereSet back = parse_spheres(format_spheres_text(s), "s.sph");
  EXPECT_EQ(back.centres[0].x, 0.1);          // a double comes back exactly
  EXPECT_EQ(float(back.centres[0].y), 0.1f);  // a float comes back as that float
  EXPECT_EQ(back.centres[0].z, 1e300);
  EXPECT_EQ(back.rgba[0], s.rgba[0]);
}

TEST(SphereWriter, FailureLeavesNoFile) {
  const auto dir = test::scratch_dir();
  SphereSet s;
  s.centres = {{0, 0, 0}, {1e300, 0, 0}};
  s.radii = {1, 1};
  const std::string path = (dir / "big.sphb").string();
  EXPECT_EQ(error_of([&] { write_spheres(path, s); }),
            path + ": cannot write sphere 1: centre or radius is not finite or beyond float32's range");
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 0);
  const std::string nodir = (dir / "no" / "a.sph").string();
  EXPECT_NE(error_of([&] { write_spheres(nodir, s); }).find(nodir + ": cannot write"), std::string::npos);
  EXPECT_EQ(error_of([&] { write_spheres((dir / "a.xyz").string(), s); }),
            (dir / "a.xyz").string() + ": unknown sphere output format (expected .sph or .sphb)");
}

}  // namespace
}  // namespace zs
