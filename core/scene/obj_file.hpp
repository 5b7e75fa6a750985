// SPDX-License-Identifier: MIT
// Wavefront OBJ files for scene shapes: the vertices, and the faces fanned into triangles.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "elan/math.hpp"

namespace elan::detail::scene_file {

// An OBJ file could not be read or is malformed. what() is one line naming the path.
class ObjError : public std::runtime_error {
 public:
  explicit ObjError(const std::string& message) : std::runtime_error(message) {}
};

struct ObjGeometry {
  std::vector<Vec3> vertices;                      // m, every `v` line in file order
  std::vector<std::array<uint32_t, 3>> triangles;  // zero-based, faces fanned in file order
};

// Reads the OBJ file `path` (a regular file of at most kMaxSceneFileBytes). A face of n vertices
// v0 .. v(n-1) becomes the triangles (v0, vk, vk+1), k = 1 .. n-2, in order. Throws ObjError for
// an unreadable file, text the OBJ reader refuses, no vertices, a vertex that is not finite, a
// face of fewer than 3 vertices or one naming a vertex that does not exist; `need_faces` also
// refuses a file with no faces.
ObjGeometry read_obj(const std::string& path, bool need_faces);

}  // namespace elan::detail::scene_file
