// libFuzzer target: the classic tet .off reader (parse_off), then topology,
// validation and a small render of any mesh it accepts. Errors the reader
// reports (FileError, one line naming the input) are expected outcomes; any
// other exception, crash, leak or sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_render.h"
#include "geometry/tets/io/off_io.h"
#include "base/util/file_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace zs;
  TetMesh mesh;
  try {
    mesh = parse_off(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.off");
  } catch (const FileError&) {
    return 0;
  }
  RenderSettings rs;
  rs.width = rs.height = fuzz::kMaxImage;
  fuzz::render_small(mesh, rs, true, true);
  return 0;
}
