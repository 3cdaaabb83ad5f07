// Classic tet OFF reader/writer. Hand-written because no library reads this
// variant; it is line-oriented so every error can name its line.
#include "geometry/tets/io/off_io.h"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <limits>

#include "base/util/file_error.h"
#include "base/util/text_lines.h"

namespace zs {

namespace {

// Walks the text one significant line at a time (skipping blank and '#'
// lines), splitting each into whitespace-separated tokens.
class LineCursor {
 public:
  LineCursor(std::string_view text, const std::string& name) : lines_(text), name_(name) {}

  // Advances to the next significant line; false at end of text.
  bool next() {
    std::string_view line;
    while (lines_.next(line)) {
      ntok_ = split_tokens(line, tok_, kMaxTok);
      if (ntok_ > 0 && tok_[0][0] != '#') return true;
    }
    ntok_ = 0;
    return false;
  }

  size_t line() const { return lines_.line_no(); }
  size_t count() const { return ntok_; }
  std::string_view token(size_t i) const { return tok_[i]; }
  size_t bytes_left() const { return lines_.bytes_left(); }

  [[noreturn]] void fail(const std::string& what) const { throw FileError(name_, lines_.line_no(), what); }

 private:
  static constexpr size_t kMaxTok = 8;
  TextLines lines_;
  const std::string& name_;
  std::string_view tok_[kMaxTok];
  size_t ntok_ = 0;
};

double parse_double(const LineCursor& cur, std::string_view tok) {
  const auto v = parse_number(tok);
  if (!v) cur.fail("expected a number, found " + quoted_token(tok));
  return *v;
}

// Counts in the header: non-negative integers that fit in 32 bits.
uint64_t parse_count(const LineCursor& cur, std::string_view tok, const char* what) {
  if (!tok.empty() && tok[0] == '-') cur.fail(std::string("negative ") + what + " count " + quoted_token(tok));
  uint64_t v = 0;
  auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && p == tok.data() + tok.size() &&
                                               v > std::numeric_limits<uint32_t>::max()))
    cur.fail(std::string(what) + " count " + quoted_token(tok) + " is too large");
  if (ec != std::errc() || p != tok.data() + tok.size())
    cur.fail(std::string("expected the ") + what + " count, found " + quoted_token(tok));
  return v;
}

uint32_t parse_index(const LineCursor& cur, std::string_view tok, uint64_t n_points) {
  if (!tok.empty() && tok[0] == '-') cur.fail("negative vertex index " + quoted_token(tok));
  uint64_t v = 0;
  auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && p == tok.data() + tok.size() && v >= n_points))
    cur.fail("vertex index " + std::string(tok) + " out of range (mesh has " +
             std::to_string(n_points) + " vertices, indices are 0-based)");
  if (ec != std::errc() || p != tok.data() + tok.size())
    cur.fail("expected a vertex index, found " + quoted_token(tok));
  return static_cast<uint32_t>(v);
}

}  // namespace

TetMesh parse_off(std::string_view text, const std::string& name) {
  LineCursor cur(text, name);
  if (!cur.next()) throw FileError(name, "empty file: expected 'n_vertices n_tets'");

  // Header: both counts on one line, or one per line.
  uint64_t n_pts = 0, n_tets = 0;
  if (cur.count() == 2) {
    n_pts = parse_count(cur, cur.token(0), "vertex");
    n_tets = parse_count(cur, cur.token(1), "tet");
  } else if (cur.count() == 1) {
    n_pts = parse_count(cur, cur.token(0), "vertex");
    if (!cur.next()) throw FileError(name, cur.line(), "file ends before the tet count");
    if (cur.count() != 1) cur.fail("expected the tet count alone on this line");
    n_tets = parse_count(cur, cur.token(0), "tet");
  } else {
    cur.fail("expected 'n_vertices n_tets' header, found " + std::to_string(cur.count()) + " tokens");
  }

  // Each vertex line needs at least 8 bytes ("0 0 0 0\n"), each tet line too:
  // refuse counts the file cannot hold before allocating for them.
  const uint64_t need = 8 * (n_pts + n_tets);
  if (need > cur.bytes_left() + 8)
    cur.fail("header declares " + std::to_string(n_pts) + " vertices and " + std::to_string(n_tets) +
             " tets, more than the remaining " + std::to_string(cur.bytes_left()) + " bytes can hold");

  TetMesh m;
  m.points.resize(n_pts);
  m.scalars.resize(n_pts);
  m.tets.resize(n_tets);
  m.scalar_name = "scalar";

  for (uint64_t i = 0; i < n_pts; ++i) {
    if (!cur.next())
      throw FileError(name, cur.line(), "file ends after " + std::to_string(i) + " of " +
                                            std::to_string(n_pts) + " vertices");
    if (cur.count() != 4)
      cur.fail("vertex " + std::to_string(i) + ": expected 'x y z s' (4 numbers), found " +
               std::to_string(cur.count()) + (cur.count() > 8 ? "+" : "") + " tokens");
    m.points[i] = {parse_double(cur, cur.token(0)), parse_double(cur, cur.token(1)),
                   parse_double(cur, cur.token(2))};
    m.scalars[i] = parse_double(cur, cur.token(3));
  }
  for (uint64_t t = 0; t < n_tets; ++t) {
    if (!cur.next())
      throw FileError(name, cur.line(), "file ends after " + std::to_string(t) + " of " +
                                            std::to_string(n_tets) + " tets");
    if (cur.count() != 4)
      cur.fail("tet " + std::to_string(t) + ": expected 4 vertex indices, found " +
               std::to_string(cur.count()) + (cur.count() > 8 ? "+" : "") + " tokens");
    for (int k = 0; k < 4; ++k) m.tets[t][k] = parse_index(cur, cur.token(k), n_pts);
  }
  if (cur.next()) cur.fail("unexpected data after the last tet (header declares " + std::to_string(n_tets) + " tets)");
  return m;
}

TetMesh read_off(const std::string& path) { return parse_off(read_text_file(path), path); }

void write_off(const std::string& path, const TetMesh& m) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw FileError(path, std::string("cannot write: ") + std::strerror(errno));
  std::string buf;
  buf.reserve(1 << 16);
  auto flush = [&] {
    if (!buf.empty() && std::fwrite(buf.data(), 1, buf.size(), f) != buf.size()) {
      std::fclose(f);
      throw FileError(path, std::string("write failed: ") + std::strerror(errno));
    }
    buf.clear();
  };
  auto put_num = [&](double v, char sep) {
    char tmp[40];
    // Shortest representation that reads back to the same double.
    auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
    buf.append(tmp, r.ptr);
    buf.push_back(sep);
  };
  buf += std::to_string(m.points.size()) + "\n" + std::to_string(m.tets.size()) + "\n";
  for (size_t i = 0; i < m.points.size(); ++i) {
    put_num(m.points[i].x, ' ');
    put_num(m.points[i].y, ' ');
    put_num(m.points[i].z, ' ');
    put_num(m.has_scalars() ? m.scalars[i] : 0.0, '\n');
    if (buf.size() > (1 << 16)) flush();
  }
  for (const Tet& t : m.tets) {
    for (int k = 0; k < 4; ++k) {
      buf += std::to_string(t[k]);
      buf.push_back(k < 3 ? ' ' : '\n');
    }
    if (buf.size() > (1 << 16)) flush();
  }
  flush();
  if (std::fclose(f) != 0) throw FileError(path, std::string("write failed: ") + std::strerror(errno));
}

}  // namespace zs
