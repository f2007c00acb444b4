// File names: extensions compared without regard to case (scene files, output images, the bench's .glb), and
// whether an output file can be written where it is asked for.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/atomic_write.h"

namespace lumis {

/// The extension of path, dot included, in lower case ("out/Room.GLB" -> ".glb"; "" when there is none).
inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// Why an output file could not be created at path, checked before any work is done: the path is a folder, its
/// folder does not exist or is not a folder, or the folder is not writable. Empty when none of these holds (the
/// write can still fail later, e.g. on a full disk). The message starts with what is wrong, for "lumis: PATH: ".
inline std::string output_file_problem(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty()) return "empty output file name";
  if (fs::is_directory(path, ec))
    return "is a folder; give an image file name, e.g. " + (fs::path(path) / "out.png").string();
  // A symbolic link is written through (core/atomic_write.h): its target's folder is the one that must be writable.
  bool loop = false;
  const std::string file = written_file(path, &loop);
  if (loop) return "is a loop of symbolic links";
  const std::string via = file == path ? "" : "links to " + file + ", but ";
  const fs::path parent = fs::path(file).parent_path();
  const std::string folder = parent.empty() ? "." : parent.string();
  if (!fs::exists(folder, ec)) return via + "the folder " + folder + " does not exist";
  if (!fs::is_directory(folder, ec)) return via + folder + " is not a folder";
  if (::access(folder.c_str(), W_OK) != 0)
    return via + "cannot write in the folder " + folder + " (" + std::strerror(errno) + ")";
  return "";
}

}  // namespace lumis
