// SPDX-License-Identifier: MIT
#include "tools/viewer/renderer.hpp"

#include <cstddef>

namespace elan::viewer {
namespace {

// Instances: the unit mesh is scaled, rotated by the quaternion (v' = v + 2w(q x v) + 2q x (q x
// v)) and moved. Normals take the inverse scale (the inverse transpose of a scaling).
const char* const kSolidVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 i_position;
layout(location = 3) in vec4 i_rotation;
layout(location = 4) in vec3 i_scale;
layout(location = 5) in vec4 i_color;
layout(location = 6) in float i_grid;
uniform mat4 u_view_projection;
out vec3 v_world;
out vec3 v_normal;
out vec4 v_color;
out float v_grid;
vec3 rotate(vec4 q, vec3 v) {
  vec3 t = 2.0 * cross(q.xyz, v);
  return v + q.w * t + cross(q.xyz, t);
}
void main() {
  vec3 p = i_position + rotate(i_rotation, a_position * i_scale);
  v_world = p;
  v_normal = rotate(i_rotation, a_normal / i_scale);
  v_color = i_color;
  v_grid = i_grid;
  gl_Position = u_view_projection * vec4(p, 1.0);
}
)";

// Lambert shading from a fixed key light and a head light, plus a sky-to-ground ambient term.
// Faces are lit from the side the eye sees (meshes and planes are two-sided). The grid: lines
// where a world coordinate crosses a whole metre, in the two axes across the face's normal, one
// pixel wide (fwidth), fading where the cells get smaller than a few pixels.
const char* const kSolidFragment = R"(#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec4 v_color;
in float v_grid;
uniform vec3 u_eye;
uniform vec3 u_light;
out vec4 o_color;
void main() {
  vec3 n = normalize(v_normal);
  vec3 to_eye = normalize(u_eye - v_world);
  if (dot(n, to_eye) < 0.0) n = -n;
  float key = max(dot(n, u_light), 0.0);
  float head = max(dot(n, to_eye), 0.0);
  float sky = 0.5 + 0.5 * n.y;
  vec3 c = v_color.rgb * (0.22 + 0.18 * sky + 0.45 * key + 0.25 * head);
  if (v_grid > 0.0) {
    vec3 a = abs(n);
    vec2 uv = (a.y >= a.x && a.y >= a.z) ? v_world.xz : ((a.x >= a.z) ? v_world.yz : v_world.xy);
    vec2 w = fwidth(uv);
    vec2 g = abs(fract(uv - 0.5) - 0.5) / max(w, vec2(1e-6));
    float line = 1.0 - min(min(g.x, g.y), 1.0);
    float fade = clamp(1.0 - 4.0 * max(w.x, w.y), 0.0, 1.0);
    c = mix(c, c * 0.55, line * fade * v_grid);
  }
  o_color = vec4(c, v_color.a);
}
)";

const char* const kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_color;
uniform mat4 u_view_projection;
out vec4 v_color;
void main() {
  v_color = a_color;
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
)";

const char* const kLineFragment = R"(#version 330 core
in vec4 v_color;
out vec4 o_color;
void main() { o_color = v_color; }
)";

GLuint compile(GLenum type, const char* source, std::string& error) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    error = std::string("shader compilation failed: ") + log;
    glDeleteShader(s);
    return 0;
  }
  return s;
}

GLuint link(const char* vertex, const char* fragment, std::string& error) {
  const GLuint v = compile(GL_VERTEX_SHADER, vertex, error);
  if (v == 0) return 0;
  const GLuint f = compile(GL_FRAGMENT_SHADER, fragment, error);
  if (f == 0) return 0;
  const GLuint p = glCreateProgram();
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    error = std::string("shader link failed: ") + log;
    glDeleteProgram(p);
    return 0;
  }
  return p;
}

void attribute(GLuint index, GLint size, GLsizei stride, std::size_t offset, bool per_instance) {
  glEnableVertexAttribArray(index);
  glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offset));
  glVertexAttribDivisor(index, per_instance ? 1 : 0);
}

}  // namespace

Renderer::~Renderer() {
  clear_meshes();
  if (solid_) glDeleteProgram(solid_);
  if (line_) glDeleteProgram(line_);
  if (line_vao_) glDeleteVertexArrays(1, &line_vao_);
  if (line_buffer_) glDeleteBuffers(1, &line_buffer_);
}

bool Renderer::init(std::string& error) {
  solid_ = link(kSolidVertex, kSolidFragment, error);
  if (solid_ == 0) return false;
  line_ = link(kLineVertex, kLineFragment, error);
  if (line_ == 0) return false;
  glGenVertexArrays(1, &line_vao_);
  glGenBuffers(1, &line_buffer_);
  glBindVertexArray(line_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, line_buffer_);
  attribute(0, 3, sizeof(LineVertex), offsetof(LineVertex, position), false);
  attribute(1, 4, sizeof(LineVertex), offsetof(LineVertex, color), false);
  glBindVertexArray(0);
  return true;
}

