// Pinhole perspective camera.
#pragma once

#include "core/geometry.h"
#include "core/math.h"

namespace lumis {

struct Camera {
  Vec3 from{0, 0, 1}, to{0, 0, 0}, up{0, 1, 0};
  float fov_y_degrees = 40;  ///< vertical field of view
  float near_clip = 0;       ///< rays start at this distance

  /// Precompute the basis for an image of width x height pixels.
  void prepare(int width, int height);
  /// Primary ray through film position (x, y) in pixels (origin top-left, y down). Direction is unit.
  Ray generate_ray(Vec2 film) const;

 private:
  Vec3 origin_, lower_left_, dx_, dy_;
  int width_ = 1, height_ = 1;
};

}  // namespace lumis
