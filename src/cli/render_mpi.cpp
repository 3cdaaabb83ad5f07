#include "cli/render_mpi.h"

#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "mpi/mpi_render.h"

namespace zs {

namespace {
bool g_enabled = false;
std::string g_schedule = "dynamic";
MpiContext g_ctx;
}  // namespace

void add_render_mpi_options(CLI::App& cmd) {
  // Option callbacks run when parsing ends, before the command's callback.
  CLI::Option* on = cmd.add_flag_callback(
      "--mpi",
      [] {
        g_ctx = mpi_init(nullptr, nullptr);
        g_enabled = true;
      },
      "Render across MPI ranks (under mpirun): every rank loads the scene, rank 0 alone writes");
  cmd.add_option("--mpi-schedule", g_schedule, "Tiles to ranks: dynamic (ranks ask rank 0 for more) or static")
      ->check(CLI::IsMember({"static", "dynamic"}))
      ->needs(on);
}

bool render_mpi_enabled() { return g_enabled; }
int render_mpi_rank() { return g_enabled ? g_ctx.rank : 0; }

uint64_t render_mpi_message_bytes(const TileGrid& grid, int threads) { return mpi_message_bytes(grid, threads); }

void render_mpi(TiledRenderer& r, TileSink* sink, MpiReport* report) {
  MpiSchedule schedule = MpiSchedule::Dynamic;
  parse_mpi_schedule(g_schedule, &schedule);  // checked by the option
  MpiReport local;
  MpiReport& rep = report ? *report : local;
  render_mpi_tiles(r, sink, schedule, &rep);
  if (g_ctx.rank != 0) return;
  std::string tiles, ms, cpu;
  for (int k = 0; k < g_ctx.size; ++k) {
    char buf[64];
    const char* sep = k ? "/" : "";
    std::snprintf(buf, sizeof buf, "%s%llu", sep, (unsigned long long)rep.tiles[k]);
    tiles += buf;
    std::snprintf(buf, sizeof buf, "%s%.0f", sep, rep.render_ms[k]);
    ms += buf;
    std::snprintf(buf, sizeof buf, "%s%.0f", sep, rep.cpu_ms[k]);
    cpu += buf;
  }
  std::printf("mpi: %d rank(s) x %d thread(s), %s schedule: tiles %s, sweeping ms %s, cpu ms %s, %.1f ms wall\n",
              g_ctx.size, r.threads(), to_string(schedule), tiles.c_str(), ms.c_str(), cpu.c_str(), rep.wall_ms);
}

}  // namespace zs
