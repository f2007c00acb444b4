// URIs of glTF buffers and images: percent-decoding as RFC 3986 says, and the '+' that tinygltf 2.7 reads as a
// space put back.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "app/gltf_internal.h"

namespace lumis::gltf {

std::string decode_uri(const std::string& uri) {
  std::string decoded;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      decoded += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  return decoded;
}

std::string resolve_uri(const Context& ctx, const std::string& uri) {
  return (std::filesystem::path(ctx.base_dir) / decode_uri(uri)).string();
}

PlusUris plus_uris(const Context& ctx, const std::string& text) {
  PlusUris uris;
  if (text.find('+') == std::string::npos) return uris;
  const auto doc = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return uris;
  std::map<std::string, std::pair<std::string, std::string>> seen;  // misread -> (meant, "glTF path 'URI'")
  for (const char* key : {"buffers", "images"}) {
    const auto list = doc.find(key);
    if (list == doc.end() || !list->is_array()) continue;
    for (size_t i = 0; i < list->size(); ++i) {
      const auto& item = (*list)[i];
      if (!item.is_object()) continue;
      const auto u = item.find("uri");
      if (u == item.end() || !u->is_string()) continue;
      const std::string uri = *u;
      if (uri.rfind("data:", 0) == 0) continue;
      std::string spaced = uri;
      std::replace(spaced.begin(), spaced.end(), '+', ' ');
      const std::string misread = decode_uri(spaced), meant = decode_uri(uri);
      const std::string at = indexed(key, i) + ".uri";
      const auto [it, fresh] = seen.try_emplace(misread, meant, at + " '" + uri + "'");
      if (!fresh && it->second.first != meant)
        ctx.fail(at, "'" + uri + "' and " + it->second.second +
                         " name different files that lumis's glTF reader (tinygltf 2.7) cannot tell apart: '+' "
                         "reads as a space there; rename one");
      if (misread != meant) uris.plus[misread] = meant;
    }
  }
  return uris;
}

std::string expand_plus_uri(const std::string& path, void* plus_uris) {
  for (const auto& [misread, meant] : static_cast<const PlusUris*>(plus_uris)->plus) {
    if (path.size() < misread.size()) continue;
    const size_t at = path.size() - misread.size();
    if (path.compare(at, misread.size(), misread) == 0 && (at == 0 || path[at - 1] == '/'))
      return path.substr(0, at) + meant;
  }
  return path;
}

}  // namespace lumis::gltf
