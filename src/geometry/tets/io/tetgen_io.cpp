#include "geometry/tets/io/tetgen_io.h"

#include <tetgen.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <vector>

#include "geometry/tets/io/stdio_capture.h"
#include "base/util/file_error.h"

namespace zs {

namespace fs = std::filesystem;

namespace {

// TetGen copies the base name into fixed 1024-byte buffers.
constexpr size_t kMaxBase = 1000;

std::string base_of(const std::string& path) {
  return fs::path(path).replace_extension("").string();
}

// The first number line of a TetGen file (comments start with '#'). TetGen
// trusts these counts blindly (new[] of whatever the header says), so we check
// them against the file size before handing the file over.
std::vector<long long> header_numbers(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw FileError(file, "cannot open for reading");
  std::string line;
  while (std::getline(in, line)) {
    size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::vector<long long> nums;
    const char* s = line.c_str();
    char* end = nullptr;
    while (true) {
      while (*s == ' ' || *s == '\t' || *s == ',' || *s == '\r') ++s;
      if (!*s) break;
      long long v = std::strtoll(s, &end, 10);
      if (end == s) throw FileError(file, "header is not a list of integers");
      nums.push_back(v);
      s = end;
    }
    if (!nums.empty()) return nums;
  }
  throw FileError(file, "empty file (no header line)");
}

void check_count(const std::string& file, long long n, long long min_bytes_each,
                 const char* what) {
  if (n <= 0) throw FileError(file, std::string("header gives no ") + what);
  std::error_code ec;
  auto size = static_cast<long long>(fs::file_size(file, ec));
  if (ec) throw FileError(file, "cannot stat file");
  if (n > INT_MAX || n * min_bytes_each > size)
    throw FileError(file, "header says " + std::to_string(n) + " " + what +
                              " but the file is only " + std::to_string(size) + " bytes");
}

void require_file(const std::string& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) throw FileError(file, "no such file");
}

}  // namespace

TetMesh read_tetgen(const std::string& path) {
  const std::string base = base_of(path);
  const std::string node_file = base + ".node", ele_file = base + ".ele";
  if (base.size() > kMaxBase) throw FileError(path, "path too long for TetGen");
  require_file(node_file);
  require_file(ele_file);

  auto nh = header_numbers(node_file);
  check_count(node_file, nh[0], 8, "points");  // "i x y z" is at least 8 bytes
  if (nh.size() > 1 && nh[1] != 3)
    throw FileError(node_file, "dimension is " + std::to_string(nh[1]) + ", expected 3");
  auto eh = header_numbers(ele_file);
  check_count(ele_file, eh[0], 10, "tetrahedra");
  if (eh.size() > 1 && eh[1] != 4 && eh[1] != 10)
    throw FileError(ele_file, "tets have " + std::to_string(eh[1]) + " corners, expected 4 or 10");

  tetgenio io;
  std::vector<char> buf(base.begin(), base.end());
  buf.push_back('\0');

  // Load one file at a time so an error names the right one.
  auto load = [&](const std::string& file, bool (tetgenio::*fn)(char*)) {
    StdioCapture cap;
    bool ok = false;
    std::string fallback = "TetGen could not read the file";
    try {
      ok = (io.*fn)(buf.data());
    } catch (const std::bad_alloc&) {
      fallback = "out of memory";
    } catch (...) {  // TetGen throws int from terminatetetgen()
    }
    std::string out = cap.finish();
    if (!ok) throw FileError(file, tetgen_error_line(out, fallback));
  };
  load(node_file, &tetgenio::load_node);
  load(ele_file, &tetgenio::load_tet);

  TetMesh m;
  const size_t np = static_cast<size_t>(io.numberofpoints);
  m.points.resize(np);
  for (size_t i = 0; i < np; ++i)
    m.points[i] = {io.pointlist[3 * i], io.pointlist[3 * i + 1], io.pointlist[3 * i + 2]};
  if (io.numberofpointattributes > 0 && io.pointattributelist) {
    const size_t na = static_cast<size_t>(io.numberofpointattributes);
    m.scalars.resize(np);
    for (size_t i = 0; i < np; ++i) m.scalars[i] = io.pointattributelist[i * na];
    if (na > 1) m.notes.push_back("TetGen: " + std::to_string(na) + " point attributes, using the first");
  }

  // Indices in the file count from the first point's number (0 or 1).
  const long long first = io.firstnumber;
  const size_t nt = static_cast<size_t>(io.numberoftetrahedra);
  const size_t nc = static_cast<size_t>(io.numberofcorners);
  m.tets.resize(nt);
  for (size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 4; ++k) {
      long long v = static_cast<long long>(io.tetrahedronlist[t * nc + k]) - first;
      if (v < 0 || v >= static_cast<long long>(np))
        throw FileError(ele_file, "tet " + std::to_string(t + first) + " has vertex index " +
                                      std::to_string(v + first) + " out of range");
      m.tets[t][k] = static_cast<uint32_t>(v);
    }
  }
  if (nc == 10) m.notes.push_back("TetGen: second-order tets, using the 4 corners");
  return m;
}

