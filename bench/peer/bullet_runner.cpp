// SPDX-License-Identifier: MIT
// bullet_runner SCENE.json [--steps N]: steps a scene file in Bullet 3 alone in its process and
// prints one JSON object like `elan run` does, so peak RSS and time can be compared process to
// process.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#if defined(__GLIBC__)
#include <malloc.h>  // mallopt
#endif

#include "bench/peer/bullet_world.hpp"

int main(int argc, char** argv) {
#if defined(__GLIBC__)
  // The allocator policy of `elan run` (tools/elan_main.cpp), so the two peaks stay comparable.
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif
  if (argc < 2) {
    std::fprintf(stderr, "usage: bullet_runner SCENE.json [--steps N]\n");
    return 2;
  }
  const std::string path = argv[1];
  long steps = 600;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    char* end = nullptr;
    if (a == "--steps" && i + 1 < argc) {
      steps = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || steps < 1) {
        std::fprintf(stderr, "bullet_runner: --steps: expected a positive integer\n");
        return 2;
      }
    } else {
      std::fprintf(stderr, "bullet_runner: unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  try {
    // As `elan run` does, only the world is held while stepping: the parsed scene is freed.
    auto scene = std::make_unique<elan::Scene>(elan::load_scene(path));
    elan::peer::BulletWorld world(*scene);
    scene.reset();
    const auto t0 = std::chrono::steady_clock::now();
    for (long s = 0; s < steps; ++s) world.step();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const elan::peer::BulletCounts c = world.counts();
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf(
        "{\"engine\": \"bullet\", \"bodies\": %zu, \"steps\": %ld, \"threads\": 1, "
        "\"wall_seconds\": %.6f, \"ms_per_step\": %.6f, \"manifolds\": %zu, \"contacts\": %zu, "
        "\"awake\": %zu, \"joints\": %zu, \"peak_rss_kib\": %ld}\n",
        world.body_count(), steps, seconds, 1000 * seconds / double(steps), c.manifolds, c.contacts,
        c.awake, world.joint_count(), long(usage.ru_maxrss));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
