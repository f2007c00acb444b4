// Reading a glTF file through tinygltf (parse_file, gltf_internal.h): the checks of its JSON text before tinygltf
// sees it, and glTF-terms explanations of tinygltf's rejections.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

#include "app/gltf_internal.h"
#include "app/json_depth.h"

namespace lumis::gltf {

namespace fs = std::filesystem;

namespace {

/// Keep embedded images encoded until a material needs them (decoded then by OpenImageIO, from validated byte ranges,
/// as external images are); tinygltf's copy of external images' bytes is dropped here.
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && image->uri.empty()) image->image.assign(bytes, bytes + size);  // data: URI
  return true;
}

/// tinygltf's file-exists test, narrowed to regular files: a buffer or image URI naming a pipe or a device
/// (/dev/zero) would block or stream forever when read, so it is reported as missing instead.
bool regular_file_exists(const std::string& path, void*) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

/// asset.version and asset.minVersion: lumis reads glTF 2.0 (a later 2.x file must read as 2.0).
void check_version(const Context& ctx, const std::string& version, const std::string& min_version) {
  if (version.rfind("2.", 0) != 0)
    ctx.fail("asset.version", "glTF version \"" + version + "\": lumis reads glTF 2.0 (major version 2)");
  if (!min_version.empty() && min_version != "2.0")
    ctx.fail("asset.minVersion", "the file needs glTF " + min_version + "; lumis reads glTF 2.0");
}

/// The JSON text of a .gltf, or the JSON chunk of a .glb (12-byte header, chunk length, "JSON", the text, read
/// without the binary chunk); nothing when a .glb's header is too damaged to find it (tinygltf then says why).
std::optional<std::string> json_text(const std::string& path, bool binary) {
  std::ifstream in(path, std::ios::binary);
  if (!binary) return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  char head[20] = {};
  if (!in.read(head, sizeof(head)) || std::string_view(head + 16, 4) != "JSON") return std::nullopt;
  uint32_t length = 0;
  std::memcpy(&length, head + 12, 4);
  std::error_code ec;
  const uint64_t size = fs::file_size(path, ec);
  if (ec || length > size - sizeof(head)) return std::nullopt;
  std::string text(length, '\0');
  if (!in.read(text.data(), length)) return std::nullopt;
  return text;
}

