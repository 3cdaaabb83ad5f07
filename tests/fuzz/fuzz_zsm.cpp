// libFuzzer target: the .zsm reader (parse_zsm, the code read_zsm runs on a
// file), then topology, validation and a small render of any mesh it
// accepts. FileError is an expected outcome; any other exception (a
// bad_alloc from a header the checks let through, say), crash, leak or
// sanitizer report is a finding, as is an accepted mesh with an index out of
// range or scalars that do not match its points.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fuzz_render.h"
#include "geometry/tets/io/zsm_io.h"
#include "base/util/file_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace zs;
  TetMesh mesh;
  try {
    mesh = parse_zsm(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.zsm");
  } catch (const FileError&) {
    return 0;
  }
  if (mesh.has_scalars() && mesh.scalars.size() != mesh.points.size()) std::abort();
  for (const Tet& t : mesh.tets)
    for (uint32_t v : t)
      if (v >= mesh.points.size()) std::abort();
  RenderSettings rs;
  rs.width = rs.height = fuzz::kMaxImage;
  fuzz::render_small(mesh, rs, true, true);
  return 0;
}
