// `zsweep render --mpi [--mpi-schedule static|dynamic]`: the render command
// across MPI ranks (src/mpi/, docs/scaling.md). Every rank loads the scene
// and sweeps its share of the tiles; rank 0 alone opens the output, writes
// it and the stats, and prints. A plain `zsweep render` never starts MPI.
//
// The mode is process-wide, as MPI is: the flags live here, and --mpi starts
// MPI while the command line is parsed, before the scene is loaded, so that a
// load failure on any rank is settled with the others (src/mpi/mpi_env.h).
#pragma once

#include <cstdint>

#include "mpi/mpi_render.h"
#include "raster/tiled_renderer.h"

namespace CLI {
class App;
}

namespace zs {

// Adds --mpi and --mpi-schedule to the render command.
void add_render_mpi_options(CLI::App& render);
// True when --mpi was given (and MPI is running).
bool render_mpi_enabled();
// This process's rank (0 without --mpi): only rank 0 writes anything.
int render_mpi_rank();
// What a renderer built for an MPI render must count against its budget
// besides the sink: the tile messages one rank holds at most.
uint64_t render_mpi_message_bytes(const TileGrid& grid, int threads);
// Renders every tile across the ranks with `r` (built on every rank from the
// same scene, without a progress bar: it would show one rank's runs only):
// into `sink` on rank 0 (null on the others). On rank 0 the renderer's tile
// totals are every rank's summed, `report` gets the per-rank split, and one
// line with that split is printed.
void render_mpi(TiledRenderer& r, TileSink* sink, MpiReport* report);

}  // namespace zs
