// SPDX-License-Identifier: MIT
// Recordings of `elan run --record`: the scene text, the settings, the state hash after every
// step and a full snapshot every K steps (keyframes), in a versioned little-endian binary file
// closed by a checksum.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "elan/one_line.hpp"

namespace elan::cli {

/// The file is not a recording, or is truncated or corrupt.
class RecordingError : public std::runtime_error {
 public:
  /// Control characters in `message` (from a file or scene name) are escaped (one_line).
  explicit RecordingError(const std::string& message) : std::runtime_error(one_line(message)) {}
};

/// A full world snapshot (elan/snapshot.hpp) after `step` steps.
struct Keyframe {
  uint64_t step = 0;
  std::vector<uint8_t> snapshot;
};

struct Recording {
  uint32_t version = 0;     // of the file read; encode always writes the current version
  uint32_t real_bytes = 0;  // sizeof(Real) of the recording build: hashes depend on it
  uint64_t steps = 0;
  double timestep = 0;  // s, the Real value used, widened exactly
  int32_t substeps = 0;
  int32_t iterations = 0;
  uint32_t threads = 0;     // informative: results do not depend on it
  uint32_t broadphase = 0;  // BroadphaseType of the recording run
  std::string scene_name;   // the scene's path at record time, for messages
  std::string scene_text;
  uint64_t keyframe_every = 0;      // 0: no keyframes (always so in version 1 files)
  std::vector<Keyframe> keyframes;  // ascending steps, the first at step 0
  std::vector<uint64_t> hashes;     // steps + 1 entries: the state hash after k steps
};

/// The keyframe with the largest step <= `step`, or null when there is none.
const Keyframe* keyframe_at_or_before(const Recording& r, uint64_t step);

/// A recording starts with these many magic bytes: a reader checks them (check_recording_magic)
/// before reading the rest, so that a file that is no recording is refused at once.
inline constexpr std::size_t kRecordingMagicBytes = 8;
/// Throws RecordingError naming `file` unless `head` (a file's first bytes, or all of a shorter
/// file) starts like a recording.
void check_recording_magic(const std::string& head, const std::string& file);

std::string encode_recording(const Recording& r);
/// Reads versions 1 (no keyframes) and 2. Throws RecordingError naming `file` and what is wrong.
Recording decode_recording(const std::string& bytes, const std::string& file);

}  // namespace elan::cli
