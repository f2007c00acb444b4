// glTF accessors read by hand: byteStride (interleaved views), normalized integers, sparse substitution, and bounds
// checks on every byte range, so that a malformed file is a SceneError and never an out-of-bounds read.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "app/gltf_internal.h"

namespace lumis::gltf {

namespace {

// Elements of an accessor without a bufferView (zeros, then sparse values): 2^26, 800 MB of mat4 at most.
constexpr uint64_t kMaxZeroAccessorCount = uint64_t(1) << 26;

/// Indices: any unsigned integer type, not normalized.
const ComponentTypes kIndices = {{{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, false},
                                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, false},
                                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, false}},
                                 /*quantizable=*/false};

/// The accessor's elements gathered into a tightly packed byte array (stride removed, sparse values applied).
struct Packed {
  std::vector<unsigned char> bytes;
  size_t count = 0;
  int components = 0, ctype = 0, elem_size = 0;
  bool normalized = false;
};

/// Accessor `index` after checking what its use (`where`) allows: its element type one of `types`, its component
/// type one of `components`. Nothing is read yet.
const tinygltf::Accessor& checked_accessor(const Context& ctx, int index, const std::string& where,
                                           const std::vector<int>& types, const ComponentTypes& components) {
  const auto& accessors = ctx.model.accessors;
  if (index < 0 || static_cast<size_t>(index) >= accessors.size())
    ctx.fail(where, "accessor index " + std::to_string(index) + " out of range (the file has " +
                        std::to_string(accessors.size()) + " accessors)");
  const tinygltf::Accessor& a = accessors[index];
  const std::string at = indexed("accessors", index);
  const std::string used = " (used by " + where + ")";

  bool type_ok = false;
  std::string expected;
  for (int t : types) {
    type_ok |= a.type == t;
    expected += (expected.empty() ? "" : " or ") + type_name(t);
  }
  if (!type_ok) ctx.fail(at, "type " + type_name(a.type) + ", expected " + expected + used);

  if (component_size(a.componentType) == 0)
    ctx.fail(at, "invalid componentType " + std::to_string(a.componentType) + used);
  if (a.normalized &&
      (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    ctx.fail(at + ".normalized", "normalized is not allowed for FLOAT or UNSIGNED_INT components");
  bool component_ok = false;
  expected.clear();
  for (size_t i = 0; i < components.allowed.size(); ++i) {
    const auto [ctype, normalized] = components.allowed[i];
    component_ok |= a.componentType == ctype && a.normalized == normalized;
    expected += (i == 0 ? "" : i + 1 == components.allowed.size() ? " or " : ", ") + component_name(ctype, normalized);
  }
  if (!component_ok)
    ctx.fail(at + ".componentType",
             component_name(a.componentType, a.normalized) + ", expected " + expected + used +
                 (components.quantizable ? "; other types need KHR_mesh_quantization, which lumis does not support"
                                         : ""));
  return a;
}

Packed pack_accessor(const Context& ctx, int index, const std::string& where, const std::vector<int>& types,
                     const ComponentTypes& components) {
  const tinygltf::Accessor& a = checked_accessor(ctx, index, where, types, components);
  const std::string at = indexed("accessors", index);
  const std::string used = " (used by " + where + ")";

  Packed p;
  p.components = type_components(a.type);
  p.ctype = a.componentType;
  p.normalized = a.normalized;
  const int csize = component_size(a.componentType);
  p.elem_size = csize * p.components;
  p.count = a.count;
  // Guards the size arithmetic below; no real accessor comes near 2^32 elements.
  if (a.count > (uint64_t(1) << 32)) ctx.fail(at, "count " + std::to_string(a.count) + " is too large");
  // glTF requires at least one element; an empty instancing accessor once drew its mesh once, as if not instanced.
  if (a.count < 1) ctx.fail(at + ".count", "0, expected at least 1 element" + used);
  // Without a bufferView the elements are zeros (then sparse values), as the spec says: nothing in the file bounds
  // their number, so lumis does (a hostile count would allocate without limit).
  if (a.bufferView < 0) {
    if (a.count > kMaxZeroAccessorCount)
      ctx.fail(at, "count " + std::to_string(a.count) + " without a bufferView (zeros, then sparse values) is more "
                   "than lumis reads (" + std::to_string(kMaxZeroAccessorCount) + ")" + used);
    p.bytes.assign(p.count * p.elem_size, 0);
  } else {
    const auto [data, size] = buffer_view_bytes(ctx, a.bufferView, at + ".bufferView");
    const auto& view = ctx.model.bufferViews[a.bufferView];
    const uint64_t stride = view.byteStride ? view.byteStride : p.elem_size;
    if (stride < static_cast<uint64_t>(p.elem_size))
      ctx.fail(at, "bufferViews[" + std::to_string(a.bufferView) + "].byteStride " + std::to_string(stride) +
                       " is smaller than the element size " + std::to_string(p.elem_size));
    // In subtractions that cannot wrap: a byteOffset near 2^64 made the sum small and let the copy below read
    // outside the buffer.
    const uint64_t room = a.byteOffset <= size ? size - a.byteOffset : 0;
    const uint64_t elem = static_cast<uint64_t>(p.elem_size);
    if (p.count > 0 && (a.byteOffset > size || elem > room || (p.count - 1) > (room - elem) / stride)) {
      char need[48];  // the bytes asked for, which may exceed 2^64
      std::snprintf(need, sizeof need, "%.0Lf",
                    static_cast<long double>(a.byteOffset) + static_cast<long double>(stride) * (p.count - 1) +
                        p.elem_size);
      ctx.fail(at, "byteOffset " + std::to_string(a.byteOffset) + " + " + std::to_string(p.count) +
                       " elements (stride " + std::to_string(stride) + ") need " + need +
                       " bytes, but bufferViews[" + std::to_string(a.bufferView) + "] has " +
                       std::to_string(size) + used);
    }
    // Allocated only now that the buffer view is known to hold every element.
    p.bytes.resize(p.count * p.elem_size);
    for (size_t i = 0; i < p.count; ++i)
      std::memcpy(&p.bytes[i * p.elem_size], data + a.byteOffset + i * stride, p.elem_size);
  }

  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    if (s.count < 1 || static_cast<size_t>(s.count) > p.count)
      ctx.fail(at + ".sparse.count", "sparse count " + std::to_string(s.count) + " must be in [1, " +
                                         std::to_string(p.count) + "]");
    const int isize = component_size(s.indices.componentType);
    if (s.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        s.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
        s.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || isize == 0)
      ctx.fail(at + ".sparse.indices.componentType", "expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    const auto [idata, isz] = buffer_view_bytes(ctx, s.indices.bufferView, at + ".sparse.indices.bufferView");
    const auto [vdata, vsz] = buffer_view_bytes(ctx, s.values.bufferView, at + ".sparse.values.bufferView");
    if (s.indices.byteOffset < 0 || uint64_t(s.indices.byteOffset) + uint64_t(s.count) * isize > isz)
      ctx.fail(at + ".sparse.indices", "byte range exceeds its bufferView");
    if (s.values.byteOffset < 0 || uint64_t(s.values.byteOffset) + uint64_t(s.count) * p.elem_size > vsz)
      ctx.fail(at + ".sparse.values", "byte range exceeds its bufferView");
    for (int k = 0; k < s.count; ++k) {
      const uint32_t target = decode_uint(idata + s.indices.byteOffset + size_t(k) * isize, s.indices.componentType);
      if (target >= p.count)
        ctx.fail(at + ".sparse.indices", "index " + std::to_string(target) + " >= accessor count " +
                                             std::to_string(p.count));
      std::memcpy(&p.bytes[size_t(target) * p.elem_size], vdata + s.values.byteOffset + size_t(k) * p.elem_size,
                  p.elem_size);
    }
  }
  return p;
}

}  // namespace

std::pair<const unsigned char*, size_t> buffer_view_bytes(const Context& ctx, int view, const std::string& where) {
  const auto& views = ctx.model.bufferViews;
  if (view < 0 || static_cast<size_t>(view) >= views.size())
    ctx.fail(where, "bufferView index " + std::to_string(view) + " out of range (the file has " +
                        std::to_string(views.size()) + " bufferViews)");
  const tinygltf::BufferView& v = views[view];
  const std::string at = indexed("bufferViews", view);
  if (v.buffer < 0 || static_cast<size_t>(v.buffer) >= ctx.model.buffers.size())
    ctx.fail(at + ".buffer", "buffer index " + std::to_string(v.buffer) + " out of range");
  const auto& data = ctx.model.buffers[v.buffer].data;
  if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)  // a sum could wrap
    ctx.fail(at, "byteOffset " + std::to_string(v.byteOffset) + " + byteLength " + std::to_string(v.byteLength) +
                     " exceeds buffers[" + std::to_string(v.buffer) + "] (" + std::to_string(data.size()) +
                     " bytes)");
  return {data.data() + v.byteOffset, v.byteLength};
}

