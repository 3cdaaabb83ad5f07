// What a renderer's set-up holds at once, item by item, against its memory
// budget (render/frame_settings.h: FrameSettings::budget()). Each item is
// checked as it is added, before the set-up allocates what comes next, so a
// render that cannot fit fails early, in one line that names the item that
// did not fit.
#pragma once

#include <cstdint>
#include <string>

namespace zs {

class MemoryLedger {
 public:
  // `render`: what the budget is for, as the message names it ("a 640x480
  // render of 12 spheres").
  MemoryLedger(uint64_t budget, std::string render);

  // Holds `bytes` more for `item` ("the tile bins"). Throws
  // std::runtime_error when the budget cannot hold them; `advice` ("lower
  // shadows.map_size") is offered after raising the budget.
  void add(const std::string& item, uint64_t bytes, const std::string& advice = "");
  // The same test for `bytes` the next step may allocate (a bound), without
  // holding them.
  void check(const std::string& item, uint64_t bytes, const std::string& advice = "") const;

  uint64_t budget() const { return budget_; }
  uint64_t held() const { return held_; }
  uint64_t left() const { return budget_ > held_ ? budget_ - held_ : 0; }

 private:
  uint64_t budget_, held_ = 0;
  std::string render_;
};

}  // namespace zs
