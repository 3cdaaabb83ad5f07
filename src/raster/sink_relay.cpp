#include "raster/sink_relay.h"

namespace zs {

bool SinkRelay::pop(Queued* out) {
  std::lock_guard<std::mutex> q(queue_mu_);
  if (queue_.empty()) return false;
  *out = std::move(queue_.front());
  queue_.pop_front();
  return true;
}

void SinkRelay::drain() {
  Queued t;
  while (pop(&t)) sink_.tile(t.r, t.rgba.data());
}

void SinkRelay::deliver(const TileRect& r, const float* rgba) {
  std::unique_lock<std::mutex> sink_lock(sink_mu_, std::try_to_lock);
  if (!sink_lock.owns_lock()) {
    {
      std::lock_guard<std::mutex> q(queue_mu_);
      if (queue_.size() < max_) {
        queue_.push_back({r, std::vector<float>(rgba, rgba + size_t(r.width()) * r.height() * channels_)});
        if (queue_.size() > peak_) peak_ = queue_.size();
        return;  // the holder (or the next delivery, or finish) passes it on
      }
    }
    sink_lock.lock();
  }
  sink_.tile(r, rgba);
  drain();
}

void SinkRelay::finish() {
  std::lock_guard<std::mutex> sink_lock(sink_mu_);
  drain();
}

}  // namespace zs
