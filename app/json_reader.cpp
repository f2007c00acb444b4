// Checked access to a parsed JSON document (JsonNode): types, ranges, allowed keys with "did you mean" suggestions,
// each failure a SceneError at the value's JSON pointer. Parsing the text: app/json_parse.cpp.
#include "app/json_reader.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "app/scene_error.h"

namespace lumis {

namespace {

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

/// A value read from the file, with as many digits as it takes to read back as the same double (9 to 17): 9 digits
/// printed 0.99999999999 as 1, which the message called out of [0, 1).
std::string format_found(double v) {
  char buf[32];
  for (int digits = 9; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// A close valid name turns a typo into a one-glance fix; far names would only distract.
std::string suggestion(std::string_view found, const std::vector<std::string>& valid) {
  size_t best = std::numeric_limits<size_t>::max();
  std::string best_name;
  for (const auto& v : valid) {
    const size_t d = edit_distance(found, v);
    if (d < best) best = d, best_name = v;
  }
  if (best_name.empty() || best >= found.size() || best > std::max<size_t>(1, best_name.size() / 3)) return "";
  return " (did you mean \"" + best_name + "\"?)";
}

}  // namespace

std::string describe_json(const Json& v) {
  switch (v.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned: return "the number " + v.dump();
    case Json::value_t::number_float: return "the number " + format_found(v.get<double>());
    case Json::value_t::string: {
      std::string s = v.get<std::string>();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return "the string \"" + s + "\"";
    }
    case Json::value_t::array:
      return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " element" : " elements");
    case Json::value_t::object: return "an object";
    default: return "an unsupported value";
  }
}

std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s;
}

void JsonNode::fail(const std::string& detail) const { throw SceneError(*file_, pointer_, detail); }

void JsonNode::fail_expected(const std::string& what) const {
  fail("expected " + what + ", found " + describe_json(*value_));
}

void JsonNode::expect_object(std::initializer_list<std::string_view> allowed) const {
  if (!value_->is_object()) fail_expected("an object");
  for (const auto& [key, member] : value_->items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    const std::vector<std::string> valid(allowed.begin(), allowed.end());
    throw SceneError(*file_, pointer_ + "/" + escape_pointer_token(key),
                     "unknown key \"" + key + "\"" + suggestion(key, valid) + "; valid keys: " + join_names(valid));
  }
}

bool JsonNode::has(std::string_view key) const { return value_->is_object() && value_->contains(key); }

JsonNode JsonNode::operator[](std::string_view key) const {
  if (!value_->is_object()) fail_expected("an object");
  const auto it = value_->find(key);
  if (it == value_->end()) fail("missing required key \"" + std::string(key) + "\"");
  return {*it, pointer_ + "/" + escape_pointer_token(key), *file_};
}

std::optional<JsonNode> JsonNode::find(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return (*this)[key];
}

std::vector<JsonNode> JsonNode::elements() const {
  if (!value_->is_array()) fail_expected("an array");
  std::vector<JsonNode> out;
  for (size_t i = 0; i < value_->size(); ++i)
    out.emplace_back((*value_)[i], pointer_ + "/" + std::to_string(i), *file_);
  return out;
}

std::vector<std::pair<std::string, JsonNode>> JsonNode::members() const {
  if (!value_->is_object()) fail_expected("an object");
  std::vector<std::pair<std::string, JsonNode>> out;
  for (const auto& [key, member] : value_->items())
    out.emplace_back(key, JsonNode(member, pointer_ + "/" + escape_pointer_token(key), *file_));
  return out;
}

float JsonNode::as_float(float lo, float hi) const {
  if (!value_->is_number()) fail_expected("a number");
  const double v = value_->get<double>();
  // The parser already rejects overflowing literals; a double beyond float range would become infinite here.
  if (!std::isfinite(v) || std::abs(v) > FLT_MAX) fail_expected("a finite number within float range");
  expect_in_range(v, lo, hi);
  return static_cast<float>(v);
}

double JsonNode::as_double(double lo, double hi) const {
  if (!value_->is_number()) fail_expected("a number");
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail_expected("a finite number");
  expect_in_range(v, lo, hi);
  return v;
}

void JsonNode::expect_in_range(double v, double lo, double hi) const {
  if (v >= lo && v <= hi) return;
  if (hi == INFINITY) fail_expected("a number >= " + format_number(lo));
  if (lo == -INFINITY) fail_expected("a number <= " + format_number(hi));
  fail_expected("a number in [" + format_number(lo) + ", " + format_number(hi) + "]");
}

int64_t JsonNode::as_integer(int64_t lo, int64_t hi) const {
  const std::string range = hi == std::numeric_limits<int64_t>::max()
                                ? "an integer >= " + std::to_string(lo)
                                : "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (value_->is_number_unsigned()) {
    const uint64_t u = value_->get<uint64_t>();
    if (u > static_cast<uint64_t>(hi) || (lo > 0 && u < static_cast<uint64_t>(lo))) fail_expected(range);
    return static_cast<int64_t>(u);
  }
  int64_t v = 0;
  if (value_->is_number_integer()) {
    v = value_->get<int64_t>();
  } else if (value_->is_number_float()) {
    const double d = value_->get<double>();
    if (!(d == std::floor(d)) || std::abs(d) > 9.0e15) fail_expected(range);
    v = static_cast<int64_t>(d);
  } else {
    fail_expected(range);
  }
  if (v < lo || v > hi) fail_expected(range);
  return v;
}

bool JsonNode::as_bool() const {
  if (!value_->is_boolean()) fail_expected("true or false");
  return value_->get<bool>();
}

std::string JsonNode::as_string() const {
  if (!value_->is_string()) fail_expected("a string");
  return value_->get<std::string>();
}

Vec3 JsonNode::as_vec3(float lo, float hi) const {
  if (!value_->is_array() || value_->size() != 3) fail_expected("an array of 3 numbers");
  const auto e = elements();
  return {e[0].as_float(lo, hi), e[1].as_float(lo, hi), e[2].as_float(lo, hi)};
}

Vec2 JsonNode::as_vec2() const {
  if (!value_->is_array() || value_->size() != 2) fail_expected("an array of 2 numbers");
  const auto e = elements();
  return {e[0].as_float(), e[1].as_float()};
}

size_t JsonNode::as_choice(const std::vector<std::string>& names, std::string_view what) const {
  const std::string s = as_string();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == s) return i;
  fail("unknown " + std::string(what) + " \"" + s + "\"" + suggestion(s, names) + "; valid: " + join_names(names));
}

}  // namespace lumis
