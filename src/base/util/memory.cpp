#include <cstdio>
#include "base/util/memory.h"

#include <sys/resource.h>
#include <unistd.h>

namespace zs {

uint64_t default_memory_budget() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? uint64_t(pages) * uint64_t(size) / 2 : (uint64_t(4) << 30);
}

uint64_t peak_rss_bytes() {
  // VmHWM is this process image's own peak. getrusage's ru_maxrss is kept
  // across execve, so a zsweep started by a large parent (Python) would
  // report the parent's peak; it is only the fallback.
  if (FILE* f = std::fopen("/proc/self/status", "r")) {
    char line[256];
    unsigned long long kb = 0;
    bool found = false;
    while (!found && std::fgets(line, sizeof line, f)) found = std::sscanf(line, "VmHWM: %llu kB", &kb) == 1;
    std::fclose(f);
    if (found) return uint64_t(kb) * 1024;
  }
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return uint64_t(u.ru_maxrss) * 1024;
}

}  // namespace zs
