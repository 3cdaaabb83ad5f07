#include "mpi/mpi_render.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <future>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <type_traits>

#include <sys/resource.h>

#include <mpi.h>

#include "base/util/memory.h"

namespace zs {

const char* to_string(MpiSchedule s) { return s == MpiSchedule::Static ? "static" : "dynamic"; }

bool parse_mpi_schedule(const std::string& s, MpiSchedule* out) {
  if (s == "static") *out = MpiSchedule::Static;
  else if (s == "dynamic") *out = MpiSchedule::Dynamic;
  else return false;
  return true;
}

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// Worker -> 0: a run of finished tiles; 0 -> worker: the next run to sweep;
// worker -> 0: "send me the next run" (its thread count, which sizes it).
constexpr int kTagTiles = 1, kTagGrant = 2, kTagRequest = 3;
// One message of tiles stays well below MPI's int counts and keeps what
// rank 0 receives at once small next to the image.
constexpr uint64_t kMaxChunkBytes = uint64_t(32) << 20;

struct Plan {
  uint32_t width = 0, height = 0, size = 0, count = 0;
};

uint32_t tile_of(const TileGrid& g, const TileRect& r) { return g.tile_of(r); }
uint64_t tile_floats(const TileGrid& g, uint32_t t) { return g.tile_floats(t); }

// The most tiles one message may carry.
uint32_t max_chunk(const TileGrid& g) {
  const uint64_t tile_bytes = uint64_t(g.size) * g.size * g.channels * 4;
  return uint32_t(std::clamp<uint64_t>(kMaxChunkBytes / tile_bytes, 1, g.count()));
}
// The smallest run worth a render call: two tiles per thread, so the
// renderer's threads balance within the run.
uint32_t min_chunk(const TileGrid& g, int threads) {
  return std::min<uint32_t>(uint32_t(std::max(2 * threads, 1)), max_chunk(g));
}

// A run of tiles packed for one message: [n][id x n][RGBA of each, in id
// order of the header], as 4-byte words (ids stored bitwise).
class Chunk : public TileSink {
 public:
  explicit Chunk(const TileGrid& g) : grid_(g) {}
  void begin(const std::vector<uint32_t>& ids) {
    uint64_t n = 1 + ids.size();
    for (uint32_t t : ids) n += tile_floats(grid_, t);
    words_.assign(n, 0.f);
    set_word(0, uint32_t(ids.size()));
    header_ = 1;
    cursor_ = 1 + ids.size();
  }
  // Tiles arrive in any order; the header records the order they came in.
  void tile(const TileRect& r, const float* rgba) override {
    set_word(header_++, tile_of(grid_, r));
    const size_t n = size_t(r.width()) * r.height() * grid_.channels;
    std::memcpy(&words_[cursor_], rgba, n * sizeof(float));
    cursor_ += n;
  }
  const float* data() const { return words_.data(); }
  int bytes() const { return int(words_.size() * sizeof(float)); }
  MPI_Request request = MPI_REQUEST_NULL;

 private:
  void set_word(size_t i, uint32_t v) { std::memcpy(&words_[i], &v, 4); }
  const TileGrid& grid_;
  std::vector<float> words_;
  size_t header_ = 0, cursor_ = 0;
};

// Runs granted to a rank of `threads` threads are at most this long.
uint32_t max_run(const TileGrid& g, int threads) { return std::min(16 * min_chunk(g, threads), max_chunk(g)); }

// What every rank sends rank 0 at the end.
struct RankResult {
  double render_ms = 0;  // wall time of this rank's render_tiles calls
  uint64_t tiles = 0, peak_rss = 0;
  double cpu_ms = 0;  // every thread of the rank, over the distributed phase
};
static_assert(std::is_trivially_copyable_v<RankResult>);

double cpu_ms() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return (u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3;
}

// Rank 0's sink, fed by its render thread and by the main thread forwarding
// other ranks' tiles: one at a time.
class LockedSink : public TileSink {
 public:
  LockedSink(TileSink* s, std::mutex& m) : s_(s), m_(m) {}
  void tile(const TileRect& r, const float* rgba) override {
    std::lock_guard<std::mutex> lock(m_);
    s_->tile(r, rgba);
  }

