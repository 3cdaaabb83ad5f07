// Sort-first rendering over MPI ranks (docs/scaling.md), for any renderer
// (raster/tiled_renderer.h). Every rank has loaded the same scene and
// prepared its own renderer over the whole scene; the screen tiles are dealt out to the ranks, each rank sweeps its
// tiles on its own threads and sends them to rank 0, which hands each to its
// sink as it arrives. A tile's pixels do not depend on which rank or thread
// swept it, so the image is bit-identical to a single-process render.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mpi/mpi_env.h"
#include "raster/tiled_renderer.h"

namespace zs {

// static: tile ids in interleaved blocks, block b to rank b mod size (fixed
// before the render; no messages but the tiles). dynamic: ranks ask rank 0
// for the next run of tiles (shrinking as the image fills) and render it.
enum class MpiSchedule { Static, Dynamic };
const char* to_string(MpiSchedule s);
bool parse_mpi_schedule(const std::string& s, MpiSchedule* out);

// Per-rank figures of one distributed render, on rank 0.
struct MpiReport {
  std::vector<uint64_t> tiles;     // tiles each rank swept
  std::vector<double> render_ms;   // time each rank spent in render_tiles
  std::vector<uint64_t> peak_rss;  // each rank's peak resident memory
  std::vector<double> cpu_ms;      // each rank's CPU time (all its threads) in the phase
  double wall_ms = 0;              // the distributed phase, on rank 0
};

// Collective: every rank of MPI_COMM_WORLD calls it with a renderer prepared
// from the same scene and settings (runs of tiles are sized by its
// threads()). `sink` is used on rank 0 only (pass null elsewhere). Starts
// with the setup vote (mpi_env.h) and checks that all ranks cut the same tile
// grid. On rank 0 the renderer's tile totals end up as every rank's summed
// (add_tile_totals), and `report` gets the per-rank split and the wall time
// of the distributed phase. A failure on any rank during the render aborts
// every rank (mpi_env.h).
void render_mpi_tiles(TiledRenderer& r, TileSink* sink, MpiSchedule schedule, MpiReport* report = nullptr);

// What one rank holds in tile messages at most (rank 0: one it received;
// the others: two in flight), for the caller's memory budget.
uint64_t mpi_message_bytes(const TileGrid& g, int threads);

}  // namespace zs
