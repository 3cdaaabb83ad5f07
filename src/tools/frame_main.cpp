// zsweep_frame: renders a classic tet .off (automatic camera and transfer
// function, as `zsweep render MESH`) a number of times and prints each
// frame's time. A profiling harness: it links the engine without VTK, CGAL or
// OpenImageIO, so it starts in milliseconds and runs under valgrind (the
// main binary loads libhwy through OpenImageIO, whose start-up uses an
// instruction valgrind 3.19 cannot decode).
//
//   zsweep_frame MESH.off [size=512] [frames=3] [threads=1] [scan=span] [tile=64]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "mesh/io/off_io.h"
#include "mesh/topology.h"
#include "scene/scene.h"
#include "volume/zsweep_renderer.h"

int main(int argc, char** argv) {
  using namespace zs;
  if (argc < 2) {
    std::fprintf(stderr, "usage: zsweep_frame MESH.off [size] [frames] [threads] [scan] [tile]\n");
    return 2;
  }
  try {
    const TetMesh mesh = read_off(argv[1]);
    const uint32_t size = argc > 2 ? uint32_t(std::atoi(argv[2])) : 512;
    const int frames = argc > 3 ? std::atoi(argv[3]) : 3;
    RenderSettings rs;
    rs.width = rs.height = size;
    rs.threads = argc > 4 ? std::atoi(argv[4]) : 1;
    if (!parse_scan_strategy(argc > 5 ? argv[5] : "span", &rs.scan)) throw std::runtime_error("unknown scan");
    if (argc > 6) rs.tile_size = uint32_t(std::atoi(argv[6]));
    rs.camera = auto_camera(mesh, Projection::Orthographic, size, size);
    rs.tf = default_transfer_function(mesh);
    const Topology topo = build_topology(mesh);
    struct Discard : TileSink {
      double sum = 0;
      void tile(const TileRect& r, const float* rgba) override {
        for (size_t k = 0; k < size_t(r.width()) * r.height() * 4; ++k) sum += rgba[k];
      }
    };
    for (int f = 0; f < frames; ++f) {
      Discard sink;
      RenderStats st;
      render_zsweep_tiles(mesh, topo, rs, sink, 0, &st);
      std::printf("frame %d: %.2f ms (setup %.2f: order %.2f, bins %.2f), %llu fragments, %llu segments, checksum %.9g\n", f, st.ms_total,
                  st.ms_setup, st.ms_order, st.ms_binning, (unsigned long long)st.fragments, (unsigned long long)st.segments, sink.sum);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "zsweep_frame: %s\n", e.what());
    return 1;
  }
  return 0;
}
