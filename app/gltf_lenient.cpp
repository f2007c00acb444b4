// Valid glTF files that tinygltf 2.7 refuses, read all the same (gltf_internal.h): it requires two fields that
// glTF 2.0 makes optional, both in parts of a file that lumis does not read (skins, animations).
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "app/gltf_internal.h"

namespace lumis::gltf {

namespace fs = std::filesystem;

std::optional<std::string> text_for_tinygltf(const Json& doc) {
  // An animation channel's target without a node (glTF: the animated object may then be defined by an extension,
  // as KHR_animation_pointer does) makes tinygltf refuse the whole file. lumis reads no animations.
  const auto animations = doc.find("animations");
  if (!doc.is_object() || animations == doc.end() || !animations->is_array()) return std::nullopt;
  bool nodeless = false;
  for (const Json& a : *animations)
    if (const auto channels = a.is_object() ? a.find("channels") : a.end(); channels != a.end() && channels->is_array())
      for (const Json& c : *channels)
        if (const auto t = c.is_object() ? c.find("target") : c.end(); t != c.end() && t->is_object())
          nodeless = nodeless || !t->contains("node");
  if (!nodeless) return std::nullopt;
  Json without = doc;
  without.erase("animations");
  return without.dump();
}

bool load_text(tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& err, std::string& warn,
               const std::string& path, bool binary, const std::string& json) {
  const std::string base = fs::path(path).parent_path().string();  // as tinygltf's LoadASCIIFromFile finds it
  if (!binary)
    return loader.LoadASCIIFromString(&model, &err, &warn, json.data(), static_cast<unsigned>(json.size()), base);
  // The .glb (its framing checked: check_glb_framing) with its JSON chunk replaced, padded with spaces to a multiple
  // of 4 bytes, and its binary chunk as it was.
  std::ifstream in(path, std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  uint32_t length = 0, json_length = 0;
  std::memcpy(&length, file.data() + 8, 4);
  std::memcpy(&json_length, file.data() + 12, 4);
  const std::string padded = json + std::string((4 - json.size() % 4) % 4, ' ');
  const std::string rest = file.substr(20 + size_t{json_length}, length - 20 - size_t{json_length});
  const uint64_t total = 20 + uint64_t{padded.size()} + rest.size();
  if (total > UINT32_MAX) {
    err = "the file without its animations would be longer than a .glb can be";
    return false;
  }
  std::string glb = file.substr(0, 20) + padded + rest;
  const uint32_t total32 = static_cast<uint32_t>(total), padded32 = static_cast<uint32_t>(padded.size());
  std::memcpy(glb.data() + 8, &total32, 4);
  std::memcpy(glb.data() + 12, &padded32, 4);
  return loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                     total32, base);
}

std::string without_spec_valid_complaints(std::string err) {
  // A skin without inverseBindMatrices (glTF: optional, identity matrices then) gets an error line from tinygltf,
  // which reads the file on. lumis draws skinned meshes in their bind pose, without the skin.
  const std::string line = "'inverseBindMatrices' property is missing in Skin.\n";
  for (size_t at; (at = err.find(line)) != std::string::npos;) err.erase(at, line.size());
  return err;
}

}  // namespace lumis::gltf
