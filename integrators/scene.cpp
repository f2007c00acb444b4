#include "integrators/scene.h"

namespace lumis {

void Scene::finalize() {
  geometry.commit();
  const Bounds3 bounds = geometry.bounds();
  std::vector<const Light*> ptrs;
  for (auto& l : lights) {
    l->preprocess(bounds);
    ptrs.push_back(l.get());
  }
  light_selector = LightSelector(std::move(ptrs), settings.light_selection);
}

}  // namespace lumis
