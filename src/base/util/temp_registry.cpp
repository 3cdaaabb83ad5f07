#include "base/util/temp_registry.h"

#include <atomic>
#include <csignal>
#include <cstring>

#include <unistd.h>

namespace zs {

namespace {

constexpr int kSlots = 64;
constexpr size_t kPathMax = 4096;

// state: 0 free, 1 being written or cleared, 2 holds a path.
struct Slot {
  std::atomic<int> state{0};
  char path[kPathMax];
};
Slot g_slots[kSlots];

void remove_all() {
  for (Slot& s : g_slots)
    if (s.state.load(std::memory_order_acquire) == 2) ::unlink(s.path);
}

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGXFSZ,
                            SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
// The actions before ours (SIG_DFL, or a sanitizer's crash reporter).
struct sigaction g_previous[NSIG];

extern "C" void on_fatal_signal(int sig, siginfo_t* info, void*) {
  remove_all();
  // Then whatever would have happened without us: the previous action back,
  // and the signal again. A fault (SIGSEGV from a bad access) recurs by
  // itself when the handler returns, with its real address for a
  // sanitizer's report; a sent one is raised again (it is blocked in this
  // handler, so it arrives on return).
  sigaction(sig, &g_previous[sig], nullptr);
  if (info == nullptr || info->si_code <= 0) ::raise(sig);
}

}  // namespace

int register_temp_file(const std::string& path) {
  if (path.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expect = 0;
    if (g_slots[i].state.compare_exchange_strong(expect, 1, std::memory_order_acq_rel)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].state.store(2, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void unregister_temp_file(int slot) {
  if (slot >= 0 && slot < kSlots) g_slots[slot].state.store(0, std::memory_order_release);
}

int registered_temp_files() {
  int n = 0;
  for (const Slot& s : g_slots) n += s.state.load() == 2;
  return n;
}

void install_temp_cleanup() {
  struct sigaction sa {};
  sa.sa_sigaction = on_fatal_signal;
  sa.sa_flags = SA_SIGINFO;
  sigemptyset(&sa.sa_mask);
  // Every handled signal is blocked while one is handled, so two signals in
  // a row do not interrupt the removal half way.
  for (int s : kSignals) sigaddset(&sa.sa_mask, s);
  for (int s : kSignals) {
    sigaction(s, nullptr, &g_previous[s]);
    // A signal the parent ignores (nohup, `trap '' HUP`) stays ignored.
    if (g_previous[s].sa_handler == SIG_IGN) continue;
    sigaction(s, &sa, nullptr);
  }
}

}  // namespace zs
