// Hand-written .sph reader, line by line so every error names its line (the
// model is geometry/tets/io/off_io.cpp).
#include "geometry/spheres/sphere_reader.h"

#include <cmath>

#include "geometry/spheres/sphere_validity.h"
#include "base/util/file_error.h"
#include "base/util/text_lines.h"

namespace zs {

namespace {

[[noreturn]] void fail_at(const std::string& name, size_t line, const std::string& what) {
  throw FileError(name, line, what);
}

constexpr size_t kMax = 8;  // x y z r R G B A
constexpr const char* kForms = "expected 'x y z r', 'x y z r scalar' or 'x y z r R G B A' (4, 5 or 8 numbers)";

}  // namespace

SphereSet parse_spheres(std::string_view text, const std::string& name) {
  SphereSet s;
  TextLines lines(text);
  std::string_view line;
  size_t first_fields = 0, first_line = 0;  // the first sphere line fixes the form
  while (lines.next(line)) {
    const size_t line_no = lines.line_no();
    std::string_view tok[kMax];
    const size_t n = split_tokens(line, tok, kMax);
    if (n == 0 || tok[0][0] == '#') continue;
    if (n != 4 && n != 5 && n != 8)
      fail_at(name, line_no, std::string(kForms) + ", found " + std::to_string(n) + (n > kMax ? "+" : "") + " fields");
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
    if (n == 8)
      for (size_t k = 4; k < 8; ++k)
        if (!valid_rgba_component(v[k]))
          fail_at(name, line_no, std::string(1, "RGBA"[k - 4]) + " " + quoted_token(tok[k]) + " is not in [0, 1]");
    if (!drawable_sphere(v[0], v[1], v[2], v[3])) {
      ++s.invalid;
      continue;
    }
    s.centres.push_back({v[0], v[1], v[2]});
    s.radii.push_back(v[3]);
    if (n == 5) {
      s.scalars.push_back(v[4]);
      if (!std::isfinite(v[4])) ++s.degenerate;
    }
    if (n == 8) s.rgba.push_back({float(v[4]), float(v[5]), float(v[6]), float(v[7])});
  }
  if (first_fields == 0) throw FileError(name, "no spheres (expected lines 'x y z r [scalar | R G B A]')");
  if (s.centres.empty())
    throw FileError(name, "no drawable spheres: all " + std::to_string(s.invalid) +
                              " have a zero, negative or non-finite radius or a non-finite centre");
  if (first_fields == 5) s.scalar_name = "scalar";
  if (s.invalid)
    s.notes.push_back(std::to_string(s.invalid) + " spheres skipped: zero, negative or non-finite radius, or non-finite centre");
  return s;
}

SphereSet read_spheres(const std::string& path) { return parse_spheres(read_text_file(path), path); }

}  // namespace zs
