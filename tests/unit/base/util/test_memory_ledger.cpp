// The memory ledger (base/util/memory_ledger.h): items add up, each is
// checked as it is added, a refused item is not held, and the one message
// names the budget, the render, the need and the item that did not fit.
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "base/util/memory_ledger.h"

namespace zs {
namespace {

std::string refusal(MemoryLedger& l, const std::string& item, uint64_t bytes, const std::string& advice = "") {
  try {
    l.add(item, bytes, advice);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(MemoryLedger, ItemsAddUpToTheBudget) {
  MemoryLedger l(1000, "a 4x4 render of 2 spheres");
  EXPECT_EQ(l.budget(), 1000u);
  EXPECT_EQ(l.held(), 0u);
  l.add("the grid", 400);
  l.add("the tiles", 600);  // exactly the budget fits
  EXPECT_EQ(l.held(), 1000u);
  EXPECT_EQ(l.left(), 0u);
  l.add("nothing", 0);
}

TEST(MemoryLedger, RefusesTheItemThatDoesNotFitAndKeepsWhatWasHeld) {
  MemoryLedger l(1000, "a 4x4 render of 2 spheres");
  l.add("the grid", 700);
  EXPECT_EQ(refusal(l, "the tile bins", 301),
            "memory budget of 1000 bytes cannot hold a 4x4 render of 2 spheres (needs more than 1001 bytes with the "
            "tile bins); raise --memory-budget");
  EXPECT_EQ(l.held(), 700u);
  EXPECT_EQ(l.left(), 300u);
  l.add("the tile bins", 300);
}

TEST(MemoryLedger, CheckTestsABoundWithoutHoldingIt) {
  MemoryLedger l(uint64_t(3) << 20, "a 640x480 render of 12 triangles");
  l.check("the visible list", uint64_t(3) << 20);
  EXPECT_EQ(l.held(), 0u);
  l.add("the tiles", uint64_t(1) << 20);
  try {
    l.check("its shadow maps", uint64_t(5) << 19, "lower shadows.map_size");
    FAIL() << "a bound over the budget was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(),
                 "memory budget of 3.0 MiB cannot hold a 640x480 render of 12 triangles (needs more than 3.5 MiB "
                 "with its shadow maps); raise --memory-budget or lower shadows.map_size");
  }
  EXPECT_EQ(l.held(), uint64_t(1) << 20);
}

TEST(MemoryLedger, LeftIsZeroWhenNothingIsLeft) {
  MemoryLedger l(0, "a 1x1 render of 0 spheres");
  EXPECT_EQ(l.left(), 0u);
  l.add("nothing", 0);
  EXPECT_NE(refusal(l, "a byte", 1), "");
  EXPECT_EQ(l.held(), 0u);
}

}  // namespace
}  // namespace zs