int Renderer::add_mesh(const MeshData& data) {
  Mesh m;
  m.index_count = GLsizei(data.indices.size());
  glGenVertexArrays(1, &m.vao);
  glGenBuffers(1, &m.vertices);
  glGenBuffers(1, &m.indices);
  glGenBuffers(1, &m.instances);
  glBindVertexArray(m.vao);
  glBindBuffer(GL_ARRAY_BUFFER, m.vertices);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.vertices.size() * sizeof(MeshVertex)),
               data.vertices.data(), GL_STATIC_DRAW);
  attribute(0, 3, sizeof(MeshVertex), offsetof(MeshVertex, position), false);
  attribute(1, 3, sizeof(MeshVertex), offsetof(MeshVertex, normal), false);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.indices);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(data.indices.size() * sizeof(uint32_t)),
               data.indices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, m.instances);
  attribute(2, 3, sizeof(Instance), offsetof(Instance, position), true);
  attribute(3, 4, sizeof(Instance), offsetof(Instance, rotation), true);
  attribute(4, 3, sizeof(Instance), offsetof(Instance, scale), true);
  attribute(5, 4, sizeof(Instance), offsetof(Instance, color), true);
  attribute(6, 1, sizeof(Instance), offsetof(Instance, grid), true);
  glBindVertexArray(0);
  meshes_.push_back(std::move(m));
  return int(meshes_.size() - 1);
}

void Renderer::clear_meshes() {
  for (Mesh& m : meshes_) {
    glDeleteVertexArrays(1, &m.vao);
    GLuint buffers[3] = {m.vertices, m.indices, m.instances};
    glDeleteBuffers(3, buffers);
  }
  meshes_.clear();
}

void Renderer::begin_frame() {
  for (Mesh& m : meshes_) {
    m.frame.clear();
    m.translucent.clear();
  }
  lines_.clear();
  overlay_lines_.clear();
}

void Renderer::add_instance(int mesh, const Instance& instance) {
  Mesh& m = meshes_[std::size_t(mesh)];
  (instance.color[3] < 1.0f ? m.translucent : m.frame).push_back(instance);
}

void Renderer::add_line(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                        const Eigen::Vector4f& color) {
  lines_.push_back({{a.x(), a.y(), a.z()}, {color[0], color[1], color[2], color[3]}});
  lines_.push_back({{b.x(), b.y(), b.z()}, {color[0], color[1], color[2], color[3]}});
}

void Renderer::add_overlay_line(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                                const Eigen::Vector4f& color) {
  overlay_lines_.push_back({{a.x(), a.y(), a.z()}, {color[0], color[1], color[2], color[3]}});
  overlay_lines_.push_back({{b.x(), b.y(), b.z()}, {color[0], color[1], color[2], color[3]}});
}

void Renderer::draw_instances(bool translucent) {
  glUseProgram(solid_);
  for (Mesh& m : meshes_) {
    const std::vector<Instance>& list = translucent ? m.translucent : m.frame;
    if (list.empty() || m.index_count == 0) continue;
    glBindVertexArray(m.vao);
    glBindBuffer(GL_ARRAY_BUFFER, m.instances);
    // Orphaning the buffer each time: the driver hands a fresh one instead of waiting for the
    // previous draw to finish reading it.
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(list.size() * sizeof(Instance)), list.data(),
                 GL_STREAM_DRAW);
    glDrawElementsInstanced(GL_TRIANGLES, m.index_count, GL_UNSIGNED_INT, nullptr,
                            GLsizei(list.size()));
  }
}

void Renderer::draw_lines(const std::vector<LineVertex>& lines) {
  if (lines.empty()) return;
  glUseProgram(line_);
  glUniformMatrix4fv(glGetUniformLocation(line_, "u_view_projection"), 1, GL_FALSE,
                     view_projection_.data());
  glBindVertexArray(line_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, line_buffer_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(lines.size() * sizeof(LineVertex)), lines.data(),
               GL_STREAM_DRAW);
  glDrawArrays(GL_LINES, 0, GLsizei(lines.size()));
}

void Renderer::draw(const Eigen::Matrix4f& view_projection, const Eigen::Vector3f& eye, int width,
                    int height) {
  view_projection_ = view_projection;
  glViewport(0, 0, width, height);
  glClearColor(kBackground[0], kBackground[1], kBackground[2], 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // meshes and planes are two-sided
  glDisable(GL_BLEND);

  glUseProgram(solid_);
  glUniformMatrix4fv(glGetUniformLocation(solid_, "u_view_projection"), 1, GL_FALSE,
                     view_projection.data());
  glUniform3f(glGetUniformLocation(solid_, "u_eye"), eye.x(), eye.y(), eye.z());
  const Eigen::Vector3f light = Eigen::Vector3f(0.4f, 1.0f, 0.3f).normalized();
  glUniform3f(glGetUniformLocation(solid_, "u_light"), light.x(), light.y(), light.z());
  draw_instances(false);
  draw_lines(lines_);
  // Translucent bodies (sensors) over the solid ones: blended, and writing no depth, so that
  // one behind another still shows.
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  draw_instances(true);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  draw_lines(overlay_lines_);
  glEnable(GL_DEPTH_TEST);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace elan::viewer
