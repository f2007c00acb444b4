// glTF accessors' component and element types: their sizes, names for messages, and decoding one component.
#include <algorithm>
#include <cstring>

#include "app/gltf_internal.h"

namespace lumis::gltf {

int component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // DOUBLE and INT are not glTF 2.0 accessor types
  }
}

int type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

std::string type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown type " + std::to_string(type);
  }
}

std::string component_name(int ctype, bool normalized) {
  const std::string prefix = normalized ? "normalized " : "";
  switch (ctype) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return prefix + "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return prefix + "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return prefix + "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return prefix + "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return prefix + "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return prefix + "FLOAT";
    default: return std::to_string(ctype);
  }
}

namespace {

// The bytes at `p` as a T (unaligned, host byte order: little-endian, as glTF's buffers are).
template <class T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

float decode_component(const unsigned char* p, int ctype, bool normalized) {
  switch (ctype) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const int8_t v = load<int8_t>(p);
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const uint8_t v = p[0];
      return normalized ? v / 255.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const int16_t v = load<int16_t>(p);
      return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const uint16_t v = load<uint16_t>(p);
      return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return static_cast<float>(load<uint32_t>(p));
    default: return load<float>(p);
  }
}

uint32_t decode_uint(const unsigned char* p, int ctype) {
  switch (ctype) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<uint16_t>(p);
    default: return load<uint32_t>(p);
  }
}

}  // namespace lumis::gltf
