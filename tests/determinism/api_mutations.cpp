// SPDX-License-Identifier: MIT
// The embedding API keeps determinism: creating and destroying bodies mid-run (in contact and
// asleep), shared thread pools and caller arenas, and many worlds stepped at once give the same
// bits as the plain runs.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <vector>

#include "elan/elan.hpp"
#include "elan/tbb_interop.hpp"

namespace elan {
namespace api_mutations_test {

constexpr Real kDt = Real(1.0 / 60.0);

struct Scene {
  ShapeId ground, box, ball;
  std::vector<BodyId> bodies;
};

// A floor with a small pile of boxes and balls; `salt` varies the layout between worlds.
Scene build_pile(World& world, int count, int salt = 0) {
  Scene s;
  ShapeDef ground;
  ground.type = ShapeType::Box;
  ground.half_extents = Vec3(20, 1, 20);
  ShapeDef box;
  box.type = ShapeType::Box;
  box.half_extents = Vec3(Real(0.4), Real(0.3), Real(0.5));
  ShapeDef ball;
  ball.type = ShapeType::Sphere;
  ball.radius = Real(0.35);
  s.ground = world.create_shape(ground);
  s.box = world.create_shape(box);
  s.ball = world.create_shape(ball);
  BodyDef floor;
  floor.motion = MotionType::Static;
  floor.shape = s.ground;
  floor.position = Vec3(0, -1, 0);
  s.bodies.push_back(world.create_body(floor));
  for (int k = 0; k < count; ++k) {
    BodyDef def;
    def.shape = (k + salt) % 3 == 0 ? s.ball : s.box;
    def.position = Vec3(Real((k % 4) - 1.5) * Real(1.1) + Real(0.01) * Real(salt),
                        Real(0.5 + 0.8 * (k / 4)), Real(((k / 2) % 3) - 1) * Real(0.2));
    def.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.1) * Real(k), Vec3::UnitY()));
    def.restitution = Real(0.1) * Real(k % 3);
    s.bodies.push_back(world.create_body(def));
  }
  return s;
}

// 240 steps with API calls in between: destroys a touching body, one asleep, adds bodies,
// pushes, teleports. Returns the hash after every step.
std::vector<uint64_t> run_mutating(int threads, BroadphaseType broadphase) {
  WorldDef def;
  def.threads = threads;
  def.broadphase = broadphase;
  World world(def);
  Scene s = build_pile(world, 24);
  std::vector<uint64_t> hashes;
  for (int step = 0; step < 240; ++step) {
    if (step == 40) world.destroy_body(s.bodies[3]);  // in contact
    if (step == 60) {
      BodyDef def2;
      def2.shape = s.ball;
      def2.position = Vec3(0, 6, 0);
      s.bodies.push_back(world.create_body(def2));
    }
    if (step == 80) world.apply_impulse(s.bodies[5], Vec3(1, 2, 0), Vec3(0, 1, 0));
    if (step == 100) {
      world.destroy_body(s.bodies[1]);  // lowest index: the last body moves into it
      BodyDef def2;
      def2.shape = s.box;
      def2.position = Vec3(1, 5, 1);
      s.bodies.push_back(world.create_body(def2));  // count back to where it was
    }
    if (step == 150) world.set_position(s.bodies[7], Vec3(2, 3, -1));
    if (step == 200) {
      // By now the pile sleeps: destroy a sleeping body holding others up.
      world.destroy_body(s.bodies[2]);
    }
    world.step(kDt);
    hashes.push_back(world.state_hash());
  }
  return hashes;
}

TEST(WorldApi, MutationsAreDeterministicAcrossThreadsAndBroadphases) {
  const std::vector<uint64_t> base = run_mutating(1, BroadphaseType::SweepAndPrune);
  EXPECT_EQ(run_mutating(2, BroadphaseType::SweepAndPrune), base);
  EXPECT_EQ(run_mutating(2, BroadphaseType::AllPairs), base);
  EXPECT_EQ(run_mutating(2, BroadphaseType::Tree), base);
  EXPECT_EQ(run_mutating(1, BroadphaseType::SweepAndPrune), base);  // twice in one process
}

TEST(WorldApi, CallerArenaGivesTheSameBitsAsOwnArena) {
  tbb::task_arena arena(2);
  ThreadPool pool = wrap_tbb_arena(arena);
  EXPECT_EQ(pool.threads(), 2);
  WorldDef with_arena;
  with_arena.thread_pool = &pool;
  World a(with_arena), b(WorldDef{});
  build_pile(a, 16);
  build_pile(b, 16);
  for (int k = 0; k < 60; ++k) {
    a.step(kDt);
    b.step(kDt);
    ASSERT_EQ(a.state_hash(), b.state_hash()) << "step " << k;
  }
}

TEST(WorldApi, SharedThreadPoolGivesTheSameBitsAsOwnPool) {
  ThreadPool pool(2);
  EXPECT_EQ(pool.threads(), 2);
  WorldDef shared;
  shared.thread_pool = &pool;
  World a(shared), b(shared), alone(WorldDef{});
  build_pile(a, 16);
  build_pile(b, 16, 1);
  build_pile(alone, 16);
  for (int k = 0; k < 60; ++k) {
    a.step(kDt);
    b.step(kDt);
    alone.step(kDt);
    ASSERT_EQ(a.state_hash(), alone.state_hash()) << "step " << k;
  }
  EXPECT_NE(a.state_hash(), b.state_hash());
  // Back to a pool of its own: the same bits go on.
  a.set_threads(1);
  EXPECT_EQ(a.settings().thread_pool, nullptr);
  a.step(kDt);
  alone.step(kDt);
  EXPECT_EQ(a.state_hash(), alone.state_hash());
}

TEST(ThreadPool, RejectsAThreadCountOutOfRange) {
  EXPECT_THROW(ThreadPool(-1), Error);
  EXPECT_THROW(ThreadPool(1025), Error);
  EXPECT_GE(ThreadPool(0).threads(), 1);
}

TEST(StepAll, EachWorldMatchesSteppingItAlone) {
  constexpr int kWorlds = 6;
  std::vector<World> many, alone;
  for (int k = 0; k < kWorlds; ++k) {
    WorldDef def;
    def.threads = 1 + k % 2;
    many.emplace_back(def);
    alone.emplace_back(def);
    build_pile(many.back(), 8 + k, k);
    build_pile(alone.back(), 8 + k, k);
  }
  std::vector<World*> ptrs;
  for (World& w : many) ptrs.push_back(&w);
  tbb::task_arena arena(2);
  ThreadPool pool(2);
  for (int step = 0; step < 90; ++step) {
    // Both ways of choosing the threads: the caller's current arena and an elan pool.
    if (step % 2 == 0) {
      arena.execute([&] { step_all(ptrs, kDt); });
    } else {
      step_all(ptrs, kDt, &pool);
    }
    for (World& w : alone) w.step(kDt);
  }
  for (int k = 0; k < kWorlds; ++k) {
    EXPECT_EQ(many[k].state_hash(), alone[k].state_hash()) << "world " << k;
  }
  // The worlds differ, so equality is not trivially the same hash everywhere.
  EXPECT_NE(many[0].state_hash(), many[1].state_hash());
}

}  // namespace api_mutations_test
}  // namespace elan
