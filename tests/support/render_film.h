// Render a scene with its own settings (integrator, sampler, seed, size) into a Film: the one helper the
// statistical image tests share. Header-only, for tests that link the integrators layer.
#pragma once

#include <memory>

#include "core/film.h"
#include "integrators/render.h"

namespace lumis::test {

struct Rendered {
  Film film;
  RenderStats stats;
};

/// scene.settings.integrator at `spp` samples per pixel into a scene.settings.width x height film.
inline Rendered render_film(const Scene& scene, uint32_t spp, RenderOptions options = {}, FilmOptions film = {}) {
  const std::unique_ptr<Integrator> integrator = make_integrator(scene.settings);
  Rendered out{Film(scene.settings.width, scene.settings.height, film), {}};
  options.spp = spp;
  out.stats = render(scene, *integrator, out.film, options);
  return out;
}

}  // namespace lumis::test
