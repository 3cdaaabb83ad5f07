// Byte counts in messages: "12.3 MiB" from a mebibyte up, else "N bytes".
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace zs {

inline std::string bytes_str(uint64_t b) {
  char buf[64];
  if (b >= (uint64_t(1) << 20)) std::snprintf(buf, sizeof buf, "%.1f MiB", double(b) / 1048576.0);
  else std::snprintf(buf, sizeof buf, "%llu bytes", (unsigned long long)b);
  return buf;
}

}  // namespace zs