 private:
  TileSink* s_;
  std::mutex& m_;
};

// The distributed render on one rank. MPI is FUNNELED: the main thread does
// every MPI call and polls while a render thread sweeps one run at a time
// (with the renderer's own threads), so messages keep moving during a sweep
// — without this, a large message between two ranks that are both sweeping
// waits for the end of the sweep (MPI progresses only inside MPI calls).
class Session {
 public:
  Session(TiledRenderer& r, TileSink* sink, const MpiContext& ctx)
      : r_(r), grid_(r.grid()), threads_(std::max(1, r.threads())), sink_(sink), ctx_(ctx) {
    // Test hook (tests/cli/mpi.sh): this rank fails in its first run, to
    // show that a failure mid-render ends every rank instead of hanging them.
    const char* f = std::getenv("ZSWEEP_MPI_FAIL_RANK");
    fail_ = f && *f && std::atoi(f) == ctx.rank;
  }

  // Any failure here aborts every rank, before the render thread (still
  // running, perhaps) would be joined.
  void run(MpiSchedule schedule) {
    try {
      if (ctx_.rank == 0) root(schedule == MpiSchedule::Dynamic);
      else worker(schedule == MpiSchedule::Dynamic);
    } catch (const std::exception& e) {
      mpi_abort_with(e.what());
    }
  }
  RankResult result() const { return RankResult{render_ms_, tiles_, peak_rss_bytes(), cpu_ms() - cpu0_}; }

 private:
  // --- the render thread: one run at a time.
  void start(std::vector<uint32_t> ids, TileSink& sink) {
    if (fail_) throw std::runtime_error("failure injected by ZSWEEP_MPI_FAIL_RANK");
    tiles_ += ids.size();
    running_ = std::move(ids);
    job_ = std::async(std::launch::async, [this, &sink] {
      const auto t0 = Clock::now();
      r_.render_tiles(sink, &running_);
      render_ms_ += ms_since(t0);
    });
  }
  bool busy() const { return job_.valid(); }
  // Waits up to one poll interval for the run; true (and rethrows its
  // failure) once it is done.
  bool run_done() {
    if (!job_.valid()) return false;
    if (job_.wait_for(kPoll) != std::future_status::ready) return false;
    job_.get();
    return true;
  }
  static void idle() { std::this_thread::sleep_for(kPoll); }

  // --- static: block b of block() tiles belongs to rank b mod size, swept
  // in runs of min_chunk.
  uint32_t block() const {
    // Each rank gets >= 32 blocks when the image allows (balance within a
    // few percent for smoothly varying cost); blocks of <= 16 tiles.
    return std::clamp<uint32_t>(grid_.count() / (uint32_t(ctx_.size) * 32), 1, 16);
  }
  std::deque<std::vector<uint32_t>> static_runs() const {
    std::vector<uint32_t> mine;
    const uint32_t b = block();
    for (uint32_t t = 0; t < grid_.count(); ++t)
      if ((t / b) % uint32_t(ctx_.size) == uint32_t(ctx_.rank)) mine.push_back(t);
    std::deque<std::vector<uint32_t>> runs;
    const size_t cap = min_chunk(grid_, threads_);
    for (size_t k = 0; k < mine.size(); k += cap)
      runs.emplace_back(mine.begin() + k, mine.begin() + std::min(mine.size(), k + cap));
    return runs;
  }

  // --- dynamic: rank 0 deals contiguous runs of tile ids (row-major, so the
  // sink sees tiles roughly in order), guided sizes: a quarter of each rank's
  // share of what is left, at least two tiles per thread of the taker.
  std::vector<uint32_t> take(int threads) {
    const uint32_t left = grid_.count() - next_;
    const uint32_t lo = min_chunk(grid_, threads), hi = max_run(grid_, threads);
    uint32_t n = std::max(lo, (left + 4 * uint32_t(ctx_.size) - 1) / (4 * uint32_t(ctx_.size)));
    n = std::min({n, hi, left});
    std::vector<uint32_t> ids(n);
    for (uint32_t k = 0; k < n; ++k) ids[k] = next_ + k;
    next_ += n;
    return ids;
  }
  void grant(int worker, int threads) {
    const std::vector<uint32_t> ids = take(threads);
    const uint32_t g[2] = {ids.empty() ? 0 : ids.front(), uint32_t(ids.size())};
    if (ids.empty()) ++done_sent_;
    MPI_Send(g, 2, MPI_UINT32_T, worker, kTagGrant, MPI_COMM_WORLD);
  }

