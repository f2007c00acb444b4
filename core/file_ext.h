// File-name extensions, compared without regard to case (scene files, output images, the bench's .glb).
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace lumis {

/// The extension of path, dot included, in lower case ("out/Room.GLB" -> ".glb"; "" when there is none).
inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace lumis
