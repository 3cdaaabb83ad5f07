// The .zsm format: exact round trips, and a one-line FileError naming the
// file for every kind of damage (truncation anywhere, bad magic, a newer
// version, any byte flipped, headers whose counts the file cannot hold,
// vertex indices out of range), without allocating for a lying header.
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include <gtest/gtest.h>

#include "base/util/checksum.h"
#include "base/util/file_error.h"
#include "geometry/tets/io/mesh_io.h"
#include "geometry/tets/io/zsm_io.h"
#include "support/file_error_of.h"
#include "support/test_paths.h"

namespace zs {
namespace {

namespace fs = std::filesystem;
using test::error_of;

// Header offsets (docs/mesh.md, "The .zsm format").
constexpr size_t kPointsAt = 16, kTetsAt = 24, kNotesAt = 32, kSecTable = 40, kHeaderSum = 184;
constexpr const char* kSecName[4] = {"points", "scalars", "tets", "strings"};

TetMesh sample_mesh() {
  TetMesh m;
  m.points = {{0.1, 1e-300, -3.5e12}, {1.0 / 3.0, 2, 3}, {4, 5, 6.25}, {7, 8, 9},
              {-0.0, 5e-324, 1.7976931348623157e308}};
  m.scalars = {0.1, 0.2, 1.0 / 7.0, -5, 42};
  m.tets = {{0, 1, 2, 3}, {3, 2, 1, 4}, {4, 0, 1, 2}};
  m.scalar_name = "Température";  // UTF-8
  m.scalar_choice = "'Density' is constant (1)";
  m.notes = {"cell data averaged to points", "", std::string("a\0b", 3)};
  return m;
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
void put_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}
std::string zsm_bytes(const TetMesh& m) {
  const std::string p = (test::scratch_dir() / "bytes.zsm").string();
  write_zsm(p, m);
  return file_bytes(p);
}

uint64_t get_u64(const std::string& b, size_t at) {
  uint64_t v;
  std::memcpy(&v, b.data() + at, 8);
  return v;
}
void set_u64(std::string& b, size_t at, uint64_t v) { std::memcpy(b.data() + at, &v, 8); }
uint64_t sec_offset(const std::string& b, int s) { return get_u64(b, kSecTable + 24 * s); }
uint64_t sec_size(const std::string& b, int s) { return get_u64(b, kSecTable + 24 * s + 8); }

// Recomputes every checksum, so that a deliberate change reaches the checks
// behind them (counts, layout, indices, strings).
void reseal(std::string& b) {
  for (int s = 0; s < 4; ++s) {
    const uint64_t off = sec_offset(b, s), size = sec_size(b, s);
    if (off <= b.size() && size <= b.size() - off)
      set_u64(b, kSecTable + 24 * s + 16, checksum64(b.data() + off, size));
  }
  set_u64(b, kHeaderSum, checksum64(b.data(), kHeaderSum));
}

// Bit-identical, NaN payloads and -0 included.
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
void expect_same(const TetMesh& a, const TetMesh& b) {
  EXPECT_TRUE(same_bits(a.points, b.points));
  EXPECT_TRUE(same_bits(a.scalars, b.scalars));
  EXPECT_TRUE(same_bits(a.cell_scalars, b.cell_scalars));
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.scalar_name, b.scalar_name);
  EXPECT_EQ(a.scalar_choice, b.scalar_choice);
  EXPECT_EQ(a.notes, b.notes);
}

// One line, naming the file, saying `what`.
void expect_error(const std::string& message, const std::string& name, const std::string& what) {
  EXPECT_EQ(message, name + ": " + what);
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(ZsmIo, RoundTripIsBitExact) {
  TetMesh m = sample_mesh();
  m.points[0].x = std::numeric_limits<double>::infinity();
  m.points[1].y = -std::numeric_limits<double>::infinity();
  m.points[2].z = std::bit_cast<double>(uint64_t(0x7ff8dead'beef0001));  // a NaN with a payload
  m.scalars[3] = std::bit_cast<double>(uint64_t(0xfff0000000000001));    // a signalling NaN
  const auto dir = test::scratch_dir();
  const std::string p = (dir / "rt.zsm").string();
  write_zsm(p, m);
  expect_same(read_zsm(p), m);
  expect_same(parse_zsm(file_bytes(p), "mem"), m);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), {}), 1);  // no temporary left beside it
}

TEST(ZsmIo, RoundTripWithoutScalarsOrStrings) {
  TetMesh m = sample_mesh();
  m.scalars.clear();
  m.scalar_name.clear();
  m.scalar_choice.clear();
  m.notes.clear();
  const TetMesh r = parse_zsm(zsm_bytes(m), "mem");
  EXPECT_FALSE(r.has_scalars());
  expect_same(r, m);
}

TEST(ZsmIo, CellScalarsRoundTrip) {
  TetMesh m = sample_mesh();
  m.scalars.clear();
  for (size_t t = 0; t < m.num_tets(); ++t) m.cell_scalars.push_back(0.5 + double(t) / 3);
  m.cell_scalars[0] = std::bit_cast<double>(uint64_t(0x7ff8dead'beef0001));
  const TetMesh r = parse_zsm(zsm_bytes(m), "mem");
  EXPECT_FALSE(r.has_scalars());
  EXPECT_TRUE(r.has_cell_scalars());
  expect_same(r, m);
  m.cell_scalars.pop_back();
  EXPECT_THROW(zsm_bytes(m), FileError);
}

TEST(ZsmIo, EmptyMeshRoundTrips) {
  const std::string b = zsm_bytes(TetMesh{});
  EXPECT_EQ(b.size(), kZsmHeaderBytes + 16u);  // the header and two empty strings
  expect_same(parse_zsm(b, "mem"), TetMesh{});
}

// The layout docs/mesh.md gives: magic, version, counts, sections in order
// at multiples of 64, the file ending with the strings.
TEST(ZsmIo, LayoutIsTheDocumentedOne) {
  const TetMesh m = sample_mesh();
  const std::string b = zsm_bytes(m);
  EXPECT_EQ(b.substr(0, 8), std::string("ZSWMESH\0", 8));
  EXPECT_EQ(b.substr(8, 8), std::string("\1\0\0\0\1\0\0\0", 8));  // version 1, flags: scalars
  EXPECT_EQ(get_u64(b, kPointsAt), 5u);
  EXPECT_EQ(get_u64(b, kTetsAt), 3u);
  EXPECT_EQ(get_u64(b, kNotesAt), 3u);
  const uint64_t sizes[4] = {5 * 24, 5 * 8, 3 * 16, 8 * 5 + 12 + 25 + 28 + 3};
  uint64_t at = 192;
  for (int s = 0; s < 4; ++s) {
    at = (at + 63) / 64 * 64;
    EXPECT_EQ(sec_offset(b, s), at) << kSecName[s];
    EXPECT_EQ(sec_size(b, s), sizes[s]) << kSecName[s];
    EXPECT_EQ(get_u64(b, kSecTable + 24 * s + 16), checksum64(b.data() + at, sizes[s])) << kSecName[s];
    at += sizes[s];
  }
  EXPECT_EQ(b.size(), at);
  EXPECT_EQ(std::memcmp(b.data() + sec_offset(b, 0), m.points.data(), 5 * 24), 0);
  EXPECT_EQ(std::memcmp(b.data() + sec_offset(b, 2), m.tets.data(), 3 * 16), 0);
  EXPECT_EQ(get_u64(b, kHeaderSum), checksum64(b.data(), kHeaderSum));
  EXPECT_EQ(b.find_first_not_of('\0', 136), kHeaderSum);  // reserved bytes are zero
}

// The writer's bytes for one tet are those of the fuzz seed written with
// the format's first version: the format does not change by accident.
TEST(ZsmIo, OneTetIsTheSeedFileByteForByte) {
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.scalars = {0, 1, 2, 3};
  m.tets = {{0, 1, 2, 3}};
  m.scalar_name = "scalar";
  EXPECT_EQ(zsm_bytes(m), file_bytes(test::test_data("../fuzz/corpus/zsm/one_tet.zsm")));
}

TEST(ZsmIo, TruncatedHeaderAtEveryLength) {
  const std::string b = zsm_bytes(sample_mesh());
  const auto dir = test::scratch_dir();
  for (size_t n = 0; n <= kZsmHeaderBytes; ++n) {
    const std::string p = (dir / ("cut" + std::to_string(n) + ".zsm")).string();
    put_file(p, b.substr(0, n));
    const std::string e = error_of([&] { read_zsm(p); });
    if (n == 0)
      expect_error(e, p, "empty file (a .zsm file starts with a 192-byte header)");
    else if (n < kZsmHeaderBytes)
      expect_error(e, p, "truncated: " + std::to_string(n) + " bytes, shorter than the 192-byte header");
    else
      expect_error(e, p, "truncated: the points section needs 120 bytes from byte 192, the file has 192");
    EXPECT_EQ(e, error_of([&] { parse_zsm(b.substr(0, n), p); }));
  }
}

TEST(ZsmIo, TruncatedInsideEverySection) {
  const std::string b = zsm_bytes(sample_mesh());
  for (size_t n = kZsmHeaderBytes; n < b.size(); ++n) {
    const std::string e = error_of([&] { parse_zsm(b.substr(0, n), "cut.zsm"); });
    int s = 0;
    while (s < 3 && sec_offset(b, s) + sec_size(b, s) <= n) ++s;  // the first section past the cut
    expect_error(e, "cut.zsm", std::string("truncated: the ") + kSecName[s] + " section needs " +
                                   std::to_string(sec_size(b, s)) + " bytes from byte " +
                                   std::to_string(sec_offset(b, s)) + ", the file has " + std::to_string(n));
  }
}

TEST(ZsmIo, NotAZsmFile) {
  std::string b = zsm_bytes(sample_mesh());
  b[3] = 'X';
  expect_error(error_of([&] { parse_zsm(b, "m.zsm"); }), "m.zsm", "not a .zsm file (bad magic)");
  expect_error(error_of([&] { parse_zsm("4 1\n0 0 0 0\n", "m.zsm"); }), "m.zsm", "not a .zsm file (bad magic)");
  expect_error(error_of([&] { parse_zsm("ZSW", "m.zsm"); }), "m.zsm",
               "truncated: 3 bytes, shorter than the 192-byte header");
}

TEST(ZsmIo, NewerVersionIsNamed) {
  std::string b = zsm_bytes(sample_mesh());
  b[8] = 7;  // checked before the header's checksum: a newer header may differ
  expect_error(error_of([&] { parse_zsm(b, "v.zsm"); }), "v.zsm", "version 7 is newer than this zsweep reads (1)");
  b[8] = 0;
  reseal(b);
  expect_error(error_of([&] { parse_zsm(b, "v.zsm"); }), "v.zsm", "version 0 in the header (versions start at 1)");
}

TEST(ZsmIo, ChecksumMismatchInEachSection) {
  const std::string b = zsm_bytes(sample_mesh());
  for (int s = 0; s < 4; ++s) {
    std::string c = b;
    c[sec_offset(b, s) + sec_size(b, s) / 2] ^= 0x10;
    expect_error(error_of([&] { parse_zsm(c, "c.zsm"); }), "c.zsm",
                 std::string("checksum mismatch in the ") + kSecName[s] + " section");
  }
  std::string c = b;
  c[kTetsAt] ^= 1;
  expect_error(error_of([&] { parse_zsm(c, "c.zsm"); }), "c.zsm", "checksum mismatch in the header");
}

// Every byte has a check: magic, version, checksums, zero padding.
TEST(ZsmIo, AnyFlippedByteIsAnError) {
  const std::string b = zsm_bytes(sample_mesh());
  for (size_t i = 0; i < b.size(); ++i)
    for (unsigned char bit : {0x01, 0x80}) {
      std::string c = b;
      c[i] = char(c[i] ^ bit);
      const std::string e = error_of([&] { parse_zsm(c, "f.zsm"); });
      EXPECT_EQ(e.rfind("f.zsm: ", 0), 0u) << "byte " << i << ": " << e;
      EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
  std::string c = b;
  c[sec_offset(b, 0) + sec_size(b, 0)] = 1;  // padding after the points
  expect_error(error_of([&] { parse_zsm(c, "f.zsm"); }), "f.zsm", "the padding before the scalars section is not zero");
}

// Counts the file cannot hold are refused before anything is allocated: a
// FileError, not bad_alloc, and not seconds of zero-filling.
TEST(ZsmIo, CountsBeyondTheFileAreRefusedBeforeAllocating) {
  const std::string b = zsm_bytes(sample_mesh());
  const std::string n = std::to_string(b.size());
  auto with = [&](size_t at, uint64_t v) {
    std::string c = b;
    set_u64(c, at, v);
    reseal(c);
    return error_of([&] { parse_zsm(c, "big.zsm"); });
  };
  expect_error(with(kPointsAt, 1000), "big.zsm",
               "truncated: the header says 1000 points (24000 bytes), the file has " + n + " bytes");
  expect_error(with(kPointsAt, uint64_t(1) << 60), "big.zsm",
               "truncated: the header says 1152921504606846976 points (over 2^64 bytes), the file has " + n + " bytes");
  expect_error(with(kTetsAt, uint64_t(1) << 40), "big.zsm",
               "truncated: the header says 1099511627776 tets (17592186044416 bytes), the file has " + n + " bytes");
  expect_error(with(kTetsAt, ~uint64_t(0)), "big.zsm",
               "truncated: the header says 18446744073709551615 tets (over 2^64 bytes), the file has " + n + " bytes");
  expect_error(with(kNotesAt, uint64_t(1) << 62), "big.zsm",
               "truncated: the header says 4611686018427387904 notes (over 2^64 bytes), the file has " + n + " bytes");
  // Counts the file could hold, that the sections do not.
  expect_error(with(kPointsAt, 4), "big.zsm", "the points section is 120 bytes, 4 points need 96");
  expect_error(with(kTetsAt, 2), "big.zsm", "the tets section is 48 bytes, 2 tets need 32");
  expect_error(with(kNotesAt, 40), "big.zsm", "the strings section is 108 bytes, too short for 42 strings");
  expect_error(with(kSecTable + 24 * 2 + 8, 1u << 20), "big.zsm", "the tets section is 1048576 bytes, 3 tets need 48");
  expect_error(with(kSecTable + 24 * 1, 384), "big.zsm", "the scalars section starts at byte 384 (expected 320)");
  std::string c = b + std::string(5, '\0');
  expect_error(error_of([&] { parse_zsm(c, "big.zsm"); }), "big.zsm",
               "5 bytes after the last section, which ends at byte " + n);
}

TEST(ZsmIo, HeaderFieldsThisVersionDoesNotDefine) {
  std::string b = zsm_bytes(sample_mesh());
  b[12] = 5;
  reseal(b);
  expect_error(error_of([&] { parse_zsm(b, "h.zsm"); }), "h.zsm",
               "unknown flags 0x5 in the header (version 1 defines 0x1, point scalars, or 0x2, cell scalars)");
  b[12] = 3;
  reseal(b);
  expect_error(error_of([&] { parse_zsm(b, "h.zsm"); }), "h.zsm",
               "contradictory flags 0x3 in the header (version 1 defines 0x1, point scalars, or 0x2, cell scalars)");
  // Point scalars read as cell scalars: the section's size is checked against the tets.
  b[12] = 2;
  reseal(b);
  EXPECT_NE(error_of([&] { parse_zsm(b, "h.zsm"); }).find("the scalars section is"), std::string::npos);
  b = zsm_bytes(sample_mesh());
  b[150] = 1;
  reseal(b);
  expect_error(error_of([&] { parse_zsm(b, "h.zsm"); }), "h.zsm", "reserved header byte 150 is not zero");
}

TEST(ZsmIo, VertexIndexOutOfRange) {
  std::string b = zsm_bytes(sample_mesh());
  b[sec_offset(b, 2) + 16 + 8] = 9;  // tet 1, its third index
  reseal(b);
  expect_error(error_of([&] { parse_zsm(b, "i.zsm"); }), "i.zsm",
               "tet 1: vertex index 9 out of range (mesh has 5 vertices, indices are 0-based)");
  TetMesh m = sample_mesh();
  m.tets[2][3] = 5;
  const std::string p = (test::scratch_dir() / "w.zsm").string();
  expect_error(error_of([&] { write_zsm(p, m); }), p,
               "cannot write: tet 2: vertex index 5 out of range (mesh has 5 vertices, indices are 0-based)");
  EXPECT_FALSE(fs::exists(p));
}

TEST(ZsmIo, MalformedStringsBehindAValidChecksum) {
  std::string b = zsm_bytes(sample_mesh());
  const uint64_t at = sec_offset(b, 3);
  set_u64(b, at, 1000);  // scalar_name's length
  reseal(b);
  expect_error(error_of([&] { parse_zsm(b, "s.zsm"); }), "s.zsm",
               "string 0 of the strings section is 1000 bytes, past its end");
  b = zsm_bytes(sample_mesh());
  set_u64(b, at + sec_size(b, 3) - 3 - 8, 1);  // the last note, "a\0b", one byte long: two are left over
  reseal(b);
  expect_error(error_of([&] { parse_zsm(b, "s.zsm"); }), "s.zsm",
               "the strings section has 2 bytes after its last string");
}

TEST(ZsmIo, DispatchByExtension) {
  EXPECT_EQ(format_of("a/b.zsm"), MeshFormat::Zsm);
  EXPECT_EQ(format_of("B.ZSM"), MeshFormat::Zsm);
  const auto dir = test::scratch_dir();
  const std::string p = (dir / "d.zsm").string();
  const TetMesh m = sample_mesh();
  write_mesh(p, m);
  expect_same(read_mesh(p), m);
  ReadOptions named;
  named.scalar = m.scalar_name;
  expect_same(read_mesh(p, named), m);
  named.scalar = "nosuch";
  expect_error(error_of([&] { read_mesh(p, named); }), p, "no array named 'nosuch'; available: Température (point)");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), {}), 1);
}

TEST(ZsmIo, WriteToAMissingDirectoryLeavesNoFile) {
  const std::string p = "/nonexistent-dir-zsweep/out.zsm";
  const std::string e = error_of([&] { write_mesh(p, sample_mesh()); });
  expect_error(e, p, "cannot write: No such file or directory");
  EXPECT_FALSE(fs::exists(p));
}

TEST(ZsmIo, MissingFileAndDirectory) {
  expect_error(error_of([] { read_mesh("/nonexistent-dir-zsweep/in.zsm"); }), "/nonexistent-dir-zsweep/in.zsm",
               "no such file");
  const std::string d = (test::scratch_dir() / "dir.zsm").string();
  fs::create_directory(d);
  expect_error(error_of([&] { read_zsm(d); }), d, "is a directory, not a mesh file");
}

}  // namespace
}  // namespace zs
