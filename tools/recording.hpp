// Recordings of `elan run --record`: the scene text, the settings and the state hash after every
// step, in a versioned little-endian binary file closed by a checksum.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace elan::cli {

/// The file is not a recording, or is truncated or corrupt.
class RecordingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Recording {
  uint32_t real_bytes = 0;  // sizeof(Real) of the recording build: hashes depend on it
  uint64_t steps = 0;
  double timestep = 0;  // s, the Real value used, widened exactly
  int32_t substeps = 0;
  int32_t iterations = 0;
  uint32_t threads = 0;     // informative: results do not depend on it
  uint32_t broadphase = 0;  // BroadphaseType of the recording run
  std::string scene_name;   // the scene's path at record time, for messages
  std::string scene_text;
  std::vector<uint64_t> hashes;  // steps + 1 entries: the state hash after k steps
};

std::string encode_recording(const Recording& r);
/// Throws RecordingError naming `file` and what is wrong.
Recording decode_recording(const std::string& bytes, const std::string& file);

}  // namespace elan::cli
