#include "integrators/scene.h"

#include <unordered_set>

namespace lumis {

void Scene::finalize() {
  geometry.commit();
  const Bounds3 bounds = geometry.bounds();
  for (auto& l : lights) l->preprocess(bounds);
  update_light_selector();
}

std::vector<std::string> Scene::inputs() const {
  std::vector<std::string> all;
  std::unordered_set<std::string> seen;
  for (const std::vector<std::string>* files : {&input_files, &input_images})
    for (const std::string& file : *files)
      if (seen.insert(file).second) all.push_back(file);
  return all;
}

void Scene::update_light_selector() {
  std::vector<const Light*> ptrs;
  for (auto& l : lights) ptrs.push_back(l.get());
  light_selector = LightSelector(std::move(ptrs), settings.light_selection);
}

}  // namespace lumis
