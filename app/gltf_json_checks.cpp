// Checks of a glTF file's JSON text for what tinygltf 2.7 lets through silently: a node with both a matrix and
// translation/rotation/scale (it keeps the matrix), and a negative byte offset, length or stride (it leaves the field
// at 0). Each scans the text first and parses it again only when the text could hold the fault.
#include <cctype>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "app/gltf_internal.h"

namespace lumis::gltf {

void check_matrix_nodes(const Context& ctx, const std::string& text) {
  if (text.find("\"matrix\"") == std::string::npos) return;  // the common case, without a second parse
  const auto doc = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return;  // tinygltf reports it
  const auto nodes = doc.find("nodes");
  if (nodes == doc.end() || !nodes->is_array()) return;
  for (size_t i = 0; i < nodes->size(); ++i) {
    const auto& n = (*nodes)[i];
    if (n.is_object() && n.contains("matrix") &&
        (n.contains("translation") || n.contains("rotation") || n.contains("scale")))
      ctx.fail(indexed("nodes", i), "has both \"matrix\" and translation/rotation/scale; glTF allows one or the "
                                    "other (lumis's reader would use the matrix alone)");
  }
}

namespace {

/// Whether some `"key": -...` occurs in the text (the key inside a string value would match too; the parse decides).
bool negative_after(std::string_view text, std::string_view key) {
  for (size_t at = text.find(key); at != std::string_view::npos; at = text.find(key, at + 1)) {
    size_t k = at + key.size();
    while (k < text.size() && (std::isspace(static_cast<unsigned char>(text[k])) || text[k] == ':')) ++k;
    if (k < text.size() && text[k] == '-') return true;
  }
  return false;
}

}  // namespace

void check_unsigned_fields(const Context& ctx, const std::string& text) {
  static const char* kFields[] = {"byteOffset", "byteLength", "byteStride"};
  static const char* kQuoted[] = {"\"byteOffset\"", "\"byteLength\"", "\"byteStride\""};
  bool suspect = false;
  for (const char* q : kQuoted) suspect = suspect || negative_after(text, q);
  if (!suspect) return;
  const auto doc = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return;  // tinygltf reports it
  for (const char* list : {"buffers", "bufferViews", "accessors"}) {
    const auto items = doc.find(list);
    if (items == doc.end() || !items->is_array()) continue;
    for (size_t i = 0; i < items->size(); ++i)
      for (const char* f : kFields) {
        const auto& item = (*items)[i];
        if (!item.is_object() || !item.contains(f) || !item[f].is_number() || item[f].get<double>() >= 0) continue;
        ctx.fail(indexed(list, i) + "." + f, "expected a whole number >= 0, found " + item[f].dump());
      }
  }
}

}  // namespace lumis::gltf
