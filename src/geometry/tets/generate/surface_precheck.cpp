// The OFF check follows CGAL 5.5's File_header_OFF and File_scanner_OFF
// (ASCII: header tokens, then one line per vertex and per face) closely
// enough to see the counts CGAL will allocate for.
#include "geometry/tets/generate/surface_precheck.h"

#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "base/util/file_error.h"

namespace zs {

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string fmt_number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

bool is_ws(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// A cursor over the OFF text with the stream operations CGAL's scanner uses.
struct OffText {
  std::string_view t;
  size_t pos = 0;

  size_t line_at(size_t p) const {  // 1-based line of p, for messages only (linear)
    size_t n = 1;
    for (size_t i = 0; i < p && i < t.size(); ++i) n += t[i] == '\n';
    return n;
  }
  size_t line() const { return line_at(pos); }
  void skip_ws() {
    while (pos < t.size() && is_ws(t[pos])) ++pos;
  }
  // CGAL's skip_comment_OFF: whitespace and '#' comments to the end of line.
  void skip_comments() {
    for (skip_ws(); pos < t.size() && t[pos] == '#'; skip_ws()) {
      while (pos < t.size() && t[pos] != '\n') ++pos;
    }
  }
  // `in >> int`: whitespace, a sign, digits; false where the stream fails.
  bool read_int(long long& v) {
    skip_ws();
    size_t p = pos;
    bool neg = false;
    if (p < t.size() && (t[p] == '+' || t[p] == '-')) neg = t[p++] == '-';
    if (p >= t.size() || !std::isdigit(static_cast<unsigned char>(t[p]))) return false;
    long long x = 0;
    for (; p < t.size() && std::isdigit(static_cast<unsigned char>(t[p])); ++p) {
      x = x * 10 + (t[p] - '0');
      if (x > INT_MAX + 1LL) return false;  // out of int range: the stream fails
    }
    if (!neg && x > INT_MAX) return false;
    pos = p;
    v = neg ? -x : x;
    return true;
  }
  std::string_view getline() {
    const size_t e = std::min(t.find('\n', pos), t.size());
    std::string_view l = t.substr(pos, e - pos);
    pos = e < t.size() ? e + 1 : e;
    return l;
  }
};

// The numbers on a face line. CGAL reads them with `istream >> double`,
// which takes a number's prefix of a token ("4888bsp" is 4888, then stops):
// we refuse any token that is not wholly a plain decimal number instead,
// and return it in `bad`.
std::vector<double> face_numbers(std::string_view line, std::string& bad) {
  std::vector<double> v;
  size_t i = 0;
  while (true) {
    while (i < line.size() && is_ws(line[i])) ++i;
    if (i >= line.size()) return v;
    size_t j = i;
    while (j < line.size() && !is_ws(line[j])) ++j;
    const std::string tok(line.substr(i, j - i));
    char* end = nullptr;
    const double d = std::strtod(tok.c_str(), &end);
    if (tok.find_first_not_of("+-.0123456789eE") != std::string::npos || end != tok.c_str() + tok.size()) {
      bad = tok.substr(0, 24);
      return v;
    }
    v.push_back(d);
    i = j;
  }
}

}  // namespace

void precheck_off(const std::string& path) {
  const std::string text = slurp(path);
  OffText in{text};
  in.skip_comments();
  // The keyword: [ST][C][N][4][n]OFF or SKEL in CGAL.
  const size_t k0 = in.pos;
  if (in.pos < text.size()) ++in.pos;
  while (in.pos < text.size() && std::isalnum(static_cast<unsigned char>(text[in.pos]))) ++in.pos;
  std::string_view kw = std::string_view(text).substr(k0, in.pos - k0);
  if (in.pos < text.size()) ++in.pos;  // CGAL consumes the character after the keyword
  // CGAL 5.5 indexes past the numbers on a vertex line for colours (C) and
  // texture coordinates (ST): plain and homogeneous (4OFF) OFF only.
  const std::string full(kw.substr(0, 24));
  if (kw.starts_with("4")) kw.remove_prefix(1);
  if (kw != "OFF" && kw.ends_with("OFF"))
    throw FileError(path, in.line_at(k0), "OFF variant '" + full + "' is not supported (expected OFF or 4OFF)");
  if (kw != "OFF") throw FileError(path, "not an OFF surface (no OFF header)");
  in.skip_comments();
  if (text.compare(in.pos, 6, "BINARY") == 0) throw FileError(path, in.line(), "binary OFF is not supported");

  long long nv = 0, nf = 0, ne = 0;
  if (in.pos >= text.size() || !std::isdigit(static_cast<unsigned char>(text[in.pos])) || !in.read_int(nv) ||
      !in.read_int(nf) || nf < 0 || !in.read_int(ne))
    return;  // CGAL fails on this header by itself, allocating nothing
  const size_t header_line = in.line();  // once; the face loop below must stay linear
  // CGAL doubles the edge count in an int.
  if (ne > INT_MAX / 2 || ne < INT_MIN / 2)
    throw FileError(path, header_line, "OFF header: edge count " + std::to_string(ne) + " is too large");
  // Each vertex and face is a line of at least two bytes.
  const size_t left = text.size() - in.pos;
  if (static_cast<uint64_t>(nv + nf) > left / 2 + 1)
    throw FileError(path, header_line,
                    "OFF header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                        " faces, more than the remaining " + std::to_string(left) + " bytes can hold");
  for (long long i = 0; i < nv; ++i) {
    in.skip_comments();
    if (in.pos >= text.size()) return;  // CGAL reports the short file
    in.getline();
  }
  for (long long f = 0; f < nf; ++f) {
    in.skip_comments();
    if (in.pos >= text.size()) return;
    const size_t start = in.pos;
    std::string_view l = in.getline();
    l = l.substr(0, l.find('#'));
    std::string bad;
    const std::vector<double> v = face_numbers(l, bad);
    if (!bad.empty())
      throw FileError(path, in.line_at(start), "OFF face " + std::to_string(f) + ": '" + bad + "' is not a number");
    if (v.empty()) return;  // CGAL fails on an empty face line by itself
    // CGAL sizes the face by its first number before it reads the indices,
    // and casts every number to size_t (undefined for a negative double).
    if (!(v[0] >= 0.0 && v[0] <= static_cast<double>(v.size() - 1)))
      throw FileError(path, in.line_at(start), "OFF face " + std::to_string(f) + ": corner count '" +
                                                   std::string(l.substr(0, std::min<size_t>(l.find_first_of(" \t\r"), 24))) +
                                                   "' does not match the " + std::to_string(v.size() - 1) +
                                                   " numbers after it");
    for (size_t k = 1; k <= static_cast<size_t>(v[0]); ++k)
      if (!(v[k] >= 0.0 && v[k] < static_cast<double>(nv)))
        throw FileError(path, in.line_at(start), "OFF face " + std::to_string(f) + ": vertex index " +
                                                     fmt_number(v[k]) + " out of range (" + std::to_string(nv) +
                                                     " vertices, 0-based)");
  }
}

void precheck_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof head);
  const std::streamsize got = in.gcount();
  if (got >= 6 && std::string_view(head, 5) == "solid" && is_ws(head[5])) return;  // ASCII
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec || got < 84) throw FileError(path, "binary STL shorter than its 84-byte header");
  uint32_t n = 0;
  std::memcpy(&n, head + 80, 4);  // little-endian, as is the machine
  if (size != 84 + 50 * uint64_t(n))
    throw FileError(path, "binary STL: " + std::to_string(n) + " triangles need " +
                              std::to_string(84 + 50 * uint64_t(n)) + " bytes, the file has " + std::to_string(size));
}

