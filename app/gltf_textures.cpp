// glTF textures: images decoded once per (image, colour space) and shared (on all cores when prefetched), samplers
// and KHR_texture_transform. The materials that use them are in gltf_materials.cpp.
#include <cmath>
#include <cstring>

#include <tbb/parallel_for.h>

#include "app/gltf_internal.h"
#include "core/image_io.h"

namespace lumis::gltf {

namespace {

/// Texture images as lumis expects them: R, G, B and optionally A (grey replicated).
Image to_rgba(Image src) {
  if (src.channels == 3 || src.channels == 4) {
    src.channel_names = src.channels == 3 ? std::vector<std::string>{"R", "G", "B"}
                                          : std::vector<std::string>{"R", "G", "B", "A"};
    return src;
  }
  const bool grey = src.channels < 3;
  const bool alpha = src.channels == 2 || src.channels > 4;
  Image out(src.width, src.height, alpha ? std::vector<std::string>{"R", "G", "B", "A"}
                                         : std::vector<std::string>{"R", "G", "B"});
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x) {
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = src.at(x, y, grey ? 0 : c);
      if (alpha) out.at(x, y, 3) = src.at(x, y, grey ? 1 : 3);
    }
  return out;
}

/// OpenImageIO's reader for encoded image bytes: the format their signature shows (for files, too, OpenImageIO goes by
/// the contents when the extension is wrong), else the declared mime type's, whose reader then says what is wrong.
std::string reader_for(const unsigned char* p, size_t n, const std::string& mime_type) {
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static const unsigned char jpeg[3] = {0xff, 0xd8, 0xff};
  if (n >= 8 && std::memcmp(p, png, 8) == 0) return "png";
  if (n >= 3 && std::memcmp(p, jpeg, 3) == 0) return "jpeg";
  return mime_type == "image/png" ? "png" : "jpeg";
}

WrapMode wrap_mode(const Context& ctx, int v, const std::string& where) {
  switch (v) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return WrapMode::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return WrapMode::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return WrapMode::MirroredRepeat;
    default: ctx.fail(where, "wrap mode " + std::to_string(v) + ", expected 10497, 33071 or 33648");
  }
}

Vec2 vec2(const Context& ctx, const tinygltf::Value& v, const std::string& where) {
  if (!v.IsArray() || v.ArrayLen() != 2) ctx.fail(where, "expected an array of 2 numbers");
  return {number(ctx, v.Get(0), where), number(ctx, v.Get(1), where)};
}

}  // namespace

float number(const Context& ctx, const tinygltf::Value& v, const std::string& where) {
  // Finite as a float too: 1e39 is a finite double.
  if (!v.IsNumber() || !std::isfinite(static_cast<float>(v.GetNumberAsDouble())))
    ctx.fail(where, "expected a finite number (within float's range)");
  return static_cast<float>(v.GetNumberAsDouble());
}

void ImageCache::prefetch(const std::set<std::pair<int, bool>>& keys) {
  std::vector<std::pair<int, bool>> todo;
  for (const auto& k : keys)
    if (k.first >= 0 && static_cast<size_t>(k.first) < ctx_.model.images.size()) todo.push_back(k);
  std::vector<std::shared_ptr<const Image>> done(todo.size());
  tbb::parallel_for(size_t(0), todo.size(), [&](size_t i) {
    try {
      done[i] = std::make_shared<const Image>(load(todo[i].first, todo[i].second));
    } catch (const SceneError&) {
    }
  });
  for (size_t i = 0; i < todo.size(); ++i)
    if (done[i]) cache_[todo[i]] = done[i];
}

std::shared_ptr<const Image> ImageCache::get(int index, bool srgb, const std::string& where) {
  if (index < 0 || static_cast<size_t>(index) >= ctx_.model.images.size())
    ctx_.fail(where, "image index " + std::to_string(index) + " out of range (the file has " +
                         std::to_string(ctx_.model.images.size()) + " images)");
  auto& slot = cache_[{index, srgb}];
  if (!slot) slot = std::make_shared<const Image>(load(index, srgb));
  // A file the image came from (decoded now or by prefetch): recorded once, here on the calling thread.
  const tinygltf::Image& img = ctx_.model.images[index];
  if (img.bufferView < 0 && !img.uri.empty() && recorded_.insert(index).second && ctx_.image_files)
    ctx_.image_files->push_back(resolve_uri(ctx_, img.uri));
  return slot;
}

