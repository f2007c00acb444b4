// Checked access to a parsed JSON document: every failure becomes a SceneError naming the file and the JSON pointer
// of the offending value, saying what was expected and what was found.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/math.h"

namespace lumis {

// Ordered, so that members come (and the first error is found) in document order.
using Json = nlohmann::ordered_json;

/// Parse JSON text. Syntax errors report "line:column" as the location; duplicate keys are errors too (their
/// location is the JSON pointer of the second occurrence).
Json parse_json_text(const std::string& text, const std::string& file);

/// nlohmann's syntax-error message in lumis's words ("syntax error while parsing value - ..."): its prefix and
/// position dropped (the caller gives line:column), bytes that are not printable UTF-8 written as \xNN.
std::string json_syntax_detail(std::string nlohmann_message);

/// A key as one token of a JSON pointer (RFC 6901: "~" becomes "~0", "/" becomes "~1").
std::string escape_pointer_token(std::string_view key);

/// "the string "abc"", "the number 3", "an array of 2 elements", ... for messages.
std::string describe_json(const Json& value);

/// "a, b or c" from a list of names.
std::string join_names(const std::vector<std::string>& names);

/// A value inside the document together with its JSON pointer. Cheap to copy; refers into the document.
class JsonNode {
 public:
  JsonNode(const Json& value, std::string pointer, const std::string& file)
      : value_(&value), pointer_(std::move(pointer)), file_(&file) {}

  const Json& value() const { return *value_; }
  const std::string& pointer() const { return pointer_; }
  const std::string& file() const { return *file_; }

  /// Throw a SceneError at this node.
  [[noreturn]] void fail(const std::string& detail) const;
  /// Throw "expected <what>, found <description of this value>".
  [[noreturn]] void fail_expected(const std::string& what) const;
  /// fail_expected with the range's wording unless lo <= v <= hi (an infinite bound is left out).
  void expect_in_range(double v, double lo, double hi) const;

  /// Require an object whose keys all lie in `allowed` (an unknown key is an error at its own pointer).
  void expect_object(std::initializer_list<std::string_view> allowed) const;
  bool has(std::string_view key) const;
  /// A required member: missing is an error at this object's pointer.
  JsonNode operator[](std::string_view key) const;
  /// An optional member.
  std::optional<JsonNode> find(std::string_view key) const;
  /// Require an array; its elements in order.
  std::vector<JsonNode> elements() const;
  /// Require an object; its members in document order.
  std::vector<std::pair<std::string, JsonNode>> members() const;

  /// Finite number (as float). The range is inclusive; messages quote it.
  float as_float(float lo = -INFINITY, float hi = INFINITY) const;
  /// Finite number kept in double (a duration: 0.05 as a float is 0.0500000007). The range is inclusive.
  double as_double(double lo, double hi) const;
  /// Integer in [lo, hi] (a number with a fractional part is an error).
  int64_t as_integer(int64_t lo, int64_t hi) const;
  bool as_bool() const;
  std::string as_string() const;
  /// Array of 3 finite numbers, each in [lo, hi].
  Vec3 as_vec3(float lo = -INFINITY, float hi = INFINITY) const;
  /// Array of 2 finite numbers.
  Vec2 as_vec2() const;
  /// A string that must be one of `names`; returns its index.
  size_t as_choice(const std::vector<std::string>& names, std::string_view what) const;

 private:
  const Json* value_;
  std::string pointer_;
  const std::string* file_;
};

}  // namespace lumis
