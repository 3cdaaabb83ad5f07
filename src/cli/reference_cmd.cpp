// `zsweep reference SCENE.json|MESH -o OUT.exr [--stats S.json]`: the
// independent ray caster every error figure is measured against.
#include <cstdio>
#include <fstream>
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/scene_args.h"
#include "mesh/topology.h"
#include "reference/reference_renderer.h"
#include "util/atomic_file.h"

namespace zs {

void add_reference_command(CLI::App& app) {
  auto a = std::make_shared<SceneArgs>();
  auto out = std::make_shared<std::string>(), stats = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "reference", "Ground-truth image: an independent ray caster (tet walk, exact integration, no early termination)");
  a->add_options(*cmd, false);
  cmd->add_option("-o,--output", *out, "Output image (.exr or .tif keep the float values)")->required();
  cmd->add_option("--stats", *stats, "Write ray-casting statistics as JSON");
  cmd->callback([a, out, stats] {
    SceneInput in = a->load();
    AtomicFile(*out).check_writable();  // before minutes of ray casting
    if (!stats->empty()) AtomicFile(*stats).check_writable();
    const Topology topo = build_topology(in.mesh);
    ReferenceStats s;
    const Image img = render_reference(in.mesh, topo, in.scene.settings, &s);
    write_image(*out, img);
    if (!stats->empty()) {
      nlohmann::json j = {{"time_ms", s.ms_total},       {"rays_hit", s.rays_hit},
                          {"segments", s.segments},      {"tet_steps", s.tet_steps},
                          {"entries", s.entries},        {"lost_walks", s.lost_walks}, {"flat_tets", s.flat_tets},
                          {"boundary_faces", s.boundary_faces}, {"unbinned_faces", s.unbinned_faces},
                          {"image", {{"width", img.width}, {"height", img.height}}}};
      AtomicFile f(*stats);
      {
        std::ofstream o(f.temp_path());
        o << j.dump(2) << "\n";
        if (!o) throw std::runtime_error(*stats + ": cannot write stats");
      }
      f.commit();
    }
    std::printf("wrote %s: %ux%u, %llu rays hit, %llu segments, %llu lost walks, %.1f ms\n", out->c_str(), img.width,
                img.height, (unsigned long long)s.rays_hit, (unsigned long long)s.segments,
                (unsigned long long)s.lost_walks, s.ms_total);
  });
}

}  // namespace zs
