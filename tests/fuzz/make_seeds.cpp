// SPDX-License-Identifier: MIT
// Writes the generated part of the seed corpora (docs/fuzzing.md): snapshots and rollback
// states of the fixed world, recordings, point clouds and shape pairs. Run once when a format
// changes: `cmake --build B --target fuzz_make_seeds && B/tests/fuzz/fuzz_make_seeds
// tests/fuzz/corpus`. The scene corpus is scene files, copied by hand.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "elan/snapshot.hpp"
#include "fuzz/fixed_world.hpp"
#include "tools/recording.hpp"

namespace {

void write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}
std::string with_mode(uint8_t mode, const std::vector<uint8_t>& b) {
  return std::string(1, char(mode)) + std::string(b.begin(), b.end());
}

// The same bytes on every platform: a fixed linear congruential generator.
struct Lcg {
  uint64_t s;
  uint8_t next() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return uint8_t(s >> 56);
  }
};

}  // namespace

int main(int argc, char** argv) {
  using namespace elan;
  using namespace elan::cli;
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds CORPUS_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  const Real dt = Real(1.0 / 60.0);

  // Snapshots (mode 1: re-seal) at rest, moving and with contacts; one unsealed (mode 0).
  World w = fuzz::fixed_world();
  write(dir + "/snapshot/fresh", with_mode(1, save_snapshot(w)));
  write(dir + "/snapshot/fresh_unsealed", with_mode(0, save_snapshot(w)));
  std::vector<std::vector<uint8_t>> keyframes{save_snapshot(w)};
  for (int k = 0; k < 30; ++k) w.step(dt);
  write(dir + "/snapshot/stepped30", with_mode(1, save_snapshot(w)));
  keyframes.push_back(save_snapshot(w));
  // Rollback states (mode 3) of the fixed world, which the target restores them into.
  write(dir + "/snapshot/rollback_stepped30", with_mode(3, save_rollback(w)));
  World fresh = fuzz::fixed_world();
  fresh.step(dt);
  write(dir + "/snapshot/rollback_stepped1", with_mode(3, save_rollback(fresh)));

  // Recordings: with keyframes, and a version-1-like one without.
  Recording r;
  r.real_bytes = sizeof(Real);
  r.steps = 30;
  r.timestep = double(dt);
  r.substeps = 4;
  r.iterations = 1;
  r.threads = 1;
  r.scene_name = "fixed.json";
  r.scene_text = R"({"bodies":[{"shape":{"type":"sphere","radius":0.5}}]})";
  r.keyframe_every = 30;
  r.keyframes = {{0, keyframes[0]}, {30, keyframes[1]}};
  r.hashes.assign(31, 0);
  for (uint64_t k = 0; k <= 30; ++k) r.hashes[k] = 0x9e3779b97f4a7c15ull * (k + 1);
  const std::string rec = encode_recording(r);
  write(dir + "/recording/keyframes", std::string(1, '\1') + rec);
  write(dir + "/recording/keyframes_unsealed", std::string(1, '\0') + rec);
  r.keyframe_every = 0;
  r.keyframes.clear();
  r.steps = 2;
  r.hashes.resize(3);
  write(dir + "/recording/no_keyframes", std::string(1, '\1') + encode_recording(r));

  // Point clouds: grid mode at each scale (even first byte), raw floats (odd).
  Lcg lcg{42};
  for (int s = 0; s < 7; ++s) {
    std::string b(1, char(2 * s));
    const int n = 4 + 3 * s;
    for (int k = 0; k < 3 * n; ++k) b.push_back(char(lcg.next()));
    write(dir + "/hull/grid_scale" + std::to_string(s), b);
  }
  {
    // A cube's corners and its centre, and four coplanar points (a refusal).
    std::string cube(1, '\2');
    for (int k = 0; k < 8; ++k) {
      cube += char((k & 1) ? 16 : -16);
      cube += char((k & 2) ? 16 : -16);
      cube += char((k & 4) ? 16 : -16);
    }
    cube += std::string(3, '\0');
    write(dir + "/hull/cube_and_centre", cube);
    write(dir + "/hull/coplanar", std::string("\2\0\0\0\20\0\0\0\20\0\20\20\0", 13));
    std::string raw(1, '\1');
    const float values[] = {0, 0, 0, 1,     0,       0, 0,    1,    0,
                            0, 0, 1, 1e30f, -1e-30f, 3, 0.5f, 0.5f, 0.5f};
    raw.append(reinterpret_cast<const char*>(values), sizeof values);
    write(dir + "/hull/raw_floats", raw);
    const uint32_t nan_bits[] = {0, 0, 0, 0x3f800000, 0, 0, 0, 0x3f800000, 0, 0x7fc00000, 0, 0};
    std::string nan(1, '\1');
    nan.append(reinterpret_cast<const char*>(nan_bits), sizeof nan_bits);
    write(dir + "/hull/nan", nan);
  }

  // Shape pairs: each of the 25 type pairs, sizes, poses and hull points drawn at random.
  for (int ta = 0; ta < 5; ++ta) {
    for (int tb = 0; tb < 5; ++tb) {
      std::string b;
      for (int t : {ta, tb}) {
        b += char(t);
        for (int k = 0; k < 80; ++k) b += char(lcg.next());
      }
      b += char(lcg.next());
      write(dir + "/narrowphase/pair_" + std::to_string(ta) + std::to_string(tb), b);
    }
  }
  return 0;
}
