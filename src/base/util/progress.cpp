#include "base/util/progress.h"

#include <unistd.h>

#include <cstdio>

namespace zs {

Progress::Progress(std::string label, uint64_t total, bool enabled)
    : label_(std::move(label)), total_(total ? total : 1), enabled_(enabled && isatty(STDERR_FILENO)) {
  start_ = last_ = std::chrono::steady_clock::now();
}

Progress::~Progress() { finish(); }

void Progress::add(uint64_t n) {
  const uint64_t d = done_.fetch_add(n, std::memory_order_relaxed) + n;
  if (!enabled_) return;
  std::unique_lock<std::mutex> lock(mu_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  draw(d, false);
}

void Progress::finish() {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mu_);
  if (shown_) {
    draw(total_, true);
    shown_ = false;
  }
  enabled_ = false;
}

void Progress::draw(uint64_t done, bool final) {
  const double frac = done >= total_ ? 1.0 : double(done) / double(total_);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = frac > 0 ? secs * (1 - frac) / frac : 0;
  const int width = 30, fill = int(frac * width);
  std::string bar(size_t(fill), '#');
  bar.resize(width, '.');
  std::fprintf(stderr, "\r%s [%s] %5.1f%%  %.1fs elapsed, ETA %.1fs   %s", label_.c_str(), bar.c_str(), frac * 100,
               secs, final ? 0.0 : eta, final ? "\n" : "");
  std::fflush(stderr);
  shown_ = true;
}

}  // namespace zs