/// A .glb's framing (glTF 2.0, "GLB File Format Specification"): a 12-byte header (magic, version 2, total length),
/// then a JSON chunk and an optional binary one, each a length, a type and its bytes, ending on 4-byte boundaries.
/// tinygltf refuses a damaged one with "Invalid glTF binary." alone, and it lets a binary chunk run up to 8 bytes past
/// the file (it leaves the chunk's own header out of its bound): this says which part is wrong, before tinygltf reads
/// it. Bytes after the binary chunk are ignored, as the specification asks; so is a file longer than its header says.
void check_glb_framing(const Context& ctx, const std::string& path) {
  std::error_code ec;
  const uint64_t size = fs::file_size(path, ec);
  if (ec) return;  // unreadable: tinygltf says so
  const std::string n = std::to_string(size);
  if (size < 20) ctx.fail("", "invalid .glb: the file is " + n + " bytes long, too short for the 12-byte header and a "
                              "JSON chunk (is it cut short?)");
  std::ifstream in(path, std::ios::binary);
  char head[20] = {};
  if (!in.read(head, sizeof(head))) return;
  uint32_t version = 0, length = 0, json_length = 0;
  std::memcpy(&version, head + 4, 4);
  std::memcpy(&length, head + 8, 4);
  std::memcpy(&json_length, head + 12, 4);
  if (version != 2)
    ctx.fail("", "invalid .glb: binary glTF version " + std::to_string(version) + ", expected 2");
  if (length > size)
    ctx.fail("", "invalid .glb: the header says the file is " + std::to_string(length) + " bytes long, but it is " + n +
                     " (is it cut short?)");
  if (std::string_view(head + 16, 4) != "JSON")
    ctx.fail("", "invalid .glb: the first chunk (at byte 12) is not of type JSON");
  const uint64_t json_end = uint64_t{json_length} + 20;
  if (json_end > length)
    ctx.fail("", "invalid .glb: the JSON chunk's " + std::to_string(json_length) + " bytes run past the " +
                     std::to_string(length) + " bytes the header gives the file");
  if (json_length == 0 || json_length % 4 != 0)
    ctx.fail("", "invalid .glb: the JSON chunk is " + std::to_string(json_length) +
                     " bytes long; it must be padded with spaces to a non-zero multiple of 4");
  if (json_end == length) return;  // no binary chunk
  const std::string at = std::to_string(json_end);
  char bin_head[8] = {};
  if (length - json_end < 12 || !in.seekg(static_cast<std::streamoff>(json_end)) || !in.read(bin_head, 8))
    ctx.fail("", "invalid .glb: the " + std::to_string(length - json_end) + " bytes after the JSON chunk (at byte " +
                     at + ") are too few for a binary chunk: its 8-byte header and at least 4 bytes");
  uint32_t bin_length = 0;
  std::memcpy(&bin_length, bin_head, 4);
  if (std::string_view(bin_head + 4, 4) != std::string_view("BIN\0", 4))
    ctx.fail("", "invalid .glb: the second chunk (at byte " + at + ") is not of type BIN");
  if (bin_length == 0 || bin_length % 4 != 0)
    ctx.fail("", "invalid .glb: the binary chunk (at byte " + at + ") is " + std::to_string(bin_length) +
                     " bytes long; it must be padded to a non-zero multiple of 4");
  if (json_end + 8 + bin_length > length)
    ctx.fail("", "invalid .glb: the binary chunk's " + std::to_string(bin_length) + " bytes (from byte " +
                     std::to_string(json_end + 8) + ") run past the " + std::to_string(length) +
                     " bytes the header gives the file");
}

/// tinygltf converts the document to its own values recursively: refuse nesting that would overflow the stack.
void check_depth(const Context& ctx, const std::string& text, bool binary) {
  if (const auto at = json_too_deep(text))
    ctx.fail("", "the JSON" + std::string(binary ? " chunk" : "") + " nests deeper than " +
                     std::to_string(kMaxJsonDepth) + " levels (at line:column " + json_line_column(text, *at) +
                     "); lumis reads at most " + std::to_string(kMaxJsonDepth));
}

/// JSON that does not parse, at its line:column and in lumis's words, as a lumis scene's (tinygltf's message is
/// nlohmann's, with its prefix and the raw bytes it last read). A number beyond the double range is such an error
/// too: nlohmann throws out_of_range for it, not parse_error.
[[noreturn]] void fail_syntax(const Context& ctx, const std::string& text, bool binary) {
  try {
    const Json doc = parse_json_text(text, ctx.file);  // throws: the text failed to parse a moment ago
    (void)doc;
  } catch (const SceneError& e) {
    const std::string plain = "invalid JSON: ";
    if (!binary || e.detail.rfind(plain, 0) != 0) throw;
    throw SceneError(e.file, e.location, "invalid JSON chunk: " + e.detail.substr(plain.size()));
  }
  ctx.fail("", "invalid JSON");  // not reached
}

