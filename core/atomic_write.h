// Files written whole or not at all: every file lumis writes (images, reports, the bench's scene) goes through here,
// so a full disk, a file-size limit or an interruption never leaves a half-written file under the name asked for.
#pragma once

#include <string>
#include <string_view>

namespace lumis {

/// Writes `bytes` to `path` through a temporary file beside it (`path.tmp-<pid>`, a long name cut short to fit the
/// file system's limit): every byte written and the file closed, each step checked, then renamed over `path` (over
/// the file it links to, when `path` is a symbolic link: the link stays). So `path` keeps what it held before or
/// holds all of `bytes`, never a part. Returns "" on success; otherwise the reason, one line without the temporary
/// name ("cannot write: No space left on device (after 204800 of 615084 bytes)"), with the temporary file removed. A
/// folder, pipe, device or socket at `path` is not replaced (an error, before anything is written); a file replaced
/// keeps its permissions; a signal that ends the process mid-write (SIGINT, SIGTERM, SIGHUP, SIGQUIT, where left at
/// their default) removes the temporary file first.
std::string write_file_atomically(const std::string& path, std::string_view bytes);

/// The temporary name write_file_atomically uses beside `path`: `path.tmp-<pid>`, or, past the longest name the
/// folder's file system allows, the name cut short (at a UTF-8 character's start) with a count to keep it unique.
std::string temporary_name(const std::string& path);

/// The file a write to `path` replaces: `path` itself, or the file its chain of symbolic links leads to (a relative
/// link read from the link's own folder). *loop (when given) is set for a loop of links (40 hops).
std::string written_file(const std::string& path, bool* loop = nullptr);

}  // namespace lumis
