// Small synthetic glTF files for the loader tests (test_gltf_files.cpp, test_gltf_errors.cpp): a base64 data: URI
// buffer built piece by piece, a .glb writer, a one-triangle mesh and a fixture that writes files into a fresh folder
// and checks load_gltf's errors.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>
#include <vector>

#include "app/gltf_loader.h"
#include "app/scene_error.h"
#include "tests/support/test_dir.h"

namespace lumis::gltf_test {

namespace fs = std::filesystem;

inline std::string base64(const std::vector<unsigned char>& d) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < d.size(); i += 3) {
    const uint32_t v = (d[i] << 16) | ((i + 1 < d.size() ? d[i + 1] : 0) << 8) | (i + 2 < d.size() ? d[i + 2] : 0);
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < d.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < d.size() ? k[v & 63] : '=';
  }
  return out;
}

/// A binary buffer built piece by piece (each piece 4-byte aligned), embedded as a data: URI.
struct Bin {
  std::vector<unsigned char> bytes;
  template <typename T>
  size_t add(std::initializer_list<T> values) {
    while (bytes.size() % 4) bytes.push_back(0);
    const size_t at = bytes.size();
    for (T v : values) {
      unsigned char b[sizeof(T)];
      std::memcpy(b, &v, sizeof(T));
      bytes.insert(bytes.end(), b, b + sizeof(T));
    }
    return at;
  }
  std::string buffer_json() const {
    return R"({"byteLength":)" + std::to_string(bytes.size()) +
           R"(,"uri":"data:application/octet-stream;base64,)" + base64(bytes) + "\"}";
  }
};

inline std::vector<unsigned char> file_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

/// A .glb: `json` (whose buffer 0 has no uri) and `bin` as its BIN chunk (none when empty), padded to 4 bytes.
inline std::string make_glb(std::string json, std::vector<unsigned char> bin) {
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin.push_back(0);
  auto u32 = [](size_t v) {
    const uint32_t x = static_cast<uint32_t>(v);
    return std::string(reinterpret_cast<const char*>(&x), 4);
  };
  const std::string chunk = bin.empty() ? "" : u32(bin.size()) + std::string("BIN\0", 4) +
                                                   std::string(bin.begin(), bin.end());
  return "glTF" + u32(2) + u32(12 + 8 + json.size() + chunk.size()) + u32(json.size()) + "JSON" + json + chunk;
}

class GltfFiles : public test::FolderTest {
 protected:
  GltfFiles() : FolderTest("lumis_gltf") {}

  std::string write(const std::string& name, const std::string& text) {
    const std::string p = file(name);
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  /// A one-primitive file: `accessors`, `views` and the primitive JSON given, one buffer from `bin`.
  std::string simple(const std::string& name, const Bin& bin, const std::string& views, const std::string& accessors,
                     const std::string& primitive, const std::string& node = R"({"mesh":0})",
                     const std::string& extra = "") {
    return write(name, R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)" + node +
                           R"(],"meshes":[{"primitives":[)" + primitive + R"(]}],"buffers":[)" + bin.buffer_json() +
                           R"(],"bufferViews":)" + views + R"(,"accessors":)" + accessors + extra + "}");
  }
  /// load_gltf must throw a SceneError whose message holds every one of `parts`.
  void expect_error(const std::string& path, std::initializer_list<std::string> parts) {
    try {
      load_gltf(path);
      ADD_FAILURE() << path << ": expected a SceneError";
    } catch (const SceneError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
      for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
    }
  }
};

/// One triangle (0,0,0) (1,0,0) (0,1,0) with normal +z, ushort indices: views 0 (positions), 1 (normals), 2
/// (indices); accessors 0, 1, 2 likewise.
struct Triangle {
  Bin bin;
  std::string views, accessors;
  Triangle() {
    const size_t p = bin.add<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const size_t n = bin.add<float>({0, 0, 1, 0, 0, 1, 0, 0, 1});
    const size_t i = bin.add<uint16_t>({0, 1, 2});
    views = "[" + view(p, 36) + "," + view(n, 36) + "," + view(i, 6) + "]";
    accessors = R"([{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
                R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC3"},)"
                R"({"bufferView":2,"componentType":5123,"count":3,"type":"SCALAR"}])";
  }
  static std::string view(size_t off, size_t len, size_t stride = 0) {
    return R"({"buffer":0,"byteOffset":)" + std::to_string(off) + R"(,"byteLength":)" + std::to_string(len) +
           (stride ? R"(,"byteStride":)" + std::to_string(stride) : "") + "}";
  }
  static constexpr const char* prim = R"({"attributes":{"POSITION":0,"NORMAL":1},"indices":2})";
};

}  // namespace lumis::gltf_test
