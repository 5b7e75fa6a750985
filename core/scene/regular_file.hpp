// SPDX-License-Identifier: MIT
// RegularFile: an input file opened for reading only when it is a regular file, read in pieces
// so that a caller can check a header before reading the rest. A device (/dev/zero,
// /dev/urandom), a FIFO or a directory is refused at once instead of being read without end or
// reported as an empty file.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace elan::detail {

/// The file cannot be opened or read, or is not a regular file. what() is one line naming it.
class FileError : public std::runtime_error {
 public:
  explicit FileError(const std::string& message);
};

class RegularFile {
 public:
  /// Opens `path` (`what` names its role in messages, e.g. "scene"). Throws FileError
  /// "PATH: cannot open WHAT: REASON" or "PATH: is a directory, not a WHAT file" (or a device,
  /// FIFO, socket).
  RegularFile(const std::string& path, const std::string& what);
  ~RegularFile();
  RegularFile(const RegularFile&) = delete;
  RegularFile& operator=(const RegularFile&) = delete;

  /// The size the file had when it was opened.
  uint64_t size() const { return size_; }
  /// Up to `n` more bytes, fewer only at the end of the file. Throws FileError on a read error.
  std::string read(uint64_t n);

 private:
  std::string path_, what_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

/// A scene file's largest size: 256 MiB. The JSON DOM built from the text takes several times
/// the text in memory (a scene of 256 MiB already needs a few GB), and a file of explicit bodies
/// that large holds about a million of them (pile10k: 2.3 MB for 10,000); bigger scenes use
/// generators. Without a cap a runaway file would exhaust memory before any check could run.
inline constexpr uint64_t kMaxSceneFileBytes = uint64_t(256) << 20;

/// The text of the scene file `path`: a regular file of at most kMaxSceneFileBytes. Throws
/// SceneError naming the file.
std::string read_scene_file(const std::string& path);

}  // namespace elan::detail
