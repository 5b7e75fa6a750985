// SPDX-License-Identifier: MIT
// Scene queries from many threads at once, between steps: each thread gets what one thread got
// alone. A file of the stage area so that the ThreadSanitizer build of the test command (which
// builds the threaded areas, not physics) runs it.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

#include "core/base/tbb_hand_off.hpp"
#include "elan/world.hpp"
#include "physics/query_worlds.hpp"

namespace elan {
namespace queries_threads_test {

using namespace query_worlds;

// Eight threads query one world at once; each gets what one thread got alone.
TEST(QueryThreads, EightThreadsGetTheAnswersOfOne) {
  const World w = random_world(11, 500, 2);
  std::mt19937 rng(12);
  std::vector<RandomRay> rays(300);
  for (RandomRay& r : rays) r = random_ray(rng);
  const auto answer = [&](std::vector<Real>& out) {
    out.clear();
    std::vector<RayHit> all;
    std::vector<BodyId> over;
    for (const RandomRay& r : rays) {
      const auto h = w.cast_ray(r.origin, r.dir, 40);
      out.push_back(h ? h->distance + Real(h->body.slot) : -1);
      w.cast_ray_all(r.origin, r.dir, 40, all);
      out.push_back(Real(all.size()));
      w.overlap_shape(ShapeId{1}, {r.origin, Quat::Identity()}, over);
      out.push_back(Real(over.size()));
      const auto c = w.cast_shape(ShapeId{0}, {r.origin, Quat::Identity()}, r.dir * 5);
      out.push_back(c ? c->fraction : -1);
    }
    std::vector<Ray> batch(rays.size());
    for (std::size_t k = 0; k < rays.size(); ++k) batch[k] = {rays[k].origin, rays[k].dir, 40};
    std::vector<RayHit> hits(batch.size());
#if defined(ELAN_THREAD_SANITIZER)
    // Under TSan the batched calls take turns (the single queries above still overlap them):
    // oneTBB reuses a task's memory for another external thread's task inside libtbb, which is
    // not instrumented, so TSan reports that reuse as a race within TBB's own task objects.
    static std::mutex one_batch_at_a_time;
    const std::lock_guard<std::mutex> lock(one_batch_at_a_time);
#endif
    w.cast_rays(batch, hits);
    for (const RayHit& h : hits) out.push_back(h.distance);
  };
  std::vector<Real> one;
  answer(one);
  std::vector<std::vector<Real>> many(8);
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) threads.emplace_back([&, t] { answer(many[t]); });
  for (std::thread& t : threads) t.join();
  for (int t = 0; t < 8; ++t) EXPECT_EQ(many[t], one) << "thread " << t;
}

// The first queries after steps refit the leaves of the bodies the steps moved (query_tree.hpp):
// eight threads start querying at once right after the steps, so they race to that refit, which
// one of them does under the tree's lock while the others wait. Each gets what one thread got from
// a twin world stepped alike.
TEST(QueryThreads, EightThreadsRacingToTheFirstQueryAfterStepsGetTheAnswersOfOne) {
  World alone = random_world(13, 400, 2);
  World shared = random_world(13, 400, 2);
  for (int n = 0; n < 20; ++n) {
    alone.step(Real(1) / 60);
    shared.step(Real(1) / 60);
  }
  std::mt19937 rng(14);
  std::vector<RandomRay> rays(200);
  for (RandomRay& r : rays) r = random_ray(rng);
  const auto answer = [&](const World& w, std::vector<Real>& out) {
    std::vector<BodyId> over;
    for (const RandomRay& r : rays) {
      const auto h = w.cast_ray(r.origin, r.dir, 40);
      out.push_back(h ? h->distance + Real(h->body.slot) : -1);
      w.overlap_shape(ShapeId{1}, {r.origin, Quat::Identity()}, over);
      out.push_back(Real(over.size()));
    }
  };
  std::vector<Real> one;
  answer(alone, one);
  std::vector<std::vector<Real>> many(8);
  std::atomic<int> ready{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&, t] {
      ready.fetch_add(1);
      while (ready.load() < 8) std::this_thread::yield();
      answer(shared, many[t]);
    });
  }
  for (std::thread& t : threads) t.join();
  for (int t = 0; t < 8; ++t) EXPECT_EQ(many[t], one) << "thread " << t;
}

}  // namespace queries_threads_test
}  // namespace elan
