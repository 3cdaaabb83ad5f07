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

#include "mesh/tet_mesh.h"
#include "mesh/topology.h"
#include "volume/render_settings.h"
#include "volume/zsweep_renderer.h"

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
// Sweeps every tile across the ranks: into `sink` on rank 0 (null on the
// others; `sink_bytes` is what it holds). Builds this rank's renderer from
// `rs` without the progress bar (it would show one rank's runs only). On
// rank 0 fills `stats` as a single-process render does and prints one line
// with the per-rank split.
void render_mpi(const TetMesh& mesh, const Topology& topo, const RenderSettings& rs, TileSink* sink,
                uint64_t sink_bytes, RenderStats* stats);

}  // namespace zs
