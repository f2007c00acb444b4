// libFuzzer target: arbitrary bytes as a glTF file, loaded both as .glb and as .gltf (tinygltf decides by the
// extension whether to expect the binary container). Each load must succeed (then the scene renders tiny) or throw
// SceneError; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/scene_error.h"
#include "app/scene_loader.h"
#include "core/image.h"
#include "tests/fuzz/fuzz_common.h"

namespace {

void load_as(const std::string& path, const uint8_t* data, size_t size) {
  using namespace lumis;
  fuzz::write_file(path, data, size);
  try {
    auto scene = load_scene(path);
    fuzz::render_tiny(*scene);
  } catch (const SceneError&) {
  } catch (const ImageError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const lumis::fuzz::ScratchFile glb(".glb"), gltf(".gltf");
  load_as(glb.path, data, size);
  load_as(gltf.path, data, size);
  return 0;
}
