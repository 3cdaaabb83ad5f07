// The MPI environment of a `--mpi` run: start-up, shutdown, and how a
// failure on one rank ends every rank without a hang.
//
// Failures are handled by phase. During setup (load, topology, renderer) a
// failing rank does not abort: it joins one collective vote that every other
// rank joins on entering the distributed render, so all ranks learn that
// someone failed, rank 0 prints the first failing rank's message as one line,
// and all exit with status 1. During the distributed render a rank that fails
// prints one line naming itself and calls MPI_Abort (point-to-point traffic
// in flight cannot be unwound cleanly; Open MPI adds its own abort banner).
// After the render only rank 0 does anything that can fail (writing files),
// and it reports that like a normal run.
#pragma once

#include <exception>
#include <stdexcept>
#include <string>

namespace zs {

struct MpiContext {
  int rank = 0, size = 1;
};

// True between mpi_init and MPI_Finalize (which runs at exit).
bool mpi_active();
// Initialises MPI with MPI_THREAD_FUNNELED (only the main thread calls MPI;
// render threads never do) and registers MPI_Finalize at exit. Idempotent;
// argc/argv may be null. Throws std::runtime_error when MPI cannot provide it.
MpiContext mpi_init(int* argc, char*** argv);
// rank 0, size 1 when MPI is not active.
MpiContext mpi_context();

// The setup vote (collective over MPI_COMM_WORLD), called by every rank
// whose setup succeeded, right before the distributed render; ranks whose
// setup threw join it from mpi_exit_on_error. When some rank failed it
// throws: on rank 0 that rank's message, elsewhere MpiStopped. On success the
// distributed phase begins; mpi_leave_distributed() ends it.
void mpi_vote_setup();
void mpi_leave_distributed();
// Prints "zsweep: error: rank R: what" and aborts every rank.
[[noreturn]] void mpi_abort_with(const std::string& what);

// Thrown on ranks that stop because another rank failed; reported already.
struct MpiStopped : std::runtime_error {
  MpiStopped() : std::runtime_error("stopped: another rank failed") {}
};

// For main()'s catch: handles an error escaping a command under MPI according
// to the phase, prints at most one line (on one rank), and returns the exit
// status (or does not return: MPI_Abort).
int mpi_exit_on_error(const std::exception& e);

}  // namespace zs
