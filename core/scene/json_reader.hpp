// SPDX-License-Identifier: MIT
// The scene file's JSON reader: nlohmann-json's parser made strict (duplicate keys and deep
// nesting are errors) and its messages made to name the file, line, column and key path.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace elan::detail::scene_file {

using Json = nlohmann::json;

// Parses `text` as one JSON object. Throws SceneError naming `file`, and for malformed text the
// line and column.
Json parse_json(const std::string& text, const std::string& file);

// The kind of a JSON value for messages: "null", "a boolean", "a number", ... "an object".
std::string kind(const Json& j);

}  // namespace elan::detail::scene_file
