// TetGen's library prints progress and errors with printf, CGAL's ImageIO
// with fprintf(stderr). This captures a file descriptor (stdout by default)
// for the duration of a call so our output stays clean, and keeps the text so
// the last "Error:" line can go into a one-line FileError.
#pragma once

#include <cstdio>
#include <string>

#include <unistd.h>

namespace zs {

class StdioCapture {
 public:
  explicit StdioCapture(int fd = 1) : fd_(fd) {
    std::fflush(nullptr);
    tmp_ = std::tmpfile();
    saved_ = ::dup(fd_);
    if (tmp_ && saved_ >= 0) ::dup2(::fileno(tmp_), fd_);
  }
  ~StdioCapture() { finish(); }
  StdioCapture(const StdioCapture&) = delete;
  StdioCapture& operator=(const StdioCapture&) = delete;

  // Restores the descriptor and returns what was printed meanwhile.
  std::string finish() {
    if (done_) return text_;
    done_ = true;
    std::fflush(nullptr);
    if (saved_ >= 0) {
      ::dup2(saved_, fd_);
      ::close(saved_);
    }
    if (tmp_) {
      std::rewind(tmp_);
      char buf[4096];
      size_t n;
      while ((n = std::fread(buf, 1, sizeof buf, tmp_)) > 0) text_.append(buf, n);
      std::fclose(tmp_);
    }
    return text_;
  }

 private:
  int fd_;
  std::FILE* tmp_ = nullptr;
  int saved_ = -1;
  bool done_ = false;
  std::string text_;
};

// The last line of TetGen output mentioning an error, trimmed; `fallback`
// when there is none.
inline std::string tetgen_error_line(const std::string& out, const std::string& fallback) {
  std::string best;
  size_t pos = 0;
  while (pos < out.size()) {
    size_t end = out.find('\n', pos);
    if (end == std::string::npos) end = out.size();
    std::string line = out.substr(pos, end - pos);
    if (line.find("Error") != std::string::npos || line.find("error") != std::string::npos) {
      size_t a = line.find_first_not_of(" \t");
      size_t b = line.find_last_not_of(" \t\r.");
      best = a == std::string::npos ? std::string() : line.substr(a, b - a + 1);
      // "Error:  Point 5 has no x coordinate" -> "Point 5 has no x coordinate"
      for (const char* tag : {"File I/O Error:", "Error:"})
        if (best.rfind(tag, 0) == 0) best = best.substr(best.find_first_not_of(' ', std::string(tag).size()));
    }
    pos = end + 1;
  }
  return best.empty() ? fallback : "TetGen: " + best;
}

}  // namespace zs
