#include "base/util/text_lines.h"

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/util/file_error.h"

namespace zs {

std::string read_text_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw FileError(path, "is a directory, not a file");  // as require_input_file
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw FileError(path, "read error");
  return ss.str();
}

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
}  // namespace

size_t split_tokens(std::string_view line, std::string_view* tok, size_t max) {
  size_t n = 0, i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    if (i >= line.size()) break;
    size_t j = i;
    while (j < line.size() && !is_space(line[j])) ++j;
    if (n < max) tok[n] = line.substr(i, j - i);
    if (++n > max) break;
    i = j;
  }
  return n;
}

std::optional<double> parse_number(std::string_view tok) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b != e && *b == '+') ++b;  // from_chars rejects a leading '+'
  double v = 0.0;
  auto [p, ec] = std::from_chars(b, e, v);
  if (b == e || (ec != std::errc() && ec != std::errc::result_out_of_range) || p != e) return std::nullopt;
  // Out of range (1e999, 1e-400) is still a number in the file, but
  // from_chars leaves v untouched then (read as 0 before a fuzzer found it):
  // take strtod's ±inf or underflowed value, and let validation count them.
  if (ec == std::errc::result_out_of_range) v = std::strtod(std::string(b, e).c_str(), nullptr);
  return v;
}

std::string quoted_token(std::string_view s) {
  if (s.size() > 24) return "'" + std::string(s.substr(0, 24)) + "...'";
  return "'" + std::string(s) + "'";
}

}  // namespace zs
