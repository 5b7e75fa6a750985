// SPDX-License-Identifier: MIT
// Off-screen pictures: a framebuffer object (multisampled, resolved into a plain one for
// reading) the renderer draws into, and PNG files written with stb_image_write.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/viewer/gl.hpp"

namespace elan::viewer {

class OffscreenTarget {
 public:
  OffscreenTarget() = default;
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  /// A w x h target with `samples` samples per pixel (0 or 1: none). False with `error` set.
  bool create(int width, int height, int samples, std::string& error);
  /// Draws go to this target after bind().
  void bind() const;
  /// The picture, RGB, rows from the top.
  std::vector<uint8_t> read_rgb() const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_ = 0, height_ = 0;
  GLuint draw_fbo_ = 0, color_ = 0, depth_ = 0;
  GLuint read_fbo_ = 0, resolved_ = 0;
};

/// Writes an RGB picture (rows from the top) as PNG. False with `error` set.
bool write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb,
               std::string& error);

}  // namespace elan::viewer
