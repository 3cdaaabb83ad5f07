// A progress bar on stderr with ETA, shown only when stderr is a terminal and
// the work has taken more than a second. Thread-safe; cheap to call often.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace zs {

class Progress {
 public:
  Progress(std::string label, uint64_t total, bool enabled);
  ~Progress();
  void add(uint64_t n);
  void finish();

 private:
  void draw(uint64_t done, bool final);
  std::string label_;
  uint64_t total_;
  bool enabled_;
  bool shown_ = false;
  std::atomic<uint64_t> done_{0};
  std::chrono::steady_clock::time_point start_, last_;
  std::mutex mu_;
};

}  // namespace zs
