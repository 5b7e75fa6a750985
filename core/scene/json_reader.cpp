// SPDX-License-Identifier: MIT
// The scene file's JSON reader: a SAX handler that builds the DOM, rejecting duplicate keys and
// deep nesting, and turns nlohmann's parse errors into one-line messages.
#include "core/scene/json_reader.hpp"

#include <algorithm>
#include <cstddef>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "elan/scene.hpp"

namespace elan::detail::scene_file {
namespace {

// Scene files are a few levels deep; a cap keeps pathological nesting from costing stack later.
constexpr std::size_t kMaxDepth = 64;

// Builds the DOM like nlohmann's own parser, but also rejects duplicate keys (which nlohmann
// would silently overwrite) and keeps the byte position of any error, overflow included.
class SceneSax {
 public:
  Json root;
  std::string error;  // empty when the text parsed
  std::size_t error_position = 0;

  bool null() { return put(Json(nullptr)); }
  bool boolean(bool v) { return put(Json(v)); }
  bool number_integer(Json::number_integer_t v) { return put(Json(v)); }
  bool number_unsigned(Json::number_unsigned_t v) { return put(Json(v)); }
  bool number_float(Json::number_float_t v, const std::string&) { return put(Json(v)); }
  bool string(std::string& v) { return put(Json(std::move(v))); }
  bool binary(Json::binary_t& v) { return put(Json::binary(std::move(v))); }
  bool start_object(std::size_t) { return open(Json::object()); }
  bool start_array(std::size_t) { return open(Json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(std::string& k) {
    Frame& top = stack_.back();
    if (!top.keys.insert(k).second) {
      error = path() + (stack_.size() > 1 ? "." : "") + k + ": duplicate key";
      return false;
    }
    member_ = &(*top.value)[k];
    top.member = k;
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) {
    error_position = position;
    // nlohmann's text is "[json.exception.parse_error.101] parse error at line 1, column 5: ..."
    std::string what = e.what();
    const std::size_t bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    const std::size_t column = what.find("column ");
    const std::size_t colon = column == std::string::npos ? column : what.find(": ", column);
    if (colon != std::string::npos) what = what.substr(colon + 2);
    std::string at = path();
    const std::string next = next_name();
    if (!next.empty()) at += (at.empty() || next[0] == '[' ? "" : ".") + next;
    error = "malformed JSON" + (at.empty() ? "" : " at " + at) + ": " + what;
    return false;
  }

 private:
  struct Frame {
    Json* value;
    std::string name;  // key or [index] that leads to this container, for messages
    std::set<std::string> keys;
    std::string member;  // the key being read, in an object
  };
  std::vector<Frame> stack_;
  Json* member_ = nullptr;

  std::string next_name() const {
    if (stack_.empty()) return "";
    const Json& top = *stack_.back().value;
    if (!top.is_array()) return stack_.back().member;
    // Appended piece by piece: GCC 12 reports a false -Wrestrict for "[" + std::to_string(n)
    // once this is inlined (GCC bug 105329).
    std::string index = "[";
    index += std::to_string(top.size());
    index += ']';
    return index;
  }
  Json* place(Json&& v) {
    if (stack_.empty()) {
      root = std::move(v);
      return &root;
    }
    // Pointers to open containers stay valid: an open container is the last element of its
    // parent array (which grows only after it closes) or a std::map node.
    Json& top = *stack_.back().value;
    if (top.is_array()) {
      top.push_back(std::move(v));
      return &top.back();
    }
    *member_ = std::move(v);
    return member_;
  }
  bool put(Json&& v) {
    place(std::move(v));
    return true;
  }
  bool open(Json&& v) {
    if (stack_.size() >= kMaxDepth) {
      error = path() + ": nesting deeper than " + std::to_string(kMaxDepth) + " levels";
      return false;
    }
    std::string name = next_name();
    stack_.push_back(Frame{place(std::move(v)), std::move(name), {}, {}});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }
  std::string path() const {
    std::string p;
    for (std::size_t i = 1; i < stack_.size(); ++i) {
      const std::string& n = stack_[i].name;
      if (!p.empty() && n[0] != '[') p += '.';
      p += n;
    }
    return p;
  }
};

}  // namespace

std::string kind(const Json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
}

Json parse_json(const std::string& text, const std::string& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw SceneError(file + ": empty file (expected a JSON object)");
  }
  SceneSax sax;
  const bool ok = Json::sax_parse(text, &sax, Json::input_format_t::json, true, false);
  if (!ok || !sax.error.empty()) {
    if (sax.error.rfind("malformed", 0) == 0) {
      std::size_t line = 1, column = 1;
      const std::size_t end = std::min(sax.error_position, text.size());
      for (std::size_t i = 0; i + 1 < end; ++i) {
        if (text[i] == '\n') {
          ++line;
          column = 1;
        } else {
          ++column;
        }
      }
      throw SceneError(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
                       sax.error);
    }
    // "bodies[3].shape.radius: ..." reads as the other messages do: "body 3: shape.radius: ...".
    std::string error = sax.error;
    if (error.rfind("bodies[", 0) == 0 && error.find("]") != std::string::npos) {
      const std::size_t close = error.find(']');
      std::string rest = error.substr(close + 1);
      if (!rest.empty() && rest[0] == '.') rest = rest.substr(1);
      error = "body " + error.substr(7, close - 7) + ": " + rest;
    }
    throw SceneError(file + ": " + error);
  }
  if (!sax.root.is_object()) {
    throw SceneError(file + ": expected a JSON object at the top level, got " + kind(sax.root));
  }
  return std::move(sax.root);
}

}  // namespace elan::detail::scene_file