void precheck_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  std::string line, element;
  bool have_element = false;
  uint64_t items = 0;
  auto is_one_of = [](const std::string& w, std::initializer_list<const char*> set) {
    for (const char* s : set)
      if (w == s) return true;
    return false;
  };
  for (size_t n = 1; n <= 10000 && std::getline(in, line); ++n) {
    std::istringstream words(line);
    std::string w, a, b, c;
    words >> w;
    if (n == 1 && w != "ply") throw FileError(path, 1, "not a PLY file (no 'ply' magic)");
    if (n <= 2) continue;  // CGAL takes line 2 as the format whatever it says ("end_header ascii 1.0": a finding)
    if (w == "element") {
      words >> element >> a;
      // CGAL reads the count as size_t: "-1" became 2^64 - 1 items, and an
      // element without properties looped over them for ever (a finding).
      // An item takes at least one byte.
      if (a.empty() || a.size() > 18 || a.find_first_not_of("0123456789") != std::string::npos)
        throw FileError(path, n, "PLY header: element count '" + a.substr(0, 24) + "' is not a number of items");
      items += std::stoull(a);
      if (items > size) throw FileError(path, n, "PLY header: element counts exceed the file's " + std::to_string(size) + " bytes");
      have_element = true;
    }
    if (w == "property") {
      if (!have_element) throw FileError(path, n, "PLY header: property before any element");
      std::string d;
      words >> a >> b >> c >> d;  // type name | list count-type entry-type name
      const bool list = a == "list";
      const std::string& name = list ? d : b;
      // A list's length is read, then that many entries allocated, before
      // anything checks it: allow 16 bits at most.
      if (list && !is_one_of(b, {"char", "uchar", "int8", "uint8", "short", "ushort", "int16", "uint16"}))
        throw FileError(path, n, "PLY header: list count type '" + b + "' (at most 16 bits: uchar or ushort)");
      const bool vertex = element == "vertex" || element == "vertices";
      if (vertex && (name == "x" || name == "y" || name == "z") &&
          (list || !is_one_of(a, {"float", "float32", "double", "float64"})))
        throw FileError(path, n, "PLY header: vertex coordinate '" + name + "' must be float or double");
      // With a uchar `red` (or r) and a uchar g, CGAL reads `green` as uchar
      // whatever it was declared: colours are uchar or absent.
      const bool face = element == "face" || element == "faces";
      if ((vertex || face) && is_one_of(name, {"red", "green", "blue", "r", "g", "b"}) &&
          (list || !is_one_of(a, {"uchar", "uint8"})))
        throw FileError(path, n, "PLY header: " + element + " colour '" + name + "' must be uchar");
      if (element == "halfedge" && (name == "source" || name == "target") && (list || !is_one_of(a, {"uint", "uint32"})))
        throw FileError(path, n, "PLY header: halfedge '" + name + "' must be uint");
    }
    if (w == "end_header") return;
  }
  throw FileError(path, "PLY header: no end_header");
}

}  // namespace zs
