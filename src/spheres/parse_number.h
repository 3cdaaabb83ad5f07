// Reads one number token the way the mesh readers do: the whole token must
// be a decimal or scientific number (a leading '+' allowed); values beyond a
// double's range are ±inf or the underflowed value, not an error.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace zs {

std::optional<double> parse_number(std::string_view tok);

// At most 24 characters of s in single quotes, for error messages.
std::string quoted_token(std::string_view s);

}  // namespace zs
