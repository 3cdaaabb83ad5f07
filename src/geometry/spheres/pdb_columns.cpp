// The fixed-column checks of PDB records before gemmi parses them
// (pdb_columns.h). gemmi reads the rest; this keeps our one-line errors.
#include "geometry/spheres/pdb_columns.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "base/util/file_error.h"
#include "base/util/text_lines.h"

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

// SSBOND, LINK and CISPEP as gemmi knows them: the first four characters,
// any case.
bool connection_record(std::string_view line) {
  if (line.size() < 4) return false;
  char up[4];
  for (int i = 0; i < 4; ++i) up[i] = static_cast<char>(std::toupper(static_cast<unsigned char>(line[i])));
  const std::string_view u(up, 4);
  return u == "SSBO" || u == "LINK" || u == "CISP";
}

bool is_alpha(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Columns 77-78 name an element: letters (or blanks) only.
bool element_field_ok(std::string_view f) {
  for (char c : f)
    if (c != ' ' && !is_alpha(c)) return false;
  return true;
}

// Columns 79-80 hold a charge: blank, or a digit and a sign ("2+", "+2").
bool charge_field_ok(std::string_view f) {
  if (trim(f).empty()) return true;
  if (f.size() != 2) return false;
  const auto sign = [](char c) { return c == '+' || c == '-' || c == ' '; };
  return (is_digit(f[0]) && sign(f[1])) || (sign(f[0]) && is_digit(f[1]));
}

void check_coordinate(std::string_view line, const char* kind, size_t line_no, const std::string& name,
                      size_t first, char axis) {
  const std::string_view field = trim(columns(line, first, 8));
  const std::string cols = " (columns " + std::to_string(first + 1) + "-" + std::to_string(first + 8) + ")";
  const auto v = parse_number(field);
  if (!v) throw FileError(name, line_no, std::string(kind) + ": " + axis + " coordinate " + quoted_token(field) +
                                             " is not a number" + cols);
  if (!std::isfinite(*v))
    throw FileError(name, line_no, std::string(kind) + ": non-finite " + axis + " coordinate " +
                                       quoted_token(field) + cols);
}

}  // namespace

PdbText prepare_pdb_text(std::string_view text, const std::string& name) {
  PdbText out;
  out.text.reserve(text.size());
  TextLines lines(text);
  std::string_view line;
  while (lines.next(line)) {
    const size_t line_no = lines.line_no();
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    // gemmi ends a line at a NUL byte and reads on after it as if a new line
    // began (found by scripts/fuzz, pdb): a NUL is no text, so a blank here.
    std::string no_nul;
    if (line.find('\0') != std::string_view::npos) {
      no_nul.assign(line);
      std::replace(no_nul.begin(), no_nul.end(), '\0', ' ');
      line = no_nul;
    }
    const bool atom = line.starts_with("ATOM"), hetatm = line.starts_with("HETATM");
    if (!atom && !hetatm) {
      out.text.append(line);
      // gemmi reads the connection records by their columns without looking
      // at the line's length (found by scripts/fuzz, pdb): padded to the
      // format's 80 columns, what is missing reads as blank, as the format says.
      if (connection_record(line) && line.size() < 80) out.text.append(80 - line.size(), ' ');
      out.text.push_back('\n');
      continue;
    }
    const char* kind = atom ? "ATOM" : "HETATM";
    if (line.size() < 54)
      throw FileError(name, line_no, std::string(kind) + " record too short: " + std::to_string(line.size()) +
                                         " columns, coordinates need columns 31-54");
    check_coordinate(line, kind, line_no, name, 30, 'x');
    check_coordinate(line, kind, line_no, name, 38, 'y');
    check_coordinate(line, kind, line_no, name, 46, 'z');
    ++out.atoms;
    if (!out.line_of_first_atom) out.line_of_first_atom = line_no;
    if (!out.line_without_b && !parse_number(trim(columns(line, 60, 6)))) out.line_without_b = line_no;
    std::string rec(line);
    if (!element_field_ok(columns(rec, 76, 2))) {
      rec.replace(76, std::min<size_t>(2, rec.size() - 76), std::min<size_t>(2, rec.size() - 76), ' ');
      ++out.element_cleared;
    }
    if (trim(columns(rec, 76, 2)).empty()) ++out.element_blank;
    if (rec.size() > 78 && !charge_field_ok(columns(rec, 78, 2))) {
      rec.resize(78);
      ++out.charge_cleared;
    }
    out.text.append(rec).push_back('\n');
  }
  return out;
}

}  // namespace zs
