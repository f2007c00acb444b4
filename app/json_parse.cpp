// JSON text to a document: nlohmann's SAX parser, with byte positions for syntax errors turned into line:column
// and duplicate keys rejected (nlohmann's parse() keeps the last silently).
#include <cstdio>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "app/json_depth.h"
#include "app/json_reader.h"
#include "app/scene_error.h"

namespace lumis {

std::string escape_pointer_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

namespace {

// Builds the document through nlohmann's SAX interface, which (unlike parse()) reports the byte position of
// every error, overflowing numbers included, and lets us reject duplicate keys that parse() silently merges.
class DomBuilder : public nlohmann::json_sax<Json> {
 public:
  Json root;
  size_t error_byte = 0;           // 1-based position of the last character read, for syntax errors
  std::string error_message;       // nlohmann's message for syntax errors
  std::string duplicate_pointer;   // set when a key repeats within one object

  bool null() override { return place(Json(nullptr)); }
  bool boolean(bool v) override { return place(Json(v)); }
  bool number_integer(number_integer_t v) override { return place(Json(v)); }
  bool number_unsigned(number_unsigned_t v) override { return place(Json(v)); }
  bool number_float(number_float_t v, const string_t&) override { return place(Json(v)); }
  bool string(string_t& v) override { return place(Json(std::move(v))); }
  bool binary(binary_t&) override { return place(Json(nullptr)); }  // text JSON has no binary values
  bool start_object(std::size_t) override { return open(Json::object()); }
  bool start_array(std::size_t) override { return open(Json::array()); }
  bool end_object() override { stack_.pop_back(); return true; }
  bool end_array() override { stack_.pop_back(); return true; }
  bool key(string_t& k) override {
    Frame& f = stack_.back();
    // A set beside the object: ordered_json's own lookup is a linear scan, which made 160,000 material names take
    // 47 s to parse.
    if (!f.keys.insert(k).second) {
      duplicate_pointer = pointer() + "/" + escape_pointer_token(k);
      return false;
    }
    f.key = k;
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::json::exception& ex) override {
    error_byte = position;
    error_message = ex.what();
    return false;
  }

 private:
  struct Frame {
    Json* value;
    std::string token;  // how the parent reaches this container
    std::string key;    // the object's current key
    std::unordered_set<std::string> keys;  // the object's keys so far
  };
  std::vector<Frame> stack_;
  std::string last_token_;

  std::string pointer() const {
    std::string p;
    for (size_t i = 1; i < stack_.size(); ++i) p += "/" + stack_[i].token;
    return p;
  }
  Json* insert(Json v) {
    if (stack_.empty()) {
      root = std::move(v);
      return &root;
    }
    Frame& f = stack_.back();
    if (f.value->is_array()) {
      last_token_ = std::to_string(f.value->size());
      f.value->push_back(std::move(v));
      return &f.value->back();
    }
    last_token_ = escape_pointer_token(f.key);
    // Appended without a search (ordered_json's operator[] scans): key() has already rejected a repeated key.
    auto& members = f.value->get_ref<Json::object_t&>();
    members.emplace_back(std::move(f.key), std::move(v));
    return &members.back().second;
  }
  bool place(Json v) {
    insert(std::move(v));
    return true;
  }
  // Containers on the stack stay put: a parent only grows after its open child is closed.
  bool open(Json v) {
    Json* p = insert(std::move(v));
    stack_.push_back({p, stack_.empty() ? "" : last_token_, ""});
    return true;
  }
};

}  // namespace

// "[json.exception.parse_error.101] parse error at line 3, column 7: syntax error ..." -> "syntax error ...", with
// what nlohmann quotes ("last read: '...'") made printable: the raw bytes of ill-formed UTF-8 or control characters
// would garble the terminal.
std::string json_syntax_detail(std::string m) {
  if (m.rfind("[json.exception.", 0) == 0) {
    const size_t close = m.find("] ");
    if (close != std::string::npos) m = m.substr(close + 2);
  }
  if (m.rfind("parse error", 0) == 0) {
    const size_t colon = m.find(": ");
    if (colon != std::string::npos) m = m.substr(colon + 2);
  }
  if (m.rfind("number overflow", 0) == 0) m += " (numbers must be finite)";
  std::string out;
  for (size_t i = 0; i < m.size(); ++i) {
    const auto c = static_cast<unsigned char>(m[i]);
    // A well-formed UTF-8 sequence is kept whole: its lead byte's count of continuation bytes follows it.
    const size_t more = c >= 0xc2 && c <= 0xdf ? 1 : c >= 0xe0 && c <= 0xef ? 2 : c >= 0xf0 && c <= 0xf4 ? 3 : 0;
    size_t k = 0;
    while (more && k < more && i + 1 + k < m.size() && (static_cast<unsigned char>(m[i + 1 + k]) & 0xc0) == 0x80) ++k;
    if (more && k == more) {
      out.append(m, i, 1 + more);
      i += more;
    } else if (c >= 0x20 && c < 0x7f) {
      out += m[i];
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  return out;
}

Json parse_json_text(const std::string& text, const std::string& file) {
  DomBuilder builder;
  if (Json::sax_parse(text, &builder)) return std::move(builder.root);
  if (!builder.duplicate_pointer.empty())
    throw SceneError(file, builder.duplicate_pointer, "duplicate key (each key may appear once per object)");
  // nlohmann reports a 1-based count of characters read.
  throw SceneError(file, json_line_column(text, builder.error_byte == 0 ? 0 : builder.error_byte - 1),
                   "invalid JSON: " + json_syntax_detail(builder.error_message));
}

}  // namespace lumis
