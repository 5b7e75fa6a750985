// SPDX-License-Identifier: MIT
// Golden state hashes: every standard scene in scenes/, stepped 120 times from its file, must give
// the state hash written below, for 1 and 2 threads and both broadphases (Box3D's
// test_determinism.c keeps such constants). A change of behaviour, however small, changes a hash,
// so it is always a deliberate edit of a constant here, never a side effect of a refactor.
//
// The constants are those of the portable float build (no -march=native), which is what a
// package or a plain `cmake -DCMAKE_BUILD_TYPE=Release` makes. Every float build must give them:
// Debug and sanitized builds, -march=native with AVX2 or AVX-512, 8 or 16 solver lanes
// (ELAN_LANES), GCC or Clang (docs/determinism.md says what that promise covers and why it holds).
// A build that differs fails here. The double build has other bits (its own rounding): there the
// test checks only that the four runs of a scene agree with each other.
//
// To update after a deliberate change of behaviour: build portable Release and run
//   for f in scenes/*.json; do build/tools/elan run $f --steps 120 | grep state_hash; done
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace golden_hashes_test {

constexpr int kSteps = 120;

#if defined(ELAN_DOUBLE)
constexpr bool kCompareConstants = false;
#else
constexpr bool kCompareConstants = true;
#endif

// A native build (-march=native) is checked for the constants, the bits of the portable build;
// that other thread counts and broadphases agree is checked in every build by the determinism
// tests, and here in the portable build.
#if defined(ELAN_NATIVE_BUILD)
constexpr bool kNativeBuild = true;
#else
constexpr bool kNativeBuild = false;
#endif

// Scene file (without .json) -> state hash after kSteps steps, every float build.
const std::map<std::string, uint64_t>& golden() {
  static const std::map<std::string, uint64_t> table = {
      {"chains", 0xead3d4ee23b124fcull},         {"joint_grid", 0x8a30cbea3997a9f2ull},
      {"joints_demo", 0x54d757140060d1afull},    {"ragdolls", 0xe5a821fcc89e008full},
      {"jolt_pyramid", 0x35d54aad4f86aef8ull},   {"many_pyramids", 0x4ef28a35e9219de1ull},
      {"pile10k", 0xb2e1bca852c1ff01ull},        {"pile1k", 0xda86c69fb3ac0246ull},
      {"pile4k", 0xf1c78fff22c83d08ull},         {"pyramid10", 0x3043830915c9b8b9ull},
      {"pyramid20", 0x0a61641085aba68eull},      {"rain", 0x7ccac63d4961de94ull},
      {"spheres_in_box", 0x1cc6bdae62762ca1ull}, {"tower20", 0xec93d1076c99a160ull},
      {"towers", 0xefd2e01bd19bcdcbull},         {"tumbler", 0x711aed2ee56c4395ull},
      {"compounds", 0x85b976512812ca5bull},      {"convex_vs_mesh", 0xf81096dd303b973aull},
      {"geometry_demo", 0xfe4c5fcb259a97a4ull},  {"heightfield_rain", 0x1470e7c86eaa09a1ull},
  };
  return table;
}

uint64_t hash_after(const std::string& scene, int threads, BroadphaseType broadphase) {
  Real dt = 0;
  World world = test::load_world(scene + ".json", threads, dt, broadphase);
  for (int n = 0; n < kSteps; ++n) world.step(dt);
  return world.state_hash();
}

std::string hex(uint64_t h) {
  char text[19];
  std::snprintf(text, sizeof text, "0x%016llx", static_cast<unsigned long long>(h));
  return text;
}

class GoldenHash : public ::testing::TestWithParam<std::string> {};

TEST_P(GoldenHash, SameHashForOneAndTwoThreadsAndBothBroadphases) {
  const std::string scene = GetParam();
  // Under the sanitizers a step is about ten times slower: there, and in a native build, one run
  // checks the constant, and the portable unsanitized build checks that the others agree.
  struct Run {
    int threads;
    BroadphaseType broadphase;
  };
  const Run all[] = {{1, BroadphaseType::SweepAndPrune},
                     {2, BroadphaseType::AllPairs},
                     {2, BroadphaseType::SweepAndPrune},
                     {1, BroadphaseType::AllPairs}};
  const int runs = test::kSanitized || kNativeBuild ? 1 : 4;
  const uint64_t first = hash_after(scene, all[0].threads, all[0].broadphase);
  if (kCompareConstants) {
    EXPECT_EQ(hex(first), hex(golden().at(scene)))
        << scene << ": the behaviour changed; if deliberately, update the constant";
  }
  for (int k = 1; k < runs; ++k) {
    EXPECT_EQ(hex(hash_after(scene, all[k].threads, all[k].broadphase)), hex(first))
        << scene << " with " << all[k].threads << " threads, "
        << (all[k].broadphase == BroadphaseType::AllPairs ? "all-pairs" : "sap");
  }
}

// Every SIMD path this CPU runs (ELAN_SIMD forces one: solver/solver_kernels.hpp) gives the
// scene's constant, at one thread with the sweep. The path a world gets by default is not run
// again: the test above checked its hash against the same constant.
TEST_P(GoldenHash, SameHashOnEverySimdPath) {
  const std::string scene = GetParam();
  const char* const saved = std::getenv("ELAN_SIMD");
  const std::string restore = saved ? saved : "";
  const SimdPath checked_above = World(WorldDef{}).simd_path();
  std::vector<SimdPath> paths;
  for (const SimdPath path : {SimdPath::Sse2, SimdPath::Avx2, SimdPath::Avx512, SimdPath::Native}) {
    WorldDef def;
    def.simd = path;
    try {
      World probe(def);
      EXPECT_EQ(probe.simd_path(), path);
      paths.push_back(path);
    } catch (const Error&) {
      // not in this build, or not on this CPU
    }
  }
  ASSERT_GE(paths.size(), 1u);
  // A build with one path (native, sanitized, double) runs it in the test above.
  if (paths.size() == 1) GTEST_SKIP() << "one SIMD path in this build";
  int ran = 0;
  std::map<std::string, uint64_t> hashes;
  for (const SimdPath path : paths) {
    if (kCompareConstants && path == checked_above) continue;
    ::setenv("ELAN_SIMD", simd_path_name(path), 1);
    hashes[simd_path_name(path)] = hash_after(scene, 1, BroadphaseType::SweepAndPrune);
    ++ran;
  }
  if (saved) {
    ::setenv("ELAN_SIMD", restore.c_str(), 1);
  } else {
    ::unsetenv("ELAN_SIMD");
  }
  ASSERT_GE(ran, 1);
  for (const auto& [name, h] : hashes) {
    if (kCompareConstants) {
      EXPECT_EQ(hex(h), hex(golden().at(scene))) << scene << " on " << name;
    }
    EXPECT_EQ(hex(h), hex(hashes.begin()->second)) << scene << " on " << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, GoldenHash,
                         ::testing::Values("chains", "joint_grid", "joints_demo", "ragdolls",
                                           "jolt_pyramid", "many_pyramids", "pile10k", "pile1k",
                                           "pile4k", "pyramid10", "pyramid20", "rain",
                                           "spheres_in_box", "tower20", "tumbler", "compounds",
                                           "convex_vs_mesh", "geometry_demo", "heightfield_rain"));

// Every scene in scenes/ has a golden hash, so a scene added without one fails here.
TEST(GoldenHash, EveryStandardSceneHasAConstant) {
  for (const auto& entry : std::filesystem::directory_iterator(ELAN_SCENE_DIR)) {
    if (entry.path().extension() != ".json") continue;
    const std::string stem = entry.path().stem().string();
    EXPECT_TRUE(golden().count(stem)) << entry.path().filename() << " has no golden hash";
  }
}

}  // namespace golden_hashes_test
}  // namespace elan
