// Hand-written PDB reader: the format is fixed-column text, and reading it
// ourselves lets every error name its line like the other readers.
#include "geometry/spheres/pdb_reader.h"

#include <cctype>
#include <cmath>
#include <cstdio>

#include "base/util/file_error.h"
#include "base/util/text_lines.h"
#include "geometry/spheres/elements.h"
#include "geometry/spheres/vdw_radii.h"

namespace zs {

namespace {

// Columns [first, first + width) of the line, 0-based, clipped to its length.
std::string_view columns(std::string_view line, size_t first, size_t width) {
  if (first >= line.size()) return {};
  return line.substr(first, width);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

bool is_alpha(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }

// The element of an atom whose element field is blank, by the convention for
// atom names (columns 13-16): a one-letter element is written from column
// 14, a two-letter one from column 13 (" CA " is carbon, "CA  " calcium).
std::string_view element_from_name(std::string_view name) {
  if (name.size() < 2) return {};
  if (name[0] == ' ' || std::isdigit(static_cast<unsigned char>(name[0])))
    return is_alpha(name[1]) ? name.substr(1, 1) : std::string_view{};
  if (!is_alpha(name[0])) return {};
  return is_alpha(name[1]) ? name.substr(0, 2) : name.substr(0, 1);
}

struct Record {
  std::string_view line;
  const char* kind;  // "ATOM" or "HETATM", for messages
  size_t line_no;
};

double coordinate(const Record& r, const std::string& name, size_t first, char axis) {
  const std::string_view field = trim(columns(r.line, first, 8));
  const std::string cols = " (columns " + std::to_string(first + 1) + "-" + std::to_string(first + 8) + ")";
  const auto v = parse_number(field);
  if (!v) throw FileError(name, r.line_no, std::string(r.kind) + ": " + axis + " coordinate " + quoted_token(field) +
                                               " is not a number" + cols);
  if (!std::isfinite(*v))
    throw FileError(name, r.line_no, std::string(r.kind) + ": non-finite " + axis + " coordinate " +
                                         quoted_token(field) + cols);
  return *v;
}

}  // namespace

SphereSet parse_pdb(std::string_view text, const std::string& name) {
  SphereSet s;
  size_t unknown = 0, no_bfactor_line = 0;
  char first_alt = ' ';
  TextLines lines(text);
  std::string_view line;
  while (lines.next(line)) {
    const size_t line_no = lines.line_no();
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.starts_with("ENDMDL")) break;  // model 1 only
    const bool atom = line.starts_with("ATOM"), hetatm = line.starts_with("HETATM");
    if (!atom && !hetatm) continue;
    const Record r{line, atom ? "ATOM" : "HETATM", line_no};
    if (line.size() < 54)
      throw FileError(name, line_no, std::string(r.kind) + " record too short: " + std::to_string(line.size()) +
                                         " columns, coordinates need columns 31-54");
    const glm::dvec3 c{coordinate(r, name, 30, 'x'), coordinate(r, name, 38, 'y'), coordinate(r, name, 46, 'z')};

    // Alternate locations: keep the first one the file names (usually 'A').
    const char alt = line[16];
    if (alt != ' ') {
      if (first_alt == ' ') first_alt = alt;
      if (alt != first_alt) {
        ++s.skipped;
        continue;
      }
    }

    std::string_view element = trim(columns(line, 76, 2));
    if (element.empty()) element = element_from_name(columns(line, 12, 4));
    double radius = kDefaultVdwRadius;
    if (!vdw_radius(element, radius)) ++unknown;
    s.element.push_back(static_cast<uint8_t>(atomic_number(element)));

    const auto b = parse_number(trim(columns(line, 60, 6)));
    if (!b && no_bfactor_line == 0) no_bfactor_line = line_no;
    s.centres.push_back(c);
    s.radii.push_back(radius);
    s.scalars.push_back(b ? *b : 0.0);
  }
  if (s.centres.empty()) throw FileError(name, "no ATOM or HETATM records in model 1");
  if (no_bfactor_line) {
    s.scalars.clear();
    s.notes.push_back("no B-factor (columns 61-66) on line " + std::to_string(no_bfactor_line) + ": no scalar");
  } else {
    s.scalar_name = "b_factor";
    for (double v : s.scalars)
      if (!std::isfinite(v)) ++s.degenerate;
  }
  if (unknown) {
    char r[32];
    std::snprintf(r, sizeof r, "%g", kDefaultVdwRadius);
    s.notes.push_back(std::to_string(unknown) + " atoms of an element without a tabulated radius: " + r + " Å");
  }
  if (s.skipped) s.notes.push_back(std::to_string(s.skipped) + " alternate locations skipped (kept '" +
                                   std::string(1, first_alt) + "')");
  return s;
}

SphereSet read_pdb(const std::string& path) { return parse_pdb(read_text_file(path), path); }

}  // namespace zs
