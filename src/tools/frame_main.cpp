// zsweep_frame: renders a classic tet .off (automatic camera and transfer
// function, as `zsweep render MESH`) a number of times and prints each
// frame's time. A profiling harness: it links the engine without VTK, CGAL or
// OpenImageIO, so it starts in milliseconds and runs under valgrind (the
// main binary loads libhwy through OpenImageIO, whose start-up uses an
// instruction valgrind 3.19 cannot decode).
//
//   zsweep_frame MESH.off [size=512] [frames=3] [threads=1] [scan=span] [tile=64] [precision=double]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "geometry/tets/io/off_io.h"
#include "geometry/tets/topology.h"
#include "scene/scene_defaults.h"
#include "render/volume/zsweep_renderer.h"

int main(int argc, char** argv) {
  using namespace zs;
  if (argc < 2) {
    std::fprintf(stderr, "usage: zsweep_frame MESH.off [size] [frames] [threads] [scan] [tile] [double|single]\n");
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
    if (argc > 7) rs.single_precision = !std::strcmp(argv[7], "single");
    rs.camera = auto_camera(mesh, Projection::Orthographic, size, size);
    rs.tf = default_transfer_function(mesh);
    const Topology topo = build_topology(mesh);
    // The sum of the image, and a hash of its bits that does not depend on
    // the order tiles arrive in (a sum of per-pixel hashes).
    struct Discard : TileSink {
      double sum = 0;
      uint64_t bits = 0;
      void tile(const TileRect& r, const float* rgba) override {
        for (uint32_t y = r.y0; y < r.y1; ++y)
          for (uint32_t x = r.x0; x < r.x1; ++x) {
            const float* p = rgba + (size_t(y - r.y0) * r.width() + (x - r.x0)) * 4;
            uint64_t h = (uint64_t(y) << 32 | x) * 0x9E3779B97F4A7C15ull;
            for (int c = 0; c < 4; ++c) {
              uint32_t u;
              std::memcpy(&u, p + c, 4);
              h = (h ^ u) * 0x100000001B3ull;
              sum += p[c];
            }
            bits += h;
          }
      }
    };
    for (int f = 0; f < frames; ++f) {
      Discard sink;
      RenderStats st;
      render_zsweep_tiles(mesh, topo, rs, sink, 0, &st);
      std::printf("frame %d: %.2f ms (setup %.2f: order %.2f, bins %.2f), %llu fragments, %llu segments, checksum %.9g, bits %016llx\n", f, st.ms_total,
                  st.ms_setup, st.ms_order, st.ms_binning, (unsigned long long)st.fragments, (unsigned long long)st.segments, sink.sum,
                  (unsigned long long)sink.bits);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "zsweep_frame: %s\n", e.what());
    return 1;
  }
  return 0;
}
