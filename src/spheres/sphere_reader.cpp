// Hand-written .sph reader, line by line so every error names its line (the
// model is mesh/io/off_io.cpp).
#include "spheres/sphere_reader.h"

#include <cmath>

#include "util/file_error.h"
#include "util/text_lines.h"

namespace zs {

namespace {

[[noreturn]] void fail_at(const std::string& name, size_t line, const std::string& what) {
  throw FileError(name, line, what);
}

constexpr size_t kMax = 5;  // x y z r scalar

}  // namespace

SphereSet parse_spheres(std::string_view text, const std::string& name) {
  SphereSet s;
  TextLines lines(text);
  std::string_view line;
  size_t first_fields = 0, first_line = 0;  // the first sphere line fixes 4 or 5 fields
  while (lines.next(line)) {
    const size_t line_no = lines.line_no();
    std::string_view tok[kMax];
    const size_t n = split_tokens(line, tok, kMax);
    if (n == 0 || tok[0][0] == '#') continue;
    if (n < 4 || n > kMax)
      fail_at(name, line_no, "expected 'x y z r [scalar]' (4 or 5 numbers), found " + std::to_string(n) + (n > kMax ? "+" : "") +
           " fields");
    if (first_fields == 0) {
      first_fields = n;
      first_line = line_no;
    } else if (n != first_fields) {
      fail_at(name, line_no, "expected " + std::to_string(first_fields) + " numbers like line " + std::to_string(first_line) +
           ", found " + std::to_string(n));
    }
    double v[kMax];
    for (size_t k = 0; k < n; ++k) {
      const auto x = parse_number(tok[k]);
      if (!x) fail_at(name, line_no, "expected a number, found " + quoted_token(tok[k]));
      v[k] = *x;
    }
    for (size_t k = 0; k < 3; ++k)
      if (!std::isfinite(v[k])) fail_at(name, line_no, "non-finite coordinate " + quoted_token(tok[k]));
    if (std::isnan(v[3]) || std::isinf(v[3])) fail_at(name, line_no, "non-finite radius " + quoted_token(tok[3]));
    if (v[3] < 0.0) fail_at(name, line_no, "negative radius " + quoted_token(tok[3]));
    s.centres.push_back({v[0], v[1], v[2]});
    s.radii.push_back(v[3]);
    if (n == 5) s.scalars.push_back(v[4]);
    if (v[3] == 0.0 || (n == 5 && !std::isfinite(v[4]))) ++s.degenerate;
  }
  if (s.centres.empty()) throw FileError(name, "no spheres (expected lines 'x y z r [scalar]')");
  if (s.has_scalars()) s.scalar_name = "scalar";
  return s;
}

SphereSet read_spheres(const std::string& path) { return parse_spheres(read_text_file(path), path); }

}  // namespace zs