Image ImageCache::load(int index, bool srgb) {
  const tinygltf::Image& img = ctx_.model.images[index];
  const std::string at = indexed("images", index);
  if (img.bufferView < 0 && !img.uri.empty()) {
    const std::string path = resolve_uri(ctx_, img.uri);
    try {
      Image decoded = read_image(path, srgb);
      check_texels(decoded, path, /*allow_negative=*/!srgb);  // colour textures (sRGB ones) are >= 0
      return to_rgba(std::move(decoded));
    } catch (const ImageError& e) {
      ctx_.fail(at, "cannot load image '" + img.uri + "': " + e.what());
    }
  }
  // Embedded: a bufferView (checked here, as tinygltf does not) or a data: URI kept raw by our image callback,
  // decoded by OpenImageIO from memory exactly as the same bytes in a file would be.
  if (img.mimeType != "image/png" && img.mimeType != "image/jpeg")
    ctx_.fail(at + ".mimeType", "unsupported image format '" + img.mimeType + "' (expected image/png or "
                                "image/jpeg)");
  const unsigned char* bytes = img.image.data();
  size_t size = img.image.size();
  std::string source = "a data: URI";
  if (img.bufferView >= 0) {
    std::tie(bytes, size) = buffer_view_bytes(ctx_, img.bufferView, at + ".bufferView");
    source = indexed("bufferViews", img.bufferView);
  }
  if (size == 0) ctx_.fail(at, "image has no data");
  try {
    const std::string reader = reader_for(bytes, size, img.mimeType);
    return to_rgba(read_image_memory(bytes, size, reader, img.mimeType + " in " + source, srgb));
  } catch (const ImageError& e) {
    ctx_.fail(at, std::string("cannot decode embedded image: ") + e.what());
  }
}

/// A material's texture reference (index, texCoord, extensions) to a Texture; `where` is e.g.
/// "materials[2].pbrMetallicRoughness.baseColorTexture".
Texture make_texture(Context& ctx, ImageCache& images, int index, int tex_coord,
                     const tinygltf::ExtensionMap& extensions, bool srgb, const std::string& where) {
  const auto& textures = ctx.model.textures;
  if (index < 0 || static_cast<size_t>(index) >= textures.size())
    ctx.fail(where + ".index", "texture index " + std::to_string(index) + " out of range (the file has " +
                                   std::to_string(textures.size()) + " textures)");
  const tinygltf::Texture& tex = textures[index];
  const std::string at = indexed("textures", index);
  if (tex.source < 0)
    ctx.fail(at, "texture has no PNG or JPEG source (only an extension's image format, which is unsupported)");
  Texture out;
  out.image = images.get(tex.source, srgb, at + ".source");
  if (tex.sampler >= 0) {
    if (static_cast<size_t>(tex.sampler) >= ctx.model.samplers.size())
      ctx.fail(at + ".sampler", "sampler index " + std::to_string(tex.sampler) + " out of range");
    const tinygltf::Sampler& s = ctx.model.samplers[tex.sampler];
    const std::string sat = indexed("samplers", tex.sampler);
    out.wrap_s = wrap_mode(ctx, s.wrapS, sat + ".wrapS");
    out.wrap_t = wrap_mode(ctx, s.wrapT, sat + ".wrapT");
    out.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
  }
  out.tex_coord = tex_coord;
  if (auto it = extensions.find("KHR_texture_transform"); it != extensions.end()) {
    const tinygltf::Value& t = it->second;
    const std::string tat = where + ".extensions.KHR_texture_transform";
    if (!t.IsObject()) ctx.fail(tat, "expected an object");
    if (t.Has("offset")) out.transform.offset = vec2(ctx, t.Get("offset"), tat + ".offset");
    if (t.Has("rotation")) out.transform.rotation = number(ctx, t.Get("rotation"), tat + ".rotation");
    if (t.Has("scale")) out.transform.scale = vec2(ctx, t.Get("scale"), tat + ".scale");
    if (t.Has("texCoord")) {
      if (!t.Get("texCoord").IsInt()) ctx.fail(tat + ".texCoord", "expected an integer");
      out.tex_coord = t.Get("texCoord").GetNumberAsInt();
    }
  }
  if (out.tex_coord < 0 || out.tex_coord > 1) {
    ctx.warn_once("texcoord", where + ": TEXCOORD_" + std::to_string(out.tex_coord) +
                                  " is not supported (only 0 and 1); using TEXCOORD_0");
    out.tex_coord = 0;
  }
  return out;
}

}  // namespace lumis::gltf
