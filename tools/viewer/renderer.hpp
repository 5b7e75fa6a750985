// SPDX-License-Identifier: MIT
// The OpenGL 3.3 renderer: meshes drawn instanced (one draw call per mesh, each instance a pose,
// a scale and a colour), lit by a key light and a head light, with a one-metre grid on static
// bodies; and coloured lines (joints and the debug-draw overlays).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tools/viewer/gl.hpp"
#include "tools/viewer/shape_mesh.hpp"

namespace elan::viewer {

struct Instance {
  float position[3];  ///< m, world: the shape frame's origin
  float rotation[4];  ///< unit quaternion x, y, z, w: shape frame to world
  float scale[3];     ///< of the unit mesh (1 for meshes built at their size)
  float color[4];     ///< linear RGBA
  float grid;         ///< 1: draw the one-metre grid on it (static bodies), 0: none
};

struct LineVertex {
  float position[3];
  float color[4];
};

/// The background colour, also what a test takes for "no body here".
inline constexpr float kBackground[3] = {0.16f, 0.18f, 0.22f};

class Renderer {
 public:
  Renderer() = default;
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Compiles the shaders; needs a current OpenGL 3.3 core context. False with `error` set.
  bool init(std::string& error);
  /// Uploads a mesh; returns its index for add_instance.
  int add_mesh(const MeshData& mesh);
  void clear_meshes();
  /// This frame's instances and lines (cleared by begin_frame).
  void begin_frame();
  void add_instance(int mesh, const Instance& instance);
  void add_line(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector4f& color);
  /// A line drawn over everything (the debug-draw overlays: contacts inside a pile stay seen).
  void add_overlay_line(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                        const Eigen::Vector4f& color);
  /// Clears the bound framebuffer's viewport and draws this frame: the solid instances, the
  /// lines, the translucent instances (alpha < 1, blended over what is behind them, writing no
  /// depth), then the overlay lines without depth test.
  void draw(const Eigen::Matrix4f& view_projection, const Eigen::Vector3f& eye, int width,
            int height);

 private:
  struct Mesh {
    GLuint vao = 0, vertices = 0, indices = 0, instances = 0;
    GLsizei index_count = 0;
    std::vector<Instance> frame;        // this frame's solid instances
    std::vector<Instance> translucent;  // and those with alpha < 1
  };
  void draw_instances(bool translucent);
  void draw_lines(const std::vector<LineVertex>& lines);

  std::vector<Mesh> meshes_;
  std::vector<LineVertex> lines_, overlay_lines_;
  Eigen::Matrix4f view_projection_ = Eigen::Matrix4f::Identity();
  GLuint solid_ = 0, line_ = 0;
  GLuint line_vao_ = 0, line_buffer_ = 0;
};

}  // namespace elan::viewer
