// How deeply JSON text nests, found by a scan that never recurses: tinygltf converts a glTF document to its own
// values recursively, so a file nested some ten thousand levels deep (a hostile or corrupt "extras") overflows the
// stack before any error could be reported. The loader refuses such files up front.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace lumis {

/// Deepest nesting lumis reads in a glTF document; real files stay below 20.
inline constexpr size_t kMaxJsonDepth = 512;

/// The byte offset of the first '[' or '{' (outside strings) that opens level `limit` + 1, or nothing when the text
/// never nests deeper than `limit`. Syntax is not checked here: the parser does that.
std::optional<size_t> json_too_deep(std::string_view text, size_t limit = kMaxJsonDepth);

/// "line:column" (both 1-based) of a byte offset in UTF-8 text, the column in characters as an editor counts them
/// (also used for JSON syntax errors).
std::string json_line_column(std::string_view text, size_t offset);

}  // namespace lumis
