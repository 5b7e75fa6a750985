// SPDX-License-Identifier: MIT
// Wavefront OBJ files through tinyobjloader (Debian's libtinyobjloader-dev). A library rather
// than a reader of our own: it is small and maintained, and handles the format's corners that a
// quick reader gets wrong (negative indices counted back from the last vertex, the v, v/vt,
// v//vn and v/vt/vn face forms, groups and objects, CRLF line ends). Its own triangulation is off
// (triangulate = false): polygons are fanned here, so the triangles are exactly the ones
// docs/scene-format.md promises, whatever the loader's version would do with them.
#include "core/scene/obj_file.hpp"

#include <tiny_obj_loader.h>

#include <cmath>
#include <cstddef>

#include "core/scene/regular_file.hpp"

namespace elan::detail::scene_file {

namespace {

// The loader's messages end in newlines and may hold several lines: one line, for our messages.
std::string joined(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  std::string out;
  for (const char c : s) {
    if (c == '\r') continue;
    if (c == '\n') {
      out += "; ";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

ObjGeometry read_obj(const std::string& path, bool need_faces) {
  std::string text;
  try {
    RegularFile file(path, "Wavefront OBJ");
    if (file.size() > kMaxSceneFileBytes) {
      throw ObjError(path + ": file too large for an OBJ (more than " +
                     std::to_string(kMaxSceneFileBytes >> 20) + " MiB)");
    }
    text = file.read(kMaxSceneFileBytes + 1);
    if (text.size() > kMaxSceneFileBytes) {
      throw ObjError(path + ": file too large for an OBJ (more than " +
                     std::to_string(kMaxSceneFileBytes >> 20) + " MiB)");
    }
  } catch (const FileError& e) {
    throw ObjError(e.what());
  }
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // From the text already read (the regular-file check applies); materials are not used, so no
  // .mtl text is given and `mtllib` lines are ignored.
  if (!reader.ParseFromString(text, "", config)) {
    throw ObjError(path + ": malformed OBJ: " + joined(reader.Error()));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  ObjGeometry g;
  const std::size_t n = attrib.vertices.size() / 3;
  if (n == 0) throw ObjError(path + ": malformed OBJ: no vertices");
  g.vertices.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = attrib.vertices[3 * i], y = attrib.vertices[3 * i + 1],
                 z = attrib.vertices[3 * i + 2];
    const Vec3 v(static_cast<Real>(x), static_cast<Real>(y), static_cast<Real>(z));
    if (!v.allFinite()) {
      throw ObjError(path + ": malformed OBJ: vertex " + std::to_string(i + 1) +
                     " is not a finite point");
    }
    g.vertices.push_back(v);
  }
  std::size_t face = 0;  // counted over the whole file, one-based as OBJ counts
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t at = 0;
    for (const unsigned char count : shape.mesh.num_face_vertices) {
      ++face;
      if (count < 3) {
        throw ObjError(path + ": malformed OBJ: face " + std::to_string(face) + " has " +
                       std::to_string(count) + " vertices, at least 3 are needed");
      }
      uint32_t v[256];
      for (std::size_t k = 0; k < count; ++k) {
        const int index = shape.mesh.indices[at + k].vertex_index;
        if (index < 0 || std::size_t(index) >= n) {
          // The loader has already turned a negative (relative) index into an absolute one.
          throw ObjError(path + ": malformed OBJ: face " + std::to_string(face) +
                         " names a vertex that does not exist (the file has " + std::to_string(n) +
                         ")");
        }
        v[k] = uint32_t(index);
      }
      for (std::size_t k = 1; k + 1 < count; ++k) g.triangles.push_back({v[0], v[k], v[k + 1]});
      at += count;
    }
  }
  if (need_faces && g.triangles.empty()) throw ObjError(path + ": malformed OBJ: no faces");
  return g;
}

}  // namespace elan::detail::scene_file
