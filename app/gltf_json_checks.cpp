// Checks of a glTF file's JSON text for what tinygltf 2.7 lets through silently. It ignores an optional field of the
// wrong type ("mesh": "0", "mode": "1", "metallicFactor": "0", an index written 1.0) and keeps its default, stops an
// array at its first wrong element ("children": [1, "2"] keeps 1), truncates an index beyond int's range, reads a
// negative byte offset as 0, and keeps a node's matrix when translation/rotation/scale are there too. Each such field
// is an error naming its glTF path here, as are a few that tinygltf refuses without naming where (a factor's length,
// an accessor's type, a perspective camera's missing yfov).
#include <climits>
#include <cmath>
#include <string>
#include <vector>

#include "app/gltf_internal.h"

namespace lumis::gltf {

namespace {

/// What a field holds; the arrays and maps hold Index, Number or String elements.
enum class Want { Index, Count, Int, Number, Positive, Bool, String, Numbers, Indices, Strings, IndexMap, Object,
                  Objects };

struct Field {
  const char* name;
  Want want;
  const std::vector<Field>* inner = nullptr;  ///< Object, Objects: the fields checked in the object(s)
  size_t length = 0;  ///< Numbers: how many the array holds (0: any number, or checked where it is read)
};
using Fields = std::vector<Field>;

// The fields lumis reads, as glTF 2.0's schema types them (zfar, minFilter, occlusion, skins, animations: not read).
const Fields kTextureInfo = {{"index", Want::Index}, {"texCoord", Want::Index}};
const Fields kNormalTextureInfo = {{"index", Want::Index}, {"texCoord", Want::Index}, {"scale", Want::Number}};
const Fields kPbr = {{"baseColorFactor", Want::Numbers, nullptr, 4},          {"metallicFactor", Want::Number},
                     {"roughnessFactor", Want::Number},           {"baseColorTexture", Want::Object, &kTextureInfo},
                     {"metallicRoughnessTexture", Want::Object, &kTextureInfo}};
const Fields kMaterial = {{"name", Want::String},          {"pbrMetallicRoughness", Want::Object, &kPbr},
                          {"normalTexture", Want::Object, &kNormalTextureInfo},
                          {"emissiveTexture", Want::Object, &kTextureInfo},
                          {"emissiveFactor", Want::Numbers, nullptr, 3}, {"alphaMode", Want::String},
                          {"alphaCutoff", Want::Number},     {"doubleSided", Want::Bool}};
const Fields kPrimitive = {{"attributes", Want::IndexMap}, {"indices", Want::Index}, {"material", Want::Index},
                           {"mode", Want::Int}};
const Fields kMesh = {{"primitives", Want::Objects, &kPrimitive}};
const Fields kNode = {{"name", Want::String},       {"camera", Want::Index},      {"mesh", Want::Index},
                      {"children", Want::Indices}, {"matrix", Want::Numbers},    {"translation", Want::Numbers},
                      {"rotation", Want::Numbers}, {"scale", Want::Numbers}};  // their lengths: gltf_nodes.cpp
const Fields kScene = {{"nodes", Want::Indices}};
const Fields kSparsePart = {{"bufferView", Want::Index}, {"byteOffset", Want::Count}, {"componentType", Want::Int}};
const Fields kSparse = {{"count", Want::Count}, {"indices", Want::Object, &kSparsePart},
                        {"values", Want::Object, &kSparsePart}};
const Fields kAccessor = {{"bufferView", Want::Index}, {"byteOffset", Want::Count}, {"componentType", Want::Int},
                          {"normalized", Want::Bool},  {"count", Want::Count},      {"type", Want::String},
                          {"sparse", Want::Object, &kSparse}};
const Fields kBufferView = {{"buffer", Want::Index}, {"byteOffset", Want::Count}, {"byteLength", Want::Count},
                            {"byteStride", Want::Count}};
const Fields kBuffer = {{"uri", Want::String}, {"byteLength", Want::Count}};
const Fields kImage = {{"uri", Want::String}, {"mimeType", Want::String}, {"bufferView", Want::Index}};
const Fields kTexture = {{"sampler", Want::Index}, {"source", Want::Index}};
const Fields kSampler = {{"magFilter", Want::Int}, {"wrapS", Want::Int}, {"wrapT", Want::Int}};
const Fields kPerspective = {{"aspectRatio", Want::Positive}, {"yfov", Want::Number}, {"znear", Want::Number}};
const Fields kCamera = {{"name", Want::String}, {"type", Want::String}, {"perspective", Want::Object, &kPerspective}};
const Fields kRoot = {{"scene", Want::Index},
                      {"scenes", Want::Objects, &kScene},
                      {"nodes", Want::Objects, &kNode},
                      {"meshes", Want::Objects, &kMesh},
                      {"materials", Want::Objects, &kMaterial},
                      {"accessors", Want::Objects, &kAccessor},
                      {"bufferViews", Want::Objects, &kBufferView},
                      {"buffers", Want::Objects, &kBuffer},
                      {"images", Want::Objects, &kImage},
                      {"textures", Want::Objects, &kTexture},
                      {"samplers", Want::Objects, &kSampler},
                      {"cameras", Want::Objects, &kCamera},
                      {"extensionsUsed", Want::Strings},
                      {"extensionsRequired", Want::Strings}};

const char* expectation(Want want) {
  switch (want) {
    case Want::Index: return "an index (a whole number >= 0)";
    case Want::Count: return "a whole number >= 0";
    case Want::Int: return "a whole number";
    case Want::Number: return "a number";
    case Want::Positive: return "a number > 0";
    case Want::Bool: return "true or false";
    case Want::String: return "a string";
    case Want::Numbers: return "an array of numbers";
    case Want::Indices: return "an array of indices";
    case Want::Strings: return "an array of strings";
    case Want::IndexMap: return "an object of indices";
    case Want::Object: return "an object";
    case Want::Objects: return "an array of objects";
  }
  return "";
}

/// Whether a scalar value is what `want` asks for, as tinygltf would read it (its indices are ints).
bool holds(const Json& v, Want want) {
  switch (want) {
    case Want::Index: return v.is_number_unsigned() && v.get<uint64_t>() <= uint64_t(INT_MAX);
    case Want::Count: return v.is_number_unsigned();
    case Want::Int:
      return v.is_number_unsigned() ? v.get<uint64_t>() <= uint64_t(INT_MAX)
                                    : v.is_number_integer() && v.get<int64_t>() >= INT_MIN;
    case Want::Number: return v.is_number();
    case Want::Positive: return v.is_number() && v.get<double>() > 0;
    case Want::Bool: return v.is_boolean();
    case Want::String: return v.is_string();
    default: return false;
  }
}

[[noreturn]] void refuse(const Context& ctx, const Json& v, Want want, const std::string& at) {
  std::string what = std::string("expected ") + expectation(want);
  const bool whole = want == Want::Index || want == Want::Count || want == Want::Int;
  if (whole && v.is_number_float() && std::floor(v.get<double>()) == v.get<double>())
    ctx.fail(at, what + " written without a decimal point or exponent, found " + v.dump());
  if (v.is_number_integer() && (want == Want::Int || (want == Want::Index && v.is_number_unsigned())))
    what += want == Want::Int ? " in int's range" : " no greater than 2147483647";  // tinygltf would truncate it
  ctx.fail(at, what + ", found " + describe_json(v));
}

void check_fields(const Context& ctx, const Json& object, const Fields& fields, const std::string& at);

void check_value(const Context& ctx, const Json& v, const Field& f, const std::string& at) {
  const auto each = [&](Want element) {
    if (!(f.want == Want::IndexMap ? v.is_object() : v.is_array())) refuse(ctx, v, f.want, at);
    size_t i = 0;
    for (auto it = v.begin(); it != v.end(); ++it, ++i)
      if (!holds(*it, element)) refuse(ctx, *it, element, v.is_object() ? at + "." + it.key() : indexed(at, i));
  };
  switch (f.want) {
    case Want::Numbers:
      each(Want::Number);
      if (f.length && v.size() != f.length)  // tinygltf's message would name no place
        ctx.fail(at, "expected an array of " + std::to_string(f.length) + " numbers, found " +
                         std::to_string(v.size()));
      return;
    case Want::Indices: return each(Want::Index);
    case Want::Strings: return each(Want::String);
    case Want::IndexMap: return each(Want::Index);
    case Want::Object:
      if (!v.is_object()) refuse(ctx, v, f.want, at);
      return check_fields(ctx, v, *f.inner, at);
    case Want::Objects:
      if (!v.is_array()) refuse(ctx, v, f.want, at);
      for (size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_object()) refuse(ctx, v[i], Want::Object, indexed(at, i));
        check_fields(ctx, v[i], *f.inner, indexed(at, i));
      }
      return;
    default:
      if (!holds(v, f.want)) refuse(ctx, v, f.want, at);
  }
}

void check_fields(const Context& ctx, const Json& object, const Fields& fields, const std::string& at) {
  for (const Field& f : fields)
    if (const auto it = object.find(f.name); it != object.end())
      check_value(ctx, *it, f, at.empty() ? f.name : at + "." + f.name);
}

}  // namespace