  // --- rank 0: sweeps its own runs into the sink while it answers requests
  // and forwards the other ranks' tiles as they arrive.
  void root(bool dynamic) {
    seen_.assign(grid_.count(), 0);
    std::deque<std::vector<uint32_t>> runs;
    if (dynamic) {
      // First runs go out unasked, so no worker waits for rank 0.
      for (int w = 1; w < ctx_.size; ++w) grant(w, threads_);
    } else {
      runs = static_runs();
    }
    const int workers = ctx_.size - 1;
    for (;;) {
      service();
      if (!busy() || run_done()) {
        if (!running_.empty()) {
          for (uint32_t t : running_) mark_seen(t);
          received_ += running_.size();
          running_.clear();
        }
        if (dynamic && next_ < grid_.count()) runs.push_back(take(threads_));
        if (!runs.empty()) {
          start(std::move(runs.front()), own_);
          runs.pop_front();
        } else if (received_ == grid_.count() && done_sent_ == (dynamic ? workers : 0)) {
          return;
        } else {
          idle();
        }
      }
    }
  }
  // Answers every request and forwards every tile message that is waiting.
  void service() {
    for (;;) {
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
      if (!flag) return;
      if (st.MPI_TAG == kTagRequest) {
        int threads = 1;
        MPI_Recv(&threads, 1, MPI_INT, st.MPI_SOURCE, kTagRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        grant(st.MPI_SOURCE, std::max(1, threads));
      } else if (st.MPI_TAG == kTagTiles) {
        forward(st);
      } else {
        throw std::runtime_error("unexpected message tag " + std::to_string(st.MPI_TAG));
      }
    }
  }
  // Receives one message of tiles and hands them to the sink one by one:
  // rank 0 holds one message, never a second image.
  void forward(const MPI_Status& st) {
    int bytes = 0;
    MPI_Get_count(&st, MPI_BYTE, &bytes);
    inbox_.resize((size_t(bytes) + 3) / 4);
    MPI_Recv(inbox_.data(), bytes, MPI_BYTE, st.MPI_SOURCE, kTagTiles, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    auto word = [&](size_t i) {
      uint32_t v;
      std::memcpy(&v, &inbox_[i], 4);
      return v;
    };
    const auto malformed = [&] {
      return std::runtime_error("malformed tile message from rank " + std::to_string(st.MPI_SOURCE));
    };
    const size_t words = size_t(bytes) / 4;
    const uint32_t n = words ? word(0) : 0;
    size_t cursor = 1 + size_t(n);
    if (words == 0 || cursor > words) throw malformed();
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t t = word(1 + k);
      if (t >= grid_.count() || cursor + tile_floats(grid_, t) > words) throw malformed();
      mark_seen(t);
      own_.tile(grid_.rect(t), &inbox_[cursor]);  // locks per tile: rank 0's own tiles interleave
      cursor += tile_floats(grid_, t);
    }
    received_ += n;
  }
  void mark_seen(uint32_t t) {
    if (seen_[t]) throw std::runtime_error("tile " + std::to_string(t) + " arrived twice");
    seen_[t] = 1;
  }

  // --- other ranks: sweep runs into packed chunks and send each without
  // waiting; two chunks alternate, so one sweeps while the other is in
  // flight. Under dynamic, ask for the next run when a run starts, so it is
  // (usually) there when the run ends.
  void worker(bool dynamic) {
    std::deque<std::vector<uint32_t>> runs;
    if (!dynamic) runs = static_runs();
    bool asked = dynamic, done = !dynamic;  // the first grant comes unasked
    Chunk* filling = nullptr;
    for (;;) {
      if (asked) {
        int flag = 0;
        MPI_Iprobe(0, kTagGrant, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
        if (flag) {
          uint32_t g[2];
          MPI_Recv(g, 2, MPI_UINT32_T, 0, kTagGrant, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          asked = false;
          if (g[1] == 0) done = true;
          else {
            runs.emplace_back(g[1]);
            for (uint32_t k = 0; k < g[1]; ++k) runs.back()[k] = g[0] + k;
          }
        }
      }
      for (Chunk& c : chunks_) {  // keeps sends moving; frees finished chunks
        int flag = 0;
        MPI_Test(&c.request, &flag, MPI_STATUS_IGNORE);
      }
      if (busy() && !run_done()) continue;
      if (filling) {
        MPI_Isend(filling->data(), filling->bytes(), MPI_BYTE, 0, kTagTiles, MPI_COMM_WORLD, &filling->request);
        filling = nullptr;
        running_.clear();
      }
      Chunk* free = nullptr;
      for (Chunk& c : chunks_)
        if (c.request == MPI_REQUEST_NULL) free = &c;
      if (!runs.empty() && free) {
        free->begin(runs.front());
        filling = free;
        start(std::move(runs.front()), *free);
        runs.pop_front();
        if (dynamic && !done && !asked) {
          MPI_Send(&threads_, 1, MPI_INT, 0, kTagRequest, MPI_COMM_WORLD);
          asked = true;
        }
      } else if (runs.empty() && done) {
        break;
      } else {
        idle();
      }
    }
    for (Chunk& c : chunks_) MPI_Wait(&c.request, MPI_STATUS_IGNORE);
  }

  static constexpr std::chrono::microseconds kPoll{200};
  TiledRenderer& r_;
  const TileGrid& grid_;
  const int threads_;
  TileSink* sink_;
  const MpiContext ctx_;
  bool fail_ = false;
  const double cpu0_ = cpu_ms();
  double render_ms_ = 0;  // written by the render thread, read once it is joined
  uint64_t tiles_ = 0;
  std::vector<uint32_t> running_;  // the run the render thread sweeps
  std::future<void> job_;
  Chunk chunks_[2] = {Chunk(grid_), Chunk(grid_)};
  // Rank 0. Members, not locals, so that they outlive a render thread
  // still running when a failure aborts.
  std::mutex sink_mu_;
  LockedSink own_{sink_, sink_mu_};
  std::vector<uint8_t> seen_;
  std::vector<float> inbox_;
  uint32_t next_ = 0, received_ = 0;
  int done_sent_ = 0;
};

// Every rank must cut the same grid, or tiles would go missing.
void check_same_grid(const TileGrid& g, const MpiContext& ctx) {
  Plan p{g.width, g.height, g.size, g.count()};
  MPI_Bcast(&p, sizeof p, MPI_BYTE, 0, MPI_COMM_WORLD);
  int differs = p.width != g.width || p.height != g.height || p.size != g.size || p.count != g.count();
  MPI_Allreduce(MPI_IN_PLACE, &differs, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (!differs) return;
  mpi_leave_distributed();  // every rank stops here together: no abort needed
  if (ctx.rank == 0)
    throw std::runtime_error("MPI ranks disagree on the image or tile size (same scene and options on every rank?)");
  throw MpiStopped();
}

}  // namespace

uint64_t mpi_message_bytes(const TileGrid& g, int threads) {
  return 2 * uint64_t(max_run(g, std::max(1, threads))) * g.size * g.size * g.channels * 4;
}

void render_mpi_tiles(TiledRenderer& r, TileSink* sink, MpiSchedule schedule, MpiReport* report) {
  const MpiContext ctx = mpi_context();
  if (ctx.rank == 0 && !sink) throw std::runtime_error("render_mpi_tiles: rank 0 needs a sink");
  mpi_vote_setup();
  check_same_grid(r.grid(), ctx);
  const auto t0 = Clock::now();
  std::vector<RankResult> all(ctx.rank == 0 ? size_t(ctx.size) : 0);
  std::vector<uint8_t> totals;
  {
    Session s(r, sink, ctx);
    s.run(schedule);  // aborts every rank on a failure
    const RankResult mine = s.result();
    MPI_Gather(&mine, sizeof mine, MPI_BYTE, all.data(), sizeof mine, MPI_BYTE, 0, MPI_COMM_WORLD);
    // Every rank runs the same renderer kind, so the totals have one size.
    const std::vector<uint8_t> my_totals = r.tile_totals();
    totals.resize(ctx.rank == 0 ? my_totals.size() * size_t(ctx.size) : 0);
    MPI_Gather(my_totals.data(), int(my_totals.size()), MPI_BYTE, totals.data(), int(my_totals.size()), MPI_BYTE, 0,
               MPI_COMM_WORLD);
  }
  mpi_leave_distributed();
  if (ctx.rank != 0) return;
  const double wall = ms_since(t0);
  const size_t n = totals.size() / size_t(ctx.size);
  for (int k = 1; k < ctx.size; ++k)
    r.add_tile_totals(std::vector<uint8_t>(totals.begin() + ptrdiff_t(k * n), totals.begin() + ptrdiff_t((k + 1) * n)));
  if (report) {
    report->wall_ms = wall;
    report->tiles.clear();
    report->render_ms.clear();
    report->peak_rss.clear();
    report->cpu_ms.clear();
    for (const RankResult& rr : all) {
      report->tiles.push_back(rr.tiles);
      report->render_ms.push_back(rr.render_ms);
      report->peak_rss.push_back(rr.peak_rss);
      report->cpu_ms.push_back(rr.cpu_ms);
    }
  }
}

}  // namespace zs
