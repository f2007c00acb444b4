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

/// Why path's extension names no image format lumis writes (.exr, .png, .jpg/.jpeg, .hdr, in any case); empty when
/// it names one. A name that is only an extension (".png") has none: it is a hidden file's name.
inline std::string output_format_problem(const std::string& path) {
  const auto is_format = [](const std::string& e) {
    return e == ".exr" || e == ".png" || e == ".jpg" || e == ".jpeg" || e == ".hdr";
  };
  const std::string ext = lower_extension(path);
  if (is_format(ext)) return "";
  const std::string formats = "use .exr, .png, .jpg/.jpeg or .hdr";
  if (!ext.empty()) return "unsupported image format '" + ext + "' (" + formats + ")";
  const std::string name = std::filesystem::path(path).filename().string();
  if (is_format(lower_extension("x" + name)))  // ".png": the name before the extension is missing
    return "'" + name + "' is a name without an extension (it starts with the dot); give a name before it, such as "
           "out" + name;
  return "no extension to tell the image format by (" + formats + ")";
}

/// Why an output file could not be created at path, checked before any work is done: the path is a folder, or
/// something other than a regular file (a pipe, device or socket, which the write's rename would replace with a
/// file), its folder does not exist or is not a folder, the folder is not writable, or the name is longer than the
/// folder's file system allows (255 bytes on Linux's). Empty when none of these holds
/// (the write can still fail later, e.g. on a full disk). The message starts with what is wrong, for
/// "lumis: PATH: "; a folder's names `example` ("out.png") as the file to give instead.
inline std::string output_file_problem(const std::string& path, const std::string& example = "out.png") {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty()) return "empty output file name";
  if (fs::is_directory(path, ec))
    return "is a folder; give a file name, e.g. " + (fs::path(path) / example).string();
  // A symbolic link is written through (core/atomic_write.h): its target's folder is the one that must be writable.
  bool loop = false;
  const std::string file = written_file(path, &loop);
  if (loop) return "is a loop of symbolic links";
  const std::string via = file == path ? "" : "links to " + file + ", but ";
  if (const fs::file_status st = fs::symlink_status(file, ec); fs::exists(st) && !fs::is_regular_file(st))
    return via + (via.empty() ? "is" : "it is") +
           " not a regular file (a pipe, device or socket): lumis writes a whole file and renames it into place, "
           "which would replace it";
  const fs::path parent = fs::path(file).parent_path();
  const std::string folder = parent.empty() ? "." : parent.string();
  if (!fs::exists(folder, ec)) return via + "the folder " + folder + " does not exist";
  if (!fs::is_directory(folder, ec)) return via + folder + " is not a folder";
  if (::access(folder.c_str(), W_OK) != 0)
    return via + "cannot write in the folder " + folder + " (" + std::strerror(errno) + ")";
  // Too long a name or path would fail only when written, after the work (the temporary name beside it is written
  // first: `path.tmp-<pid>`, up to 24 bytes more, must fit in the 4096 bytes Linux takes).
  if (file.size() + 24 >= 4096)
    return via + "the path is " + std::to_string(file.size()) + " bytes long; lumis writes at most 4071 (the system "
           "takes 4095, and the file is first written under a temporary name 24 bytes longer)";
  const std::string name = fs::path(file).filename().string();
  if (const long limit = ::pathconf(folder.c_str(), _PC_NAME_MAX); limit > 0 && name.size() > size_t(limit))
    return via + "the file name is " + std::to_string(name.size()) + " bytes long, more than the " +
           std::to_string(limit) + " its folder's file system allows";
  return "";
}

/// output_file_problem, then output_format_problem: why an image cannot be written at path (empty when it can).
inline std::string image_output_problem(const std::string& path, const std::string& example = "out.png") {
  const std::string problem = output_file_problem(path, example);
  return problem.empty() ? output_format_problem(path) : problem;
}

}  // namespace lumis
