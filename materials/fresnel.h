// Schlick's Fresnel approximation, shared by the GGX lobe and the PBR diffuse/specular coupling.
#pragma once

#include "core/math.h"

namespace lumis {

/// Reflectance for cosine c between a direction and the (micro)normal, given f0 at normal incidence.
inline Color schlick_fresnel(Color f0, float c) {
  const float m = clamp(1.0f - c, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (Color(1.0f) - f0) * (m2 * m2 * m);
}

}  // namespace lumis
