// SPDX-License-Identifier: MIT
// RegularFile: open(2) with O_NONBLOCK, so that opening a FIFO with no writer does not block,
// then fstat(2) on the open descriptor, so that what is checked is what is read.
#include "core/scene/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "elan/one_line.hpp"
#include "elan/scene.hpp"

namespace elan::detail {

FileError::FileError(const std::string& message) : std::runtime_error(one_line(message)) {}

namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

RegularFile::RegularFile(const std::string& path, const std::string& what)
    : path_(path), what_(what) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw FileError(path + ": cannot open " + what + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int e = errno;
    ::close(fd_);
    throw FileError(path + ": cannot open " + what + ": " + std::strerror(e));
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw FileError(path + ": is " + kind_of(st.st_mode) + ", not a " + what + " file");
  }
  size_ = uint64_t(st.st_size);
}

RegularFile::~RegularFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::string RegularFile::read(uint64_t n) {
  std::string out;
  // Grown as bytes arrive rather than reserved from `n`, which may be a bound, not a size.
  constexpr uint64_t kChunk = 1 << 16;
  while (out.size() < n) {
    const std::size_t want = std::size_t(std::min<uint64_t>(kChunk, n - out.size()));
    const std::size_t old = out.size();
    out.resize(old + want);
    const ssize_t got = ::read(fd_, out.data() + old, want);
    if (got < 0 && errno == EINTR) {
      out.resize(old);
      continue;
    }
    if (got < 0) throw FileError(path_ + ": cannot read " + what_ + ": " + std::strerror(errno));
    out.resize(old + std::size_t(got));
    if (got == 0) break;
  }
  return out;
}

std::string read_scene_file(const std::string& path) {
  try {
    RegularFile file(path, "scene");
    const auto too_large = [&] {
      return SceneError(path + ": file too large for a scene (more than " +
                        std::to_string(kMaxSceneFileBytes >> 20) + " MiB)");
    };
    if (file.size() > kMaxSceneFileBytes) throw too_large();
    // One byte past the cap tells a file that grew past it since it was opened.
    std::string text = file.read(kMaxSceneFileBytes + 1);
    if (text.size() > kMaxSceneFileBytes) throw too_large();
    return text;
  } catch (const FileError& e) {
    throw SceneError(e.what());
  }
}

}  // namespace elan::detail