void write_tetgen(const std::string& path, const TetMesh& m) {
  const std::string base = base_of(path);
  const std::string node_file = base + ".node", ele_file = base + ".ele";
  if (base.size() > kMaxBase) throw FileError(path, "path too long for TetGen");
  if (m.points.size() > INT_MAX / 3 || m.tets.size() > INT_MAX / 4)
    throw FileError(path, "mesh too large for the TetGen format");

  // tetgenio frees its arrays with delete[] in its destructor.
  tetgenio io;
  io.firstnumber = 0;
  io.mesh_dim = 3;
  io.numberofpoints = static_cast<int>(m.points.size());
  io.pointlist = new REAL[3 * m.points.size()];
  for (size_t i = 0; i < m.points.size(); ++i) {
    io.pointlist[3 * i] = m.points[i].x;
    io.pointlist[3 * i + 1] = m.points[i].y;
    io.pointlist[3 * i + 2] = m.points[i].z;
  }
  if (m.has_scalars()) {
    io.numberofpointattributes = 1;
    io.pointattributelist = new REAL[m.points.size()];
    for (size_t i = 0; i < m.points.size(); ++i) io.pointattributelist[i] = m.scalars[i];
  }
  io.numberofcorners = 4;
  io.numberoftetrahedra = static_cast<int>(m.tets.size());
  io.tetrahedronlist = new int[4 * m.tets.size()];
  for (size_t t = 0; t < m.tets.size(); ++t)
    for (int k = 0; k < 4; ++k) io.tetrahedronlist[4 * t + k] = static_cast<int>(m.tets[t][k]);

  // TetGen's save_* do not check fopen (they crash on an unwritable path), so
  // make sure both files can be created first.
  for (const std::string& f : {node_file, ele_file}) {
    std::FILE* fp = std::fopen(f.c_str(), "w");
    if (!fp) throw FileError(f, std::string("cannot write: ") + std::strerror(errno));
    std::fclose(fp);
  }

  std::vector<char> buf(base.begin(), base.end());
  buf.push_back('\0');
  std::string out;
  errno = 0;
  {
    StdioCapture cap;
    try {
      io.save_nodes(buf.data());
      io.save_elements(buf.data());
    } catch (...) {  // terminatetetgen() throws int when fopen fails
    }
    out = cap.finish();
  }
  // save_* return nothing; a failed fopen only shows up as a printed message.
  for (const std::string& f : {node_file, ele_file}) {
    std::error_code ec;
    if (!fs::exists(f, ec) || out.find("Cannot create") != std::string::npos)
      throw FileError(f, tetgen_error_line(out, "cannot write"));
  }
  // Nor do they check their writes: a full disk or a file size limit
  // leaves short files behind a success. Read them back and compare.
  const int write_errno = errno;
  bool whole = false;
  try {
    const TetMesh back = read_tetgen(node_file);
    whole = back.points.size() == m.points.size() && back.tets.size() == m.tets.size();
  } catch (const std::exception&) {
  }
  if (!whole)
    throw FileError(path, std::string("cannot write: the files came out incomplete") +
                              (write_errno ? std::string(": ") + std::strerror(write_errno) : std::string()));
}

}  // namespace zs
