#include "integrators/scene.h"

namespace lumis {

void Scene::finalize() {
  geometry.commit();
  const Bounds3 bounds = geometry.bounds();
  for (auto& l : lights) l->preprocess(bounds);
  update_light_selector();
}

std::vector<std::string> Scene::inputs() const {
  std::vector<std::string> all = input_files;
  all.insert(all.end(), input_images.begin(), input_images.end());
  return all;
}

void Scene::update_light_selector() {
  std::vector<const Light*> ptrs;
  for (auto& l : lights) ptrs.push_back(l.get());
  light_selector = LightSelector(std::move(ptrs), settings.light_selection);
}

}  // namespace lumis
