// Image textures with glTF sampling rules: wrap modes, KHR_texture_transform, bilinear filtering.
#pragma once

#include <memory>

#include "core/image.h"
#include "core/math.h"

namespace lumis {

enum class WrapMode { Repeat, ClampToEdge, MirroredRepeat };

/// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv.
struct TextureTransform {
  Vec2 offset{0, 0};
  float rotation = 0;  ///< radians, counter-clockwise in UV space
  Vec2 scale{1, 1};
  Vec2 apply(Vec2 uv) const {
    const float c = std::cos(rotation), s = std::sin(rotation);
    const float x = uv.x * scale.x, y = uv.y * scale.y;
    return {c * x + s * y + offset.x, -s * x + c * y + offset.y};
  }
};

struct Texture {
  std::shared_ptr<const Image> image;  ///< linear values; RGBA (missing channels: 0 for G/B, 1 for alpha)
  WrapMode wrap_s = WrapMode::Repeat, wrap_t = WrapMode::Repeat;
  bool nearest = false;                 ///< nearest-neighbour instead of bilinear
  TextureTransform transform;
  int tex_coord = 0;                    ///< which TEXCOORD set (0 or 1)

  /// Bilinear lookup at glTF uv (origin top-left, v down), after the transform. Returns RGBA.
  Vec4 sample(Vec2 uv) const;
};

}  // namespace lumis
