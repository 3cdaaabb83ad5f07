// Hands finished tiles to a TileSink from several threads without making a
// renderer wait while another thread writes (an EXR tile's compression costs
// about as much as rendering a light tile): a thread that finds the sink busy
// leaves a copy of its tile in a short queue and goes back to rendering, and
// whichever thread holds the sink delivers the queue before letting go. Only
// when the queue is full does a thread wait. Tiles reach the sink one at a
// time, in no particular order (as TileSink allows).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <vector>

#include "raster/tile_sink.h"

namespace zs {

class SinkRelay {
 public:
  // `channels`: floats per pixel of the tiles delivered.
  SinkRelay(TileSink& sink, size_t max_queued, uint32_t channels = 4)
      : sink_(sink), max_(max_queued), channels_(channels) {}
  // Thread-safe. Exceptions from the sink propagate to the caller.
  void deliver(const TileRect& r, const float* rgba);
  // Delivers what is still queued; call once every thread is done.
  void finish();
  size_t peak_queued() const { return peak_; }

 private:
  struct Queued {
    TileRect r;
    std::vector<float> rgba;
  };
  bool pop(Queued* out);
  void drain();  // with sink_mu_ held

  TileSink& sink_;
  size_t max_;
  uint32_t channels_;
  std::mutex sink_mu_, queue_mu_;
  std::deque<Queued> queue_;
  size_t peak_ = 0;
};

}  // namespace zs
