#include "spheres/parse_number.h"

#include <charconv>
#include <cstdlib>
#include <string>

namespace zs {

std::optional<double> parse_number(std::string_view tok) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b != e && *b == '+') ++b;  // from_chars rejects a leading '+'
  double v = 0.0;
  auto [p, ec] = std::from_chars(b, e, v);
  if (b == e || (ec != std::errc() && ec != std::errc::result_out_of_range) || p != e) return std::nullopt;
  // from_chars leaves v untouched when out of range (off_io's finding 2):
  // take strtod's ±inf or underflowed value instead.
  if (ec == std::errc::result_out_of_range) v = std::strtod(std::string(b, e).c_str(), nullptr);
  return v;
}

std::string quoted_token(std::string_view s) {
  if (s.size() > 24) return "'" + std::string(s.substr(0, 24)) + "...'";
  return "'" + std::string(s) + "'";
}

}  // namespace zs
