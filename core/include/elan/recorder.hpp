// SPDX-License-Identifier: MIT
// The program recorder: records every state-changing call a program makes on a World between
// steps, and every step with its state hash, into a recording (elan/recording.hpp) that
// `elan replay`, the divergence finder and the viewer play back; and the replayer that does it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "elan/recording.hpp"
#include "elan/world.hpp"

namespace elan {

struct RecordOptions {
  /// A full snapshot every K steps (keyframes), for finding the first differing body of a
  /// replay that diverges and for seeking on the viewer's timeline; 0 keeps none.
  uint64_t keyframe_every = 60;
  std::string name;  ///< the program's (or scene's) name, for messages
};

/// Starts recording `world`: its whole state now (a snapshot, so a world built through the API
/// is covered), then every state-changing call (every non-const World method but set_threads,
/// set_broadphase and reserve, which change no result, and set_pair_filter, whose code cannot be
/// recorded; plus restore_snapshot and restore_rollback) with its arguments bit for bit, every
/// step with its timestep and the state hash after it. Calls that throw are not recorded.
/// Restarts the recording when one is running. Costs one branch per call when not recording.
void start_recording(World& world, const RecordOptions& options = {});
bool is_recording(const World& world);
/// The recording so far, encoded (encode_recording); the recording goes on. Empty when not
/// recording.
std::vector<uint8_t> save_recording(const World& world);
/// Stops recording and returns the recording (as save_recording).
std::vector<uint8_t> stop_recording(World& world);

/// One recorded call, as list_calls finds it in Recording::calls.
struct RecordedCall {
  uint64_t step = 0;       ///< recorded steps taken before it
  uint16_t op = 0;         ///< the call (recorded_call_name)
  std::size_t offset = 0;  ///< of its arguments in Recording::calls
  std::size_t size = 0;    ///< bytes of arguments
};
/// Every call of a program recording, in order, the steps included (op "step", arguments: the
/// timestep). Throws RecordingError for a malformed call stream.
std::vector<RecordedCall> list_calls(const Recording& r);
/// The World method an op records ("set_linear_velocity", "step", ...); "" for an unknown op.
std::string_view recorded_call_name(uint16_t op);
/// Every recorded method name (for checking that none is missed).
std::vector<std::string_view> recorded_call_names();

/// The world a recording starts from: a program recording's starting snapshot, with the given
/// thread count and broadphase. Scene recordings start from their scene (Recording::scene_text,
/// loaded with elan/scene.hpp). Throws RecordingError for a snapshot that does not load.
World recording_start_world(const Recording& r, int threads, BroadphaseType broadphase);

/// Plays a recording forward on a world: before each step the calls recorded before it, then
/// the step with its recorded timestep; compares each state hash with the recorded one.
/// `recording` must outlive the replayer.
class Replayer {
 public:
  /// `world` is the recording's state after `start_step` steps: recording_start_world (or the
  /// loaded scene) for 0, a keyframe or a saved snapshot for later steps.
  Replayer(const Recording& recording, World world, uint64_t start_step = 0);
  World& world() { return world_; }
  uint64_t step() const { return step_; }  ///< recorded steps replayed
  uint64_t steps() const;                  ///< recorded steps in all
  /// Applies the calls recorded before the next step and takes it. Returns whether the state
  /// hash then equals the recorded one. Throws RecordingError naming the call and step when a
  /// recorded call fails or returns another id than recorded (the replay has diverged), or when
  /// the recording has no step left.
  bool advance();
  uint64_t expected_hash() const;  ///< recorded after step()
  uint64_t actual_hash() const { return world_.state_hash(); }

 private:
  const Recording* r_;
  World world_;
  uint64_t step_ = 0;
  std::size_t next_call_ = 0;  // offset in r_->calls
};

/// One step of a recording on `world`, which holds the recording's state after `step` steps: the
/// calls recorded before the next step, then that step with its recorded timestep (a scene
/// recording: the step alone). Returns the step's StepStatus. For players that own their world
/// (the viewer's timeline); Replayer does the same without searching the calls each time.
/// Throws as Replayer::advance.
uint32_t replay_step(World& world, const Recording& r, uint64_t step);

struct ReplayOptions {
  int threads = 1;                           ///< 0: all cores
  std::optional<BroadphaseType> broadphase;  ///< default: the recorded one
  std::optional<uint64_t> until;             ///< stop after this many steps (default: all)
};

struct ReplayResult {
  bool match = true;                  ///< every state hash replayed equals the recorded one
  uint64_t steps = 0;                 ///< steps replayed
  uint64_t mismatch_step = 0;         ///< the first step whose hash differs (match false)
  uint64_t expected = 0, actual = 0;  ///< its hashes
  std::string error;                  ///< a recorded call that failed on replay (match false)
  std::vector<uint8_t> snapshot;      ///< the world where the replay stopped (save_snapshot)
};

/// Replays a program recording (`bytes`, as stop_recording returns) from its start. Throws
/// RecordingError for a corrupt recording, one from a build with other promises
/// (check_recording_build) or a scene recording (replay those with `elan replay`).
ReplayResult replay_recording(std::span<const uint8_t> bytes, const ReplayOptions& options = {});

}  // namespace elan
