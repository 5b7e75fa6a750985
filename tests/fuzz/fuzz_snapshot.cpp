// SPDX-License-Identifier: MIT
// Fuzz target: the snapshot and rollback readers on any bytes. The first byte chooses: bit 0
// re-seals the checksum over the mutated bytes (else almost every mutation would stop at the
// checksum and the parser behind it would go unexplored), bit 1 reads a rollback state into the
// fixed world instead of a snapshot. A state is either refused with one elan::Error line, the
// world left as it was, or it loads: then it is finite, steps finite, and saving it again gives
// bytes that load and save to the same bytes.
#include <vector>

#include "core/world/byte_io.hpp"
#include "elan/snapshot.hpp"
#include "fuzz/fixed_world.hpp"
#include "fuzz/world_checks.hpp"

namespace {

void reseal(std::vector<uint8_t>& bytes) {
  if (bytes.size() < 8) return;
  const std::size_t body = bytes.size() - 8;
  const uint64_t sum = elan::detail::checksum_words(std::span<const uint8_t>(bytes.data(), body));
  for (int i = 0; i < 8; ++i) bytes[body + i] = uint8_t(sum >> (8 * i));
}

void check_snapshot(const std::vector<uint8_t>& bytes) {
  using namespace elan;
  World w;
  try {
    w = load_snapshot(bytes);
  } catch (const Error& e) {
    fuzz::require_one_line(e.what());
    return;
  }
  fuzz::require_finite(w, "a loaded snapshot", false);
  const std::vector<uint8_t> saved = save_snapshot(w);
  World again = load_snapshot(saved);
  fuzz::require(save_snapshot(again) == saved, "save(load(save(w))) == save(w)");
  fuzz::require(again.state_hash() == w.state_hash(), "a reloaded snapshot has the same hash");
  if (w.body_count() <= 64) {
    for (int k = 0; k < 4; ++k) {
      w.step(Real(1.0 / 60.0));
      fuzz::require_finite(w, "a step of a loaded snapshot", false);
    }
  }
}

void check_rollback(const std::vector<uint8_t>& bytes) {
  using namespace elan;
  World w = fuzz::fixed_world();
  w.step(Real(1.0 / 60.0));
  const uint64_t before = w.state_hash();
  try {
    restore_rollback(w, bytes);
  } catch (const Error& e) {
    fuzz::require_one_line(e.what());
    fuzz::require(w.state_hash() == before, "a refused rollback leaves the world unchanged");
    return;
  }
  fuzz::require_finite(w, "a restored rollback", false);
  for (int k = 0; k < 4; ++k) {
    w.step(Real(1.0 / 60.0));
    fuzz::require_finite(w, "a step after a rollback", false);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const uint8_t mode = data[0];
  std::vector<uint8_t> bytes(data + 1, data + size);
  if (mode & 1) reseal(bytes);
  if (mode & 2) {
    check_rollback(bytes);
  } else {
    check_snapshot(bytes);
  }
  return 0;
}