/// Where tinygltf rejects a file, name the cause in glTF terms when it is one of the likely ones above: a version
/// other than 2.0 (the structure of 1.0 differs) or a missing or short buffer file. Returns when it is none of them.
void explain_rejection(const Context& ctx, const std::string& path, bool binary) {
  const std::optional<std::string> json = json_text(path, binary);
  if (!json) return;
  const std::string& text = *json;
  const auto doc = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return;
  if (auto a = doc.find("asset"); a != doc.end() && a->is_object() && a->contains("version") &&
                                  (*a)["version"].is_string()) {
    // Not a->value("minVersion", ...): that throws for a minVersion of another type, which tinygltf ignores.
    const auto mv = a->find("minVersion");
    check_version(ctx, (*a)["version"], mv != a->end() && mv->is_string() ? mv->get<std::string>() : std::string());
  }
  if (auto b = doc.find("buffers"); b != doc.end() && b->is_array())
    for (size_t i = 0; i < b->size(); ++i) {
      const auto& buffer = (*b)[i];
      // A .glb's buffer with "uri": "" is its BIN chunk to tinygltf, so the rejection lies elsewhere.
      if (buffer.is_object() && buffer.contains("uri") && buffer["uri"].is_string() &&
          buffer.contains("byteLength") && buffer["byteLength"].is_number_unsigned() &&
          !(binary && buffer["uri"].get<std::string>().empty()))
        check_buffer_uri(ctx, i, buffer["uri"], buffer["byteLength"], /*explaining=*/true);
    }
}

}  // namespace

void parse_file(Context& ctx, const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) ctx.fail("", "no such file");
  char magic[4] = {};
  std::ifstream(path, std::ios::binary).read(magic, 4);
  const bool binary = std::string(magic, 4) == "glTF";
  if (binary) check_glb_framing(ctx, path);
  const std::optional<std::string> text = json_text(path, binary);
  if (text) check_depth(ctx, *text, binary);
  PlusUris plus;
  std::optional<std::string> lenient;  // the JSON text tinygltf gets instead, where it would refuse a valid file
  {  // one parse for lumis's own checks and the '+' URIs, freed before tinygltf parses the text into its model
    const Json doc = text ? Json::parse(*text, nullptr, /*allow_exceptions=*/false) : Json();
    if (text && doc.is_discarded()) fail_syntax(ctx, *text, binary);
    check_json(ctx, doc);
    plus = plus_uris(ctx, doc);
    lenient = text_for_tinygltf(doc);
  }

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  loader.SetFsCallbacks({&regular_file_exists, &expand_plus_uri, &tinygltf::ReadWholeFile,
                         &tinygltf::WriteWholeFile, &plus});
  std::string err, warn;
  const bool ok = lenient    ? load_text(loader, ctx.model, err, warn, path, binary, *lenient)
                 : binary     ? loader.LoadBinaryFromFile(&ctx.model, &err, &warn, path)
                              : loader.LoadASCIIFromFile(&ctx.model, &err, &warn, path);
  err = without_spec_valid_complaints(err);
  // tinygltf's message, without trailing blanks and at most 300 characters (it can quote a whole data: URI).
  auto trim = [](std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    if (s.size() > 300) s = s.substr(0, 300) + "... (" + std::to_string(s.size() - 300) + " more characters)";
    return s;
  };
  if (!ok || !err.empty()) {
    explain_rejection(ctx, path, binary);
    ctx.fail("", std::string(binary ? "invalid .glb: " : "invalid glTF: ") + trim(err.empty() ? warn : err));
  }
  check_version(ctx, ctx.model.asset.version, ctx.model.asset.minVersion);
  // tinygltf also looks in the working folder: a buffer must be where the file says.
  for (size_t i = 0; i < ctx.model.buffers.size(); ++i)
    check_buffer_uri(ctx, i, ctx.model.buffers[i].uri, ctx.model.buffers[i].data.size(), /*explaining=*/false);

  // Missing external images: name the URI (tinygltf only warns).
  for (size_t i = 0; i < ctx.model.images.size(); ++i) {
    const auto& img = ctx.model.images[i];
    if (img.bufferView >= 0 || img.uri.empty()) continue;
    const std::string file = resolve_uri(ctx, img.uri);
    if (const std::string why = unreadable_reason(file); !why.empty())
      ctx.fail(indexed("images", i), "image file '" + img.uri + "' " + why + " (looked for " + file + ")");
  }
  if (!warn.empty()) ctx.fail("", "tinygltf: " + trim(warn));
}

}  // namespace lumis::gltf
