// SPDX-License-Identifier: MIT
// A scene's text with its OBJ files written into it, for recordings: a recording keeps the scene
// text alone, and a replay elsewhere (another directory, another machine) must find the same
// geometry without the files.
#pragma once

#include <string>

namespace elan::detail::scene_file {

// `text` (the scene file `file_name`, already accepted by parse_scene) with every shape's `file`
// replaced by what parse_scene reads from it: a mesh's `vertices` and fanned `triangles`, a
// hull's `points`, each coordinate the Real the parser made of it, so the text parses to the same
// shapes bit for bit. A scene without files is returned unchanged, byte for byte. Throws
// SceneError as parse_scene does (a file that changed or vanished since).
std::string self_contained(const std::string& text, const std::string& file_name);

}  // namespace elan::detail::scene_file
