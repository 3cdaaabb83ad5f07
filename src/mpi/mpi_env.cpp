#include "mpi/mpi_env.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include <mpi.h>

namespace zs {

namespace {

enum class Phase { Setup, Distributed, After };

bool g_active = false;
Phase g_phase = Phase::Setup;
MpiContext g_ctx;
constexpr int kTagError = 9001;  // the first failing rank's message, to rank 0

void finalize_at_exit() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (g_active && !finalized) MPI_Finalize();
  g_active = false;
}

// Every rank says whether its setup succeeded; returns the lowest failing
// rank (or -1) and, on rank 0, that rank's message.
int vote(bool ok, const std::string& error, std::string* root_message) {
  int first = ok ? g_ctx.size : g_ctx.rank;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == g_ctx.size) return -1;
  if (first == 0) {
    if (g_ctx.rank == 0) *root_message = error;
    return 0;
  }
  if (g_ctx.rank == first) {
    MPI_Send(error.data(), int(error.size()), MPI_CHAR, 0, kTagError, MPI_COMM_WORLD);
  } else if (g_ctx.rank == 0) {
    MPI_Status st;
    MPI_Probe(first, kTagError, MPI_COMM_WORLD, &st);
    int n = 0;
    MPI_Get_count(&st, MPI_CHAR, &n);
    std::string msg(size_t(n), '\0');
    MPI_Recv(msg.data(), n, MPI_CHAR, first, kTagError, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    *root_message = "rank " + std::to_string(first) + ": " + msg;
  }
  return first;
}

}  // namespace

bool mpi_active() { return g_active; }

MpiContext mpi_context() { return g_active ? g_ctx : MpiContext{}; }

MpiContext mpi_init(int* argc, char*** argv) {
  if (g_active) return g_ctx;
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) throw std::runtime_error("MPI was initialised elsewhere");
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw std::runtime_error("MPI_Init_thread failed");
  g_active = true;
  std::atexit(finalize_at_exit);
  if (provided < MPI_THREAD_FUNNELED) throw std::runtime_error("MPI does not provide MPI_THREAD_FUNNELED");
  MPI_Comm_rank(MPI_COMM_WORLD, &g_ctx.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_ctx.size);
  return g_ctx;
}

void mpi_vote_setup() {
  std::string msg;
  const int first = vote(true, "", &msg);
  if (first < 0) {
    g_phase = Phase::Distributed;
    return;
  }
  g_phase = Phase::After;  // nothing distributed starts: errors are ordinary now
  if (g_ctx.rank == 0) throw std::runtime_error(msg);
  throw MpiStopped();
}

void mpi_leave_distributed() { g_phase = Phase::After; }

void mpi_abort_with(const std::string& what) {
  std::fprintf(stderr, "zsweep: error: rank %d: %s\n", g_ctx.rank, what.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::abort();  // MPI_Abort does not return; be sure
}

int mpi_exit_on_error(const std::exception& e) {
  if (dynamic_cast<const MpiStopped*>(&e)) return 1;
  switch (g_phase) {
    case Phase::Setup: {
      std::string msg;
      vote(false, e.what(), &msg);
      g_phase = Phase::After;
      if (g_ctx.rank == 0) std::cerr << "zsweep: error: " << msg << "\n";
      return 1;
    }
    case Phase::Distributed:
      mpi_abort_with(e.what());
    case Phase::After:
      break;
  }
  std::cerr << "zsweep: error: " << e.what() << "\n";
  return 1;
}

}  // namespace zs
