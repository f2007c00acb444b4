#include "core/camera.h"

#include <cmath>

namespace lumis {

void Camera::prepare(int width, int height) {
  width_ = width;
  height_ = height;
  const Vec3 w = normalize(from - to);  // camera looks along -w
  Vec3 u = cross(up, w);
  if (!(length_squared(u) > 1e-12f)) u = cross(std::abs(w.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0), w);
  u = normalize(u);
  const Vec3 v = cross(w, u);
  const float half_h = std::tan(fov_y_degrees * kPi / 360.0f);
  const float half_w = half_h * static_cast<float>(width) / static_cast<float>(height);
  origin_ = from;
  // Image plane at distance 1: pixel (0,0) is the top-left corner.
  lower_left_ = -w - u * half_w + v * half_h;
  dx_ = u * (2 * half_w / static_cast<float>(width));
  dy_ = v * (-2 * half_h / static_cast<float>(height));
}

Ray Camera::generate_ray(Vec2 film) const {
  const Vec3 d = normalize(lower_left_ + dx_ * film.x + dy_ * film.y);
  return {origin_ + d * near_clip, d, 0, INFINITY};
}

}  // namespace lumis
