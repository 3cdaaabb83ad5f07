// libFuzzer target: the scene / transfer-function JSON parser (parse_scene),
// then a small render of the embedded default mesh with the parsed camera,
// transfer function and render settings (image clamped to a few pixels).
// Rejections (std::runtime_error naming the input) are expected outcomes;
// anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_render.h"
#include "mesh/default_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace zs;
  static const TetMesh mesh = default_mesh(2);  // a few dozen tets
  Scene scene;
  try {
    // Preset paths resolve against a directory that does not exist, so a
    // fuzzed scene cannot read the machine's files.
    scene = parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json",
                        "/nonexistent-zsweep-fuzz");
  } catch (const std::runtime_error&) {
    return 0;
  }
  fuzz::render_small(mesh, scene.settings, !scene.has_camera, !scene.has_transfer_function);
  return 0;
}
