// Shared pieces of the hand-written text readers (.off, .sph, .pdb): whole
// file in memory, line by line with line numbers, whitespace tokens, and one
// number parse, so every reader rejects and reports the same way.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace zs {

// Throws FileError naming the file when it cannot be opened or read, or is a
// directory.
std::string read_text_file(const std::string& path);

// Walks text one line at a time ('\n'-separated; a '\r' before it stays in
// the line), counting lines from 1.
class TextLines {
 public:
  explicit TextLines(std::string_view text) : text_(text) {}

  // The next line, or false at the end of the text.
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_no_;
    return true;
  }

  size_t line_no() const { return line_no_; }
  size_t bytes_left() const { return pos_ < text_.size() ? text_.size() - pos_ : 0; }

 private:
  std::string_view text_;
  size_t pos_ = 0, line_no_ = 0;
};

// Splits line at spaces, tabs, '\r', '\f' and '\v' into tok[0..max). Returns
// the token count, capped at max + 1 so that "too many fields" is still seen.
size_t split_tokens(std::string_view line, std::string_view* tok, size_t max);

// One number token: the whole token must be a decimal or scientific number
// (a leading '+' allowed). Values beyond a double's range are ±inf or the
// underflowed value, not an error (robustness.md, finding 2).
std::optional<double> parse_number(std::string_view tok);

// At most 24 characters of s in single quotes, for error messages.
std::string quoted_token(std::string_view s);

}  // namespace zs