const FloatData& AccessorCache::floats(int index, const std::string& where, std::vector<int> types,
                                       const ComponentTypes& components, bool finite) {
  if (auto it = floats_.find(index); it != floats_.end()) {
    // Cached under another use: the types must still be ones this caller accepts.
    checked_accessor(ctx_, index, where, types, components);
    return it->second;
  }
  const Packed p = pack_accessor(ctx_, index, where, types, components);
  FloatData out;
  out.components = p.components;
  out.values.resize(p.count * p.components);
  const int csize = p.elem_size / p.components;
  for (size_t i = 0; i < out.values.size(); ++i) {
    const float v = decode_component(&p.bytes[i * csize], p.ctype, p.normalized);
    if (finite && !std::isfinite(v))
      ctx_.fail(indexed("accessors", index), "element " + std::to_string(i / p.components) +
                                                 " is not finite (NaN or Inf; used by " + where + ")");
    out.values[i] = v;
  }
  return floats_.emplace(index, std::move(out)).first->second;
}

const std::vector<uint32_t>& AccessorCache::uints(int index, const std::string& where) {
  if (auto it = uints_.find(index); it != uints_.end()) return it->second;
  const Packed p = pack_accessor(ctx_, index, where, {TINYGLTF_TYPE_SCALAR}, kIndices);
  std::vector<uint32_t> out(p.count);
  for (size_t i = 0; i < p.count; ++i) out[i] = decode_uint(&p.bytes[i * p.elem_size], p.ctype);
  return uints_.emplace(index, std::move(out)).first->second;
}

}  // namespace lumis::gltf
