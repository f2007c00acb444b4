// libFuzzer target: arbitrary bytes as a lumis JSON scene. Every input must either load (and then render tiny) or
// throw SceneError/ImageError; anything else (a crash, a sanitizer report, another exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "app/scene_error.h"
#include "app/scene_loader.h"
#include "core/image.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lumis;
  // The bytes are parsed in memory; the (never written) path only names the scene in messages and anchors relative
  // paths (textures, glTF files) in the temporary folder.
  static const std::string path = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + "/fuzz.json";
  try {
    auto scene = load_scene_text(std::string(reinterpret_cast<const char*>(data), size), path);
    fuzz::render_tiny(*scene);
  } catch (const SceneError&) {
  } catch (const ImageError&) {
  }
  return 0;
}
