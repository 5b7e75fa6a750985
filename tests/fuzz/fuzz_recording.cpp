// SPDX-License-Identifier: MIT
// Fuzz target: the recording reader on any bytes. The first byte's bit 0 re-seals the file's
// checksum (FNV-1a over every byte before the last eight, as core/world/recording.cpp writes it)
// over the mutated bytes, so mutations reach the parser behind it. A recording is either refused
// with one RecordingError line, or it decodes, encodes back to bytes that decode to the same bytes
// again, and each keyframe's snapshot loads or is refused with one elan::Error line.
#include <string>

#include "elan/snapshot.hpp"
#include "fuzz/world_checks.hpp"
#include "tools/recording.hpp"

namespace {

void reseal(std::string& bytes) {
  if (bytes.size() < 8) return;
  const std::size_t body = bytes.size() - 8;
  uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < body; ++i) h = (h ^ uint8_t(bytes[i])) * 0x100000001b3ull;
  for (int i = 0; i < 8; ++i) bytes[body + i] = char(uint8_t(h >> (8 * i)));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace elan;
  using namespace elan::cli;
  if (size == 0) return 0;
  std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] & 1) reseal(bytes);
  Recording r;
  try {
    check_recording_magic(bytes.substr(0, kRecordingMagicBytes), "fuzz.rec");
    r = decode_recording(bytes, "fuzz.rec");
  } catch (const RecordingError& e) {
    fuzz::require_one_line(e.what());
    return 0;
  }
  const std::string again = encode_recording(r);
  Recording r2;
  try {
    r2 = decode_recording(again, "again.rec");
  } catch (const RecordingError& e) {
    fuzz::fail("a decoded recording encodes to a readable one:", e.what());
  }
  fuzz::require(encode_recording(r2) == again, "encode(decode(encode(r))) == encode(r)");
  for (const Keyframe& k : r.keyframes) {
    try {
      const World w = load_snapshot(k.snapshot);
      fuzz::require_finite(w, "a keyframe's world", false);
    } catch (const Error& e) {
      fuzz::require_one_line(e.what());
    }
  }
  return 0;
}
