// SPDX-License-Identifier: MIT
#include "tools/viewer/screenshot.hpp"

#include <cerrno>
#include <cstring>

#include "stb/stb_image_write.h"

namespace elan::viewer {

OffscreenTarget::~OffscreenTarget() {
  GLuint fbos[2] = {draw_fbo_, read_fbo_};
  GLuint rbs[3] = {color_, depth_, resolved_};
  glDeleteFramebuffers(2, fbos);
  glDeleteRenderbuffers(3, rbs);
}

bool OffscreenTarget::create(int width, int height, int samples, std::string& error) {
  width_ = width;
  height_ = height;
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples = samples > max_samples ? max_samples : samples;
  glGenFramebuffers(1, &draw_fbo_);
  glGenRenderbuffers(1, &color_);
  glGenRenderbuffers(1, &depth_);
  glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_);
  glBindRenderbuffer(GL_RENDERBUFFER, color_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    error = "the off-screen framebuffer is incomplete";
    return false;
  }
  glGenFramebuffers(1, &read_fbo_);
  glGenRenderbuffers(1, &resolved_);
  glBindFramebuffer(GL_FRAMEBUFFER, read_fbo_);
  glBindRenderbuffer(GL_RENDERBUFFER, resolved_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolved_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    error = "the off-screen resolve framebuffer is incomplete";
    return false;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return true;
}

void OffscreenTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_);
}

std::vector<uint8_t> OffscreenTarget::read_rgb() const {
  // Resolving the samples: a blit from the multisampled target to the plain one.
  glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, read_fbo_);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo_);
  std::vector<uint8_t> rgba(std::size_t(width_) * std::size_t(height_) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // OpenGL's rows start at the bottom; a PNG's at the top.
  std::vector<uint8_t> rgb(std::size_t(width_) * std::size_t(height_) * 3);
  for (int y = 0; y < height_; ++y) {
    const uint8_t* src = &rgba[std::size_t(height_ - 1 - y) * std::size_t(width_) * 4];
    uint8_t* dst = &rgb[std::size_t(y) * std::size_t(width_) * 3];
    for (int x = 0; x < width_; ++x) {
      dst[3 * x] = src[4 * x];
      dst[3 * x + 1] = src[4 * x + 1];
      dst[3 * x + 2] = src[4 * x + 2];
    }
  }
  return rgb;
}

bool write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb,
               std::string& error) {
  errno = 0;
  if (stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3) == 0) {
    error =
        path + ": cannot write the PNG" + (errno ? std::string(": ") + std::strerror(errno) : "");
    return false;
  }
  return true;
}

}  // namespace elan::viewer
