// libFuzzer target: the closed triangle-surface reader behind `mesh generate
// --surface` (read_surface: CGAL's .off/.stl/.ply/.obj polygon-soup readers,
// then our fan triangulation, closure, manifold and self-intersection
// checks). The first byte picks the format (mod 4: off, stl, obj, ply; the
// seeds use '0'..'3'), the rest is the file, written to a per-process
// temporary because the readers take paths. Rejections (FileError naming the
// file) are expected outcomes; surface_precheck.h keeps CGAL 5.5's readers
// from the inputs they crash or run out of memory on (docs/robustness.md).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include <unistd.h>

#include "geometry/tets/generate/surface_io.h"
#include "base/util/file_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kExt[4] = {".off", ".stl", ".obj", ".ply"};
  const std::string path =
      "/tmp/zsweep-fuzz-surface-" + std::to_string(::getpid()) + kExt[data[0] % 4];
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data + 1, 1, size - 1, f);
    std::fclose(f);
  } else {
    return 0;
  }
  try {
    (void)zs::read_surface(path);
  } catch (const zs::FileError&) {
  }
  std::remove(path.c_str());
  return 0;
}