void check_json(const Context& ctx, const Json& doc) {
  if (!doc.is_object()) return;  // tinygltf reports it
  // glTF 1.0's fields differ ("scene": "name"): its version is what to report, once tinygltf has read the file.
  if (const auto asset = doc.find("asset"); asset != doc.end() && asset->is_object())
    if (const auto v = asset->find("version"); v != asset->end() && v->is_string())
      if (v->get<std::string>().rfind("2.", 0) != 0) return;
  check_fields(ctx, doc, kRoot, "");
  const auto nodes = doc.find("nodes");  // an array of objects, if there, once check_fields has passed
  for (size_t i = 0; nodes != doc.end() && i < nodes->size(); ++i) {
    const Json& n = (*nodes)[i];
    if (n.contains("matrix") && (n.contains("translation") || n.contains("rotation") || n.contains("scale")))
      ctx.fail(indexed("nodes", i), "has both \"matrix\" and translation/rotation/scale; glTF allows one or the "
                                    "other (lumis's reader would use the matrix alone)");
  }
  // What tinygltf refuses without naming where: an accessor's type, a perspective camera without its field of view
  // (which it calls an OrthographicCamera's).
  const auto accessors = doc.find("accessors");
  for (size_t i = 0; accessors != doc.end() && i < accessors->size(); ++i)
    if (const auto t = (*accessors)[i].find("type"); t != (*accessors)[i].end())
      if (const std::string s = *t; s != "SCALAR" && s != "VEC2" && s != "VEC3" && s != "VEC4" && s != "MAT2" &&
                                    s != "MAT3" && s != "MAT4")
        ctx.fail(indexed("accessors", i) + ".type",
                 "expected SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4, found " + describe_json(*t));
  const auto cameras = doc.find("cameras");
  for (size_t i = 0; cameras != doc.end() && i < cameras->size(); ++i) {
    const Json& c = (*cameras)[i];
    if (c.value("type", Json()) == "perspective" && c.contains("perspective") && !c["perspective"].contains("yfov"))
      ctx.fail(indexed("cameras", i) + ".perspective",
               "has no yfov; a perspective camera needs its vertical field of view, in radians");
  }
}

}  // namespace lumis::gltf
