// URIs of glTF buffers and images: percent-decoding as RFC 3986 says, the '+' that tinygltf 2.7 reads as a space put
// back, and a buffer's URI checked (its file, or its data: URI's base64) so that an error names the buffer.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>


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

std::string unreadable_reason(const std::string& file) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(file, ec);
  if (std::filesystem::is_regular_file(st)) return {};
  if (std::filesystem::is_directory(st)) return "is a folder";
  if (std::filesystem::exists(st)) return "is not a regular file (a pipe, device or socket)";
  return "not found";
}

namespace {

/// At most n characters of s, for messages: a data: URI can be megabytes long.
std::string clip(const std::string& s, size_t n) {
  return s.size() <= n ? s : s.substr(0, n) + "... (" + std::to_string(s.size() - n) + " more characters)";
}

bool is_base64_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/';
}

/// A base64 data: URI as tinygltf 2.7 decodes it: one of its media types, the alphabet, '=' only as the final padding,
/// and exactly byte_length bytes.
void check_data_uri(const Context& ctx, const std::string& at, const std::string& uri, uint64_t byte_length) {
  // The media types tinygltf 2.7 decodes for a buffer (IsDataURI and DecodeDataURI agree on these); another one is
  // read as a file name.
  static const char* kPrefixes[] = {"data:application/octet-stream;base64,", "data:application/gltf-buffer;base64,",
                                    "data:image/jpeg;base64,", "data:image/png;base64,", "data:image/bmp;base64,",
                                    "data:image/gif;base64,", "data:text/plain;base64,"};
  const size_t comma = uri.find(',');
  const std::string head = uri.substr(0, comma == std::string::npos ? uri.size() : comma + 1);
  if (std::none_of(std::begin(kPrefixes), std::end(kPrefixes), [&](const char* p) { return head == p; }))
    ctx.fail(at + ".uri", "a data: URI that lumis's glTF reader cannot decode, '" + clip(head, 60) +
                              "' (expected " + kPrefixes[0] + "... or " + kPrefixes[1] + "...)");
  const std::string_view data = std::string_view(uri).substr(comma + 1);
  size_t end = data.size();
  while (end > 0 && data.size() - end < 2 && data[end - 1] == '=') --end;  // up to two padding characters
  for (size_t k = 0; k < end; ++k)
    if (!is_base64_char(data[k])) {
      const unsigned char c = static_cast<unsigned char>(data[k]);
      char shown[8];
      std::snprintf(shown, sizeof shown, std::isprint(c) ? "'%c'" : "0x%02x", c);
      ctx.fail(at + ".uri", "invalid base64 in the data: URI: " + std::string(shown) + " at character " +
                                std::to_string(k) + " after the comma");
    }
  const uint64_t bytes = end * 3 / 4;
  if (bytes != byte_length)
    ctx.fail(at + ".byteLength", "is " + std::to_string(byte_length) + ", but the data: URI holds " +
                                     std::to_string(bytes) + " bytes");
}

}  // namespace

void check_buffer_uri(const Context& ctx, size_t i, const std::string& uri, uint64_t byte_length, bool explaining) {
  const std::string at = indexed("buffers", i);
  if (uri.empty()) {
    if (explaining)
      ctx.fail(at + ".uri", "is empty: expected a file name or a data: URI (a .glb's own buffer has none)");
    return;
  }
  if (uri.rfind("data:", 0) == 0) {
    if (explaining) check_data_uri(ctx, at, uri, byte_length);
    return;
  }
  if (decode_uri(uri).find('\0') != std::string::npos)
    ctx.fail(at + ".uri", "'" + uri + "' names a file with a NUL character (%00) in it");
  const std::string file = resolve_uri(ctx, uri);
  if (const std::string why = unreadable_reason(file); !why.empty())
    ctx.fail(at + ".uri", "buffer file '" + uri + "' " + why + " (looked for " + file + ")");
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(file, ec);
  if (!ec && size != byte_length)
    ctx.fail(at + ".byteLength", "is " + std::to_string(byte_length) + ", but the file " + file + " has " +
                                     std::to_string(size) + " bytes");
}

PlusUris plus_uris(const Context& ctx, const Json& doc) {
  PlusUris uris;
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
