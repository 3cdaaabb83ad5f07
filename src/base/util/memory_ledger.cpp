#include "base/util/memory_ledger.h"

#include <stdexcept>
#include <utility>

#include "base/util/bytes_str.h"

namespace zs {

MemoryLedger::MemoryLedger(uint64_t budget, std::string render) : budget_(budget), render_(std::move(render)) {}

void MemoryLedger::add(const std::string& item, uint64_t bytes, const std::string& advice) {
  check(item, bytes, advice);
  held_ += bytes;
}

void MemoryLedger::check(const std::string& item, uint64_t bytes, const std::string& advice) const {
  const uint64_t need = held_ + bytes;
  if (need <= budget_) return;
  throw std::runtime_error("memory budget of " + bytes_str(budget_) + " cannot hold " + render_ +
                           " (needs more than " + bytes_str(need) + " with " + item + "); raise --memory-budget" +
                           (advice.empty() ? "" : " or " + advice));
}

}  // namespace zs
