// The machine's memory as renderers budget it.
#pragma once

#include <cstdint>

namespace zs {

// Half of physical memory (4 GiB when it cannot be read): what a render may
// use when the user sets no --memory-budget.
uint64_t default_memory_budget();
// This process's peak resident memory so far.
uint64_t peak_rss_bytes();

}  // namespace zs
