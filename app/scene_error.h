// The one error type for bad scene input. Printed by main as "file:location: message".
#pragma once

#include <stdexcept>
#include <string>

namespace lumis {

struct SceneError : std::runtime_error {
  std::string file;      ///< the file at fault
  std::string location;  ///< JSON pointer ("/shapes/2/radius"), glTF path ("meshes[3].primitives[0]"), or line:col
  std::string detail;    ///< what was wrong and what was expected
  SceneError(std::string file_, std::string location_, std::string detail_)
      : std::runtime_error(format(file_, location_, detail_)), file(std::move(file_)),
        location(std::move(location_)), detail(std::move(detail_)) {}
  static std::string format(const std::string& f, const std::string& loc, const std::string& d) {
    std::string s = f;
    if (!loc.empty()) s += ":" + loc;
    return s + ": " + d;
  }
};

}  // namespace lumis
