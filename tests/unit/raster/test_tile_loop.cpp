// The raster core's tile machinery: TileGrid's rectangles, run_tiles (every
// tile delivered once with its pixels, the sink never entered twice at once,
// exceptions), the relay queue's bound, SinkRelay's queueing, ImageSink's
// assembly, and the pod_bytes round trip.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdint>
#include <mutex>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "raster/image_sink.h"
#include "raster/sink_relay.h"
#include "raster/tile_grid.h"
#include "raster/tile_loop.h"
#include "raster/tiled_renderer.h"

namespace zs {
namespace {

// The value of channel c at image pixel (x, y): tile content checks.
float pixel_value(uint32_t x, uint32_t y, uint32_t c) { return float(x) * 1000.f + float(y) + 0.125f * float(c); }

void fill_tile(const TileRect& r, uint32_t channels, std::vector<float>* out) {
  out->resize(size_t(r.width()) * r.height() * channels);
  for (uint32_t y = r.y0; y < r.y1; ++y)
    for (uint32_t x = r.x0; x < r.x1; ++x)
      for (uint32_t c = 0; c < channels; ++c)
        (*out)[(size_t(y - r.y0) * r.width() + (x - r.x0)) * channels + c] = pixel_value(x, y, c);
}

TEST(TileGrid, RectsCoverTheImageExactlyOnce) {
  const uint32_t sizes[][3] = {{64, 64, 64},  {100, 37, 16}, {1, 1, 64}, {5, 3, 1},   {17, 300, 7},
                               {129, 128, 64}, {10, 10, 1000}, {63, 65, 64}, {256, 1, 32}};
  for (const auto& s : sizes) {
    const TileGrid g{s[0], s[1], s[2]};
    EXPECT_EQ(g.cols(), (s[0] + s[2] - 1) / s[2]);
    EXPECT_EQ(g.rows(), (s[1] + s[2] - 1) / s[2]);
    std::vector<int> hits(size_t(g.width) * g.height, 0);
    uint64_t area = 0;
    for (uint32_t t = 0; t < g.count(); ++t) {
      const TileRect r = g.rect(t);
      ASSERT_LT(r.x0, r.x1);
      ASSERT_LT(r.y0, r.y1);
      ASSERT_LE(r.x1, g.width);
      ASSERT_LE(r.y1, g.height);
      ASSERT_LE(r.width(), g.size);
      ASSERT_LE(r.height(), g.size);
      // Only the last column / row may be narrower.
      if (t % g.cols() + 1 < g.cols()) EXPECT_EQ(r.width(), g.size);
      if (t / g.cols() + 1 < g.rows()) EXPECT_EQ(r.height(), g.size);
      EXPECT_EQ(g.tile_of(r), t);
      for (uint32_t y = r.y0; y < r.y1; ++y)
        for (uint32_t x = r.x0; x < r.x1; ++x) ++hits[size_t(y) * g.width + x];
      area += uint64_t(r.width()) * r.height();
    }
    EXPECT_EQ(area, uint64_t(g.width) * g.height);
    EXPECT_TRUE(std::all_of(hits.begin(), hits.end(), [](int h) { return h == 1; }))
        << s[0] << "x" << s[1] << " tile " << s[2];
  }
  // A tile larger than the image: one tile, the whole image.
  const TileGrid big{10, 7, 64};
  ASSERT_EQ(big.count(), 1u);
  const TileRect r = big.rect(0);
  EXPECT_EQ(r.x0, 0u);
  EXPECT_EQ(r.y0, 0u);
  EXPECT_EQ(r.x1, 10u);
  EXPECT_EQ(r.y1, 7u);
  // Row-major from the top left.
  const TileGrid g{100, 37, 16};
  EXPECT_EQ(g.rect(1).x0, 16u);
  EXPECT_EQ(g.rect(1).y0, 0u);
  EXPECT_EQ(g.rect(g.cols()).x0, 0u);
  EXPECT_EQ(g.rect(g.cols()).y0, 16u);
}

TEST(TileGrid, TileFloatsCountChannels) {
  for (uint32_t channels : {4u, 5u}) {
    TileGrid g{100, 37, 16};
    g.channels = channels;
    uint64_t total = 0;
    for (uint32_t t = 0; t < g.count(); ++t) total += g.tile_floats(t);
    EXPECT_EQ(total, uint64_t(100) * 37 * channels);
    EXPECT_EQ(g.tile_floats(0), uint64_t(16) * 16 * channels);
    EXPECT_EQ(g.tile_floats(g.count() - 1), uint64_t(100 - 96) * (37 - 32) * channels);  // the corner
  }
}

TEST(TileLoop, AllTilesListsEveryIdInOrder) {
  const TileGrid g{100, 37, 16};
  const auto all = all_tiles(g);
  ASSERT_EQ(all.size(), g.count());
  for (uint32_t t = 0; t < all.size(); ++t) EXPECT_EQ(all[t], t);
}

TEST(TileLoop, RelayQueueBounds) {
  TileGrid g{4096, 4096, 64};
  EXPECT_EQ(relay_queue_tiles(g, 1), 0u);
  EXPECT_EQ(relay_queue_tiles(g, 0), 0u);
  EXPECT_EQ(relay_queue_tiles(g, 2), 16u);  // 64 KiB tiles: the count bound
  EXPECT_EQ(relay_queue_tiles(g, 64), 16u);
  for (uint32_t channels : {4u, 5u})
    for (uint32_t size : {1u, 16u, 64u, 256u, 512u, 1024u, 1500u, 2048u, 4096u}) {
      g.size = size;
      g.channels = channels;
      const uint64_t tile_bytes = uint64_t(size) * size * channels * 4;
      const size_t q = relay_queue_tiles(g, 4);
      EXPECT_GE(q, 1u);
      EXPECT_LE(q, 16u);
      if (tile_bytes <= (uint64_t(64) << 20)) {
        EXPECT_LE(q * tile_bytes, uint64_t(64) << 20) << size << " " << channels;
        // As many as fit, up to 16.
        EXPECT_EQ(q, std::min<uint64_t>(16, (uint64_t(64) << 20) / tile_bytes)) << size << " " << channels;
      } else {
        // A single tile larger than 64 MiB (4096² RGBA: 256 MiB; 2048² with
        // Z: 80 MiB) still gets one queue slot (the floor of one), so the
        // "at most 64 MiB" of tile_loop.h does not hold for such tiles.
        EXPECT_EQ(q, 1u) << size << " " << channels;
      }
    }
}

// A sink that records every tile, checks its pixels and detects two
// threads inside it at once.
class CheckingSink : public TileSink {
 public:
  CheckingSink(const TileGrid& g, std::chrono::microseconds delay = {}) : grid_(g), delay_(delay) {}
  void tile(const TileRect& r, const float* px) override {
    if (inside_.fetch_add(1) != 0) concurrent_ = true;
    if (delay_.count()) std::this_thread::sleep_for(delay_);
    bool ok = true;
    for (uint32_t y = r.y0; y < r.y1 && ok; ++y)
      for (uint32_t x = r.x0; x < r.x1 && ok; ++x)
        for (uint32_t c = 0; c < grid_.channels; ++c)
          ok = ok && px[(size_t(y - r.y0) * r.width() + (x - r.x0)) * grid_.channels + c] == pixel_value(x, y, c);
    if (!ok) ++bad_pixels_;
    delivered_.push_back(grid_.tile_of(r));
    rects_.push_back(r);
    inside_.fetch_sub(1);
  }
  const TileGrid& grid_;
  std::chrono::microseconds delay_;
  std::atomic<int> inside_{0};
  std::atomic<bool> concurrent_{false};
  int bad_pixels_ = 0;
  std::vector<uint32_t> delivered_;  // only written inside the sink
  std::vector<TileRect> rects_;
};

TEST(TileLoop, RunTilesDeliversEveryTileOnceWithItsPixels) {
  for (uint32_t channels : {4u, 5u})
    for (int threads : {1, 2})
      for (bool slow : {false, true}) {
        TileGrid g{70, 45, 8};
        g.channels = channels;
        CheckingSink sink(g, std::chrono::microseconds(slow ? 300 : 0));
        std::atomic<int> renders{0};
        std::set<std::thread::id> thread_ids;
        std::mutex ids_mu;
        run_tiles(g, all_tiles(g), threads, sink, [&](uint32_t tile, const TileRect& r) -> const float* {
          thread_local std::vector<float> buf;
          EXPECT_EQ(g.tile_of(r), tile);
          fill_tile(r, g.channels, &buf);
          ++renders;
          {
            std::lock_guard<std::mutex> l(ids_mu);
            thread_ids.insert(std::this_thread::get_id());
          }
          return buf.data();
        });
        EXPECT_EQ(renders.load(), int(g.count()));
        EXPECT_FALSE(sink.concurrent_) << threads;
        EXPECT_EQ(sink.bad_pixels_, 0);
        ASSERT_EQ(sink.delivered_.size(), g.count());
        std::vector<uint32_t> d = sink.delivered_;
        std::sort(d.begin(), d.end());
        EXPECT_EQ(d, all_tiles(g));  // each exactly once
        for (size_t i = 0; i < sink.rects_.size(); ++i) {
          const TileRect want = g.rect(sink.delivered_[i]);
          EXPECT_EQ(sink.rects_[i].x1, want.x1);
          EXPECT_EQ(sink.rects_[i].y1, want.y1);
        }
        if (threads == 1) {
          EXPECT_EQ(sink.delivered_, all_tiles(g));  // in list order, on the caller's thread
          EXPECT_EQ(thread_ids.size(), 1u);
          EXPECT_EQ(*thread_ids.begin(), std::this_thread::get_id());
        } else {
          EXPECT_LE(thread_ids.size(), 2u);
        }
      }
}

TEST(TileLoop, RunTilesOnASubsetAndNoTiles) {
  const TileGrid g{64, 64, 16};
  for (int threads : {1, 2}) {
    CheckingSink sink(g);
    const std::vector<uint32_t> some{15, 3, 7};
    run_tiles(g, some, threads, sink, [&](uint32_t, const TileRect& r) -> const float* {
      thread_local std::vector<float> buf;
      fill_tile(r, g.channels, &buf);
      return buf.data();
    });
    std::vector<uint32_t> d = sink.delivered_;
    std::sort(d.begin(), d.end());
    EXPECT_EQ(d, (std::vector<uint32_t>{3, 7, 15}));
    EXPECT_EQ(sink.bad_pixels_, 0);
    CheckingSink none(g);
    int calls = 0;
    run_tiles(g, {}, threads, none, [&](uint32_t, const TileRect&) -> const float* {
      ++calls;
      return nullptr;
    });
    EXPECT_EQ(calls, 0);
    EXPECT_TRUE(none.delivered_.empty());
  }
}

TEST(TileLoop, ExceptionInATilePropagatesAndStopsTheLoop) {
  const TileGrid g{512, 512, 8};  // 4096 tiles
  const uint32_t failing = 5;
  for (int threads : {1, 2}) {
    CheckingSink sink(g);
    std::atomic<int> renders{0};
    std::mutex ids_mu;
    std::set<std::thread::id> ids;
    auto thread_count = [&] {
      std::lock_guard<std::mutex> l(ids_mu);
      return ids.size();
    };
    EXPECT_THROW(run_tiles(g, all_tiles(g), threads, sink,
                           [&](uint32_t tile, const TileRect& r) -> const float* {
                             ++renders;
                             {
                               std::lock_guard<std::mutex> l(ids_mu);
                               ids.insert(std::this_thread::get_id());
                             }
                             if (tile == failing) {
                               // With two threads, fail only once the other
                               // one is rendering too, so that stopping it is
                               // what is tested (up to 2 s for it to start).
                               for (int i = 0; threads > 1 && thread_count() < 2 && i < 20000; ++i)
                                 std::this_thread::sleep_for(std::chrono::microseconds(100));
                               throw std::runtime_error("tile failed");
                             }
                             if (threads > 1 && tile > failing)
                               std::this_thread::sleep_for(std::chrono::milliseconds(1));
                             thread_local std::vector<float> buf;
                             fill_tile(r, g.channels, &buf);
                             return buf.data();
                           }),
                 std::runtime_error);
    EXPECT_FALSE(sink.concurrent_);
    EXPECT_EQ(std::count(sink.delivered_.begin(), sink.delivered_.end(), failing), 0);
    EXPECT_EQ(sink.bad_pixels_, 0);
    if (threads == 1) {
      EXPECT_EQ(renders.load(), int(failing) + 1);  // in order, nothing after the failure
      EXPECT_EQ(sink.delivered_.size(), failing);
    } else {
      if (thread_count() < 2) std::printf("note: TBB ran one thread only; the stop is not exercised\n");
      // The other thread finishes its current tile and stops (without the
      // stop it would render all 4096, 1 ms each).
      EXPECT_LT(renders.load(), 200) << "the loop went on after the exception";
    }
  }
}

// SinkRelay with the sink held by one thread: other deliveries queue
// copies (up to max_queued) and return at once; the holder passes them on.
TEST(SinkRelay, QueuesCopiesWhileTheSinkIsBusy) {
  const TileGrid g{32, 32, 8};  // 16 tiles
  struct BlockingSink : TileSink {
    std::mutex mu;
    std::condition_variable cv;
    bool entered = false, released = false;
    std::vector<std::pair<TileRect, std::vector<float>>> got;
    void tile(const TileRect& r, const float* px) override {
      std::unique_lock<std::mutex> l(mu);
      if (got.empty()) {  // the first tile: hold the sink until released
        entered = true;
        cv.notify_all();
        cv.wait(l, [&] { return released; });
      }
      got.push_back({r, std::vector<float>(px, px + size_t(r.width()) * r.height() * 4)});
    }
  } sink;
  SinkRelay relay(sink, 3, g.channels);
  std::vector<float> first;
  fill_tile(g.rect(0), 4, &first);
  std::thread holder([&] { relay.deliver(g.rect(0), first.data()); });
  {
    std::unique_lock<std::mutex> l(sink.mu);
    sink.cv.wait(l, [&] { return sink.entered; });
  }
  // Three deliveries while the sink is held: queued, each returns.
  std::vector<float> buf;
  for (uint32_t t = 1; t <= 3; ++t) {
    fill_tile(g.rect(t), 4, &buf);
    relay.deliver(g.rect(t), buf.data());
    std::fill(buf.begin(), buf.end(), -1.f);  // the relay kept a copy
  }
  EXPECT_EQ(relay.peak_queued(), 3u);
  {
    std::lock_guard<std::mutex> l(sink.mu);
    EXPECT_EQ(sink.got.size(), 0u);
    sink.released = true;
  }
  sink.cv.notify_all();
  holder.join();
  // The holder delivered its tile and then the queue, in order.
  ASSERT_EQ(sink.got.size(), 4u);
  for (uint32_t t = 0; t < 4; ++t) {
    EXPECT_EQ(g.tile_of(sink.got[t].first), t);
    std::vector<float> want;
    fill_tile(g.rect(t), 4, &want);
    EXPECT_EQ(sink.got[t].second, want) << t;
  }
  relay.finish();  // nothing left
  EXPECT_EQ(sink.got.size(), 4u);
}

TEST(SinkRelay, QueueFullMakesTheDelivererWait) {
  const TileGrid g{32, 32, 8};
  struct GateSink : TileSink {
    std::mutex mu;
    std::condition_variable cv;
    bool entered = false, released = false;
    std::vector<uint32_t> got;
    const TileGrid* g;
    void tile(const TileRect& r, const float*) override {
      std::unique_lock<std::mutex> l(mu);
      if (got.empty()) {
        entered = true;
        cv.notify_all();
        cv.wait(l, [&] { return released; });
      }
      got.push_back(g->tile_of(r));
    }
  } sink;
  sink.g = &g;
  SinkRelay relay(sink, 1, g.channels);
  std::vector<float> buf(8 * 8 * 4, 0.f);
  std::thread holder([&] { relay.deliver(g.rect(0), buf.data()); });
  {
    std::unique_lock<std::mutex> l(sink.mu);
    sink.cv.wait(l, [&] { return sink.entered; });
  }
  relay.deliver(g.rect(1), buf.data());  // queued
  std::atomic<bool> second_returned{false};
  std::thread waiter([&] {
    relay.deliver(g.rect(2), buf.data());  // queue full: waits for the sink
    second_returned = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(second_returned.load());
  {
    std::lock_guard<std::mutex> l(sink.mu);
    sink.released = true;
  }
  sink.cv.notify_all();
  holder.join();
  waiter.join();
  relay.finish();
  EXPECT_TRUE(second_returned.load());
  EXPECT_EQ(relay.peak_queued(), 1u);
  std::vector<uint32_t> got = sink.got;
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(SinkRelay, SlowSinkTwoThreadsEverythingDeliveredAfterFinish) {
  const TileGrid g{96, 96, 8};  // 144 tiles
  CheckingSink sink(g, std::chrono::microseconds(200));
  SinkRelay relay(sink, 4, g.channels);
  auto worker = [&](uint32_t parity) {
    std::vector<float> buf;
    for (uint32_t t = parity; t < g.count(); t += 2) {
      fill_tile(g.rect(t), g.channels, &buf);
      relay.deliver(g.rect(t), buf.data());
      std::fill(buf.begin(), buf.end(), -7.f);
    }
  };
  std::thread a(worker, 0u), b(worker, 1u);
  a.join();
  b.join();
  relay.finish();
  EXPECT_FALSE(sink.concurrent_);
  EXPECT_EQ(sink.bad_pixels_, 0);
  std::vector<uint32_t> d = sink.delivered_;
  std::sort(d.begin(), d.end());
  EXPECT_EQ(d, all_tiles(g));
  EXPECT_LE(relay.peak_queued(), 4u);
}

TEST(SinkRelay, ZeroQueueDeliversDirectly) {
  const TileGrid g{16, 16, 8};
  CheckingSink sink(g);
  SinkRelay relay(sink, 0, g.channels);
  std::vector<float> buf;
  for (uint32_t t = 0; t < g.count(); ++t) {
    fill_tile(g.rect(t), 4, &buf);
    relay.deliver(g.rect(t), buf.data());
    EXPECT_EQ(sink.delivered_.size(), t + 1);  // synchronously
  }
  relay.finish();
  EXPECT_EQ(relay.peak_queued(), 0u);
  EXPECT_EQ(sink.bad_pixels_, 0);
}

TEST(ImageSink, AssemblesRgbaAndZFromTilesInAnyOrder) {
  for (uint32_t channels : {4u, 5u}) {
    TileGrid g{50, 29, 8};
    g.channels = channels;
    std::vector<uint32_t> order = all_tiles(g);
    std::mt19937 rng(channels);
    std::shuffle(order.begin(), order.end(), rng);
    ImageSink sink(g);
    EXPECT_EQ(sink.image.width, 50u);
    EXPECT_EQ(sink.image.height, 29u);
    EXPECT_EQ(sink.z.size(), channels > 4 ? size_t(50) * 29 : 0u);
    std::vector<float> buf;
    for (uint32_t t : order) {
      fill_tile(g.rect(t), channels, &buf);
      sink.tile(g.rect(t), buf.data());
    }
    for (uint32_t y = 0; y < g.height; ++y)
      for (uint32_t x = 0; x < g.width; ++x) {
        for (uint32_t c = 0; c < 4; ++c) ASSERT_EQ(sink.image.at(x, y)[c], pixel_value(x, y, c)) << x << "," << y;
        if (channels > 4) ASSERT_EQ(sink.z[size_t(y) * g.width + x], pixel_value(x, y, 4)) << x << "," << y;
      }
  }
}

TEST(ImageSink, ThroughRunTilesWithTwoThreads) {
  TileGrid g{77, 33, 16};
  g.channels = 5;
  ImageSink sink(g);
  run_tiles(g, all_tiles(g), 2, sink, [&](uint32_t, const TileRect& r) -> const float* {
    thread_local std::vector<float> buf;
    fill_tile(r, g.channels, &buf);
    return buf.data();
  });
  for (uint32_t y = 0; y < g.height; ++y)
    for (uint32_t x = 0; x < g.width; ++x) {
      ASSERT_EQ(sink.image.at(x, y)[3], pixel_value(x, y, 3));
      ASSERT_EQ(sink.z[size_t(y) * g.width + x], pixel_value(x, y, 4));
    }
}

TEST(PodBytes, RoundTripAndSizeMismatch) {
  struct Totals {
    uint64_t a;
    double b;
    uint32_t c[3];
  };
  const Totals in{0x0123456789abcdefull, -2.5e-300, {1, 2, 0xffffffffu}};
  const std::vector<uint8_t> bytes = pod_bytes(in);
  ASSERT_EQ(bytes.size(), sizeof(Totals));
  Totals out{};
  ASSERT_TRUE(pod_from_bytes(bytes, &out));
  EXPECT_EQ(out.a, in.a);
  EXPECT_EQ(out.b, in.b);
  EXPECT_EQ(out.c[0], 1u);
  EXPECT_EQ(out.c[2], 0xffffffffu);
  // Wrong sizes are rejected and leave the target alone.
  Totals untouched{7, 7.0, {7, 7, 7}};
  std::vector<uint8_t> shorter(bytes.begin(), bytes.end() - 1), longer = bytes;
  longer.push_back(0);
  EXPECT_FALSE(pod_from_bytes(shorter, &untouched));
  EXPECT_FALSE(pod_from_bytes(longer, &untouched));
  EXPECT_FALSE(pod_from_bytes(std::vector<uint8_t>{}, &untouched));
  EXPECT_EQ(untouched.a, 7u);
  EXPECT_EQ(untouched.c[1], 7u);
  // A different type of another size.
  uint32_t small = 0;
  EXPECT_FALSE(pod_from_bytes(bytes, &small));
  EXPECT_EQ(small, 0u);
}

}  // namespace
}  // namespace zs
