#include "integrators/integrator.h"

#include <stdexcept>

namespace lumis {

const std::vector<std::string>& integrator_names() {
  static const std::vector<std::string> names{"uniform", "bsdf", "light", "mis", "nee_mis"};
  return names;
}

bool finds_lights_by_hitting(const std::string& integrator) {
  return integrator == "uniform" || integrator == "bsdf" || integrator == "mis";
}

std::unique_ptr<Integrator> make_integrator(const RenderSettings& s) {
  if (s.integrator == "uniform") return make_uniform_integrator(s);
  if (s.integrator == "bsdf") return make_bsdf_integrator(s);
  if (s.integrator == "light") return make_light_integrator(s);
  if (s.integrator == "mis") return make_mis_integrator(s);
  if (s.integrator == "nee_mis") return make_nee_mis_integrator(s);
  std::string valid;
  for (const auto& n : integrator_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + s.integrator + "' (valid: " + valid + ")");
}

}  // namespace lumis
