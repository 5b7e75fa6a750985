// SPDX-License-Identifier: MIT
// The recording file: what `elan run --record` and the program recorder (elan/recorder.hpp)
// write and `elan replay` reads. A versioned little-endian binary file closed by a checksum: the
// starting world (a scene's text or a snapshot), the calls a program made between steps, the
// state hash after every step, full snapshots every K steps (keyframes) and the fingerprint of
// the build that made it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "elan/math.hpp"
#include "elan/one_line.hpp"

namespace elan {

/// The engine's version, written into recordings (informative: replay does not refuse another).
inline constexpr char kEngineVersion[] = "0.1.0";

/// What a build promises about its bits, in one place: two builds with the same promise give the
/// same state hashes for the same calls (a portable and a native build of the same source
/// included), so a recording made by one replays on the other; `elan replay` refuses a recording
/// whose promise differs. The `double` build is a different promise (other hashes).
inline constexpr const char* kDeterminismPromise =
#if defined(__x86_64__) || defined(_M_X64)
    sizeof(Real) == 4 ? "x86-64 float, cross-build" : "x86-64 double, cross-build";
#elif defined(__aarch64__) || defined(_M_ARM64)
    sizeof(Real) == 4 ? "aarch64 float, one build" : "aarch64 double, one build";
#else
    sizeof(Real) == 4 ? "other float, one build" : "other double, one build";
#endif

/// Format version written by encode_recording; versions kOldestRecordingVersion and on are read.
/// 1: scene, settings and hashes; 2: keyframes; 3: fingerprint, starting snapshot and calls.
inline constexpr uint32_t kRecordingVersion = 3;
inline constexpr uint32_t kOldestRecordingVersion = 1;

/// The file is not a recording, is truncated or corrupt, comes from a build with other promises,
/// or a recorded call failed on replay. Control characters in the message are escaped.
class RecordingError : public std::runtime_error {
 public:
  explicit RecordingError(const std::string& message) : std::runtime_error(one_line(message)) {}
};

/// A full world snapshot (elan/snapshot.hpp) after `step` recorded steps.
struct Keyframe {
  uint64_t step = 0;
  std::vector<uint8_t> snapshot;
};

struct Recording {
  uint32_t version = 0;        ///< of the file read; encode always writes kRecordingVersion
  uint32_t real_bytes = 0;     ///< sizeof(Real) of the recording build: hashes depend on it
  std::string engine_version;  ///< version 3 on (empty before)
  std::string promise;         ///< kDeterminismPromise of the recording build (version 3 on)
  uint64_t steps = 0;
  /// s, the Real value used, widened exactly. Program recordings carry each step's own timestep
  /// in `calls`; this is their first (0 when none was taken).
  double timestep = 0;
  int32_t substeps = 0;  ///< at the start
  int32_t iterations = 0;
  uint32_t threads = 0;     ///< informative: results do not depend on it
  uint32_t broadphase = 0;  ///< BroadphaseType of the recording run
  std::string scene_name;   ///< the scene's path (or the program's name) at record time
  std::string scene_text;   ///< scene recordings: the scene the world started from
  /// Program recordings: the world when recording started (save_snapshot); empty for a scene
  /// recording, which starts from `scene_text`.
  std::vector<uint8_t> initial_snapshot;
  /// Program recordings: every state-changing call and every step, in order, each as
  /// u16 op | u32 n | n bytes of arguments (elan/recorder.hpp, list_calls).
  std::vector<uint8_t> calls;
  uint64_t keyframe_every = 0;      ///< 0: no keyframes (always so in version 1 files)
  std::vector<Keyframe> keyframes;  ///< ascending steps, the first at step 0
  std::vector<uint64_t> hashes;     ///< steps + 1 entries: the state hash after k steps

  bool is_program() const { return !initial_snapshot.empty(); }
};

/// The keyframe with the largest step <= `step`, or null when there is none.
const Keyframe* keyframe_at_or_before(const Recording& r, uint64_t step);

/// A recording starts with these many magic bytes: a reader checks them (check_recording_magic)
/// before reading the rest, so that a file that is no recording is refused at once.
inline constexpr std::size_t kRecordingMagicBytes = 8;
/// Throws RecordingError naming `file` unless `head` (a file's first bytes, or all of a shorter
/// file) starts like a recording.
void check_recording_magic(std::string_view head, const std::string& file);

std::string encode_recording(const Recording& r);
/// Reads versions 1 to 3. Throws RecordingError naming `file` and what is wrong (a future
/// version is refused with the versions this build reads).
Recording decode_recording(std::string_view bytes, const std::string& file);

/// Throws RecordingError naming `file` and what differs when `r` comes from a build with other
/// promises than this one: another `Real` size or another kDeterminismPromise (version 3). The
/// engine version may differ.
void check_recording_build(const Recording& r, const std::string& file);

}  // namespace elan
