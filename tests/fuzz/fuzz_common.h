// Shared by the libFuzzer targets: load a scene file and, when it loads, render it tiny so that what the loader
// accepted is also exercised by the BVH build, the lights and the integrator (NaN rays abort inside Embree).
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "app/scene_error.h"
#include "core/film.h"
#include "core/image.h"
#include "integrators/render.h"

namespace lumis::fuzz {

/// A per-process scratch file with this extension (in $TMPDIR or /tmp), rewritten for every input and removed at
/// exit.
struct ScratchFile {
  std::string path;
  explicit ScratchFile(const std::string& ext) {
    const char* dir = std::getenv("TMPDIR");
    path = std::string(dir && *dir ? dir : "/tmp") + "/lumis-fuzz-" + std::to_string(::getpid()) + ext;
  }
  ~ScratchFile() { std::remove(path.c_str()); }
};

inline void write_file(const std::string& path, const uint8_t* data, size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size) std::fwrite(data, 1, size, f);
  std::fclose(f);
}

/// Render 4x4 pixels at 1 spp with short paths on one thread: cheap, but every code path of a pixel runs.
inline void render_tiny(Scene& scene) {
  RenderSettings& s = scene.settings;
  s.width = s.height = 4;
  s.max_depth = 3;
  s.time_budget = 0;
  std::unique_ptr<Integrator> integrator;
  try {
    integrator = make_integrator(s);
  } catch (const std::exception&) {
    return;  // a bad name is reported before rendering; the loader has already validated it
  }
  Film film(s.width, s.height);
  RenderOptions ro;
  ro.spp = 1;
  ro.threads = 1;
  render(scene, *integrator, film, ro);
}

}  // namespace lumis::fuzz
