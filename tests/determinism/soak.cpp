// SPDX-License-Identifier: MIT
// Soak: thousands of random API operations (bodies and joints created and destroyed, forces,
// impulses, velocities, teleports, kinematic moves, masses and materials, sleep and wake, joint
// settings, snapshots restored over the running worlds, rollbacks, ray and box queries)
// interleaved with steps, applied alike to a 1-thread and a 2-thread world. After every step:
// nothing non-finite, the same state hash in both, the same joints; a snapshot taken now and a
// rollback restored now continue as the world does. Three seeds, so that a change to the engine
// that happens to dodge one sequence still meets the others.
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "elan/snapshot.hpp"
#include "physics/physics_util.hpp"

namespace elan {
namespace soak_test {

// A fixed generator whose stream is the same on every platform (std::mt19937 is, but the
// standard distributions are not).
struct Random {
  uint64_t state;
  uint32_t next() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return uint32_t(state >> 33);
  }
  uint32_t below(uint32_t n) { return next() % n; }
  Real between(Real lo, Real hi) {
    return lo + (hi - lo) * Real(next() & 0xFFFFFF) / Real(0x1000000);
  }
  Vec3 in_box(Real half) {
    return {between(-half, half), between(-half, half), between(-half, half)};
  }
};

// The two worlds under test, and the same call made on both: each either succeeds in both or
// throws elan::Error in both.
struct Twins {
  World one, two;
  std::vector<ShapeId> shapes_one, shapes_two;

  template <class F>
  void both(F&& f) {
    bool threw_one = false, threw_two = false;
    try {
      f(one, shapes_one);
    } catch (const Error&) {
      threw_one = true;
    }
    try {
      f(two, shapes_two);
    } catch (const Error&) {
      threw_two = true;
    }
    ASSERT_EQ(threw_one, threw_two);
  }
};

WorldDef world_def(int threads) {
  WorldDef def;
  def.threads = threads;
  return def;
}

std::vector<ShapeId> make_shapes(World& w) {
  std::vector<ShapeId> out;
  out.push_back(w.create_shape(test::sphere_shape(Real(0.3))));
  out.push_back(w.create_shape(test::box_shape(Vec3(Real(0.4), Real(0.2), Real(0.3)))));
  out.push_back(w.create_shape(test::capsule_shape(Real(0.15), Real(0.3))));
  ShapeDef hull;
  hull.type = ShapeType::ConvexHull;
  hull.points = {{0, 0, 0},
                 {Real(0.6), 0, 0},
                 {0, Real(0.5), 0},
                 {0, 0, Real(0.4)},
                 {Real(0.3), Real(0.3), Real(0.3)}};
  out.push_back(w.create_shape(hull));
  return out;
}

void expect_finite(const World& w) {
  ASSERT_TRUE(test::all_finite(w));
  for (std::size_t k = 0; k < w.joint_count(); ++k) {
    const JointId j = w.joint_at(k);
    ASSERT_TRUE(w.joint_force(j).allFinite());
    ASSERT_TRUE(w.joint_torque(j).allFinite());
    ASSERT_TRUE(std::isfinite(w.joint_coordinate(j)));
  }
}

class Soak : public testing::TestWithParam<uint64_t> {};

TEST_P(Soak, RandomOperationsKeepBothWorldsAlikeFiniteAndRestorable) {
  Twins t{World(world_def(1)), World(world_def(2)), {}, {}};
  t.shapes_one = make_shapes(t.one);
  t.shapes_two = make_shapes(t.two);
  t.both([](World& w, std::vector<ShapeId>&) { test::add_ground(w); });
  Random rng{GetParam()};
  const int operations = test::kSanitized ? 1500 : 4000;
  std::optional<std::vector<uint8_t>> rollback;
  int steps = 0;
  for (int op = 0; op < operations; ++op) {
    SCOPED_TRACE(testing::Message() << "operation " << op);
    const uint32_t kind = rng.below(100);
    const std::size_t bodies = t.one.body_count();
    const uint32_t pick = rng.next(), pick2 = rng.next();
    auto body_at = [&](World& w, uint32_t p) { return w.body_at(1 + p % (bodies - 1)); };
    if (kind < 20 && bodies < 150) {
      // A body: mostly dynamic, sometimes kinematic or static, somewhere above the ground.
      const uint32_t shape = rng.below(4);
      const uint32_t motion = rng.below(10);
      BodyDef d;
      d.position = Vec3(rng.between(-4, 4), rng.between(Real(0.5), 6), rng.between(-4, 4));
      d.orientation = Quat(rng.between(-1, 1), rng.between(-1, 1), rng.between(-1, 1), 1);
      d.linear_velocity = rng.in_box(3);
      d.angular_velocity = rng.in_box(5);
      d.motion = motion == 0   ? MotionType::Static
                 : motion == 1 ? MotionType::Kinematic
                               : MotionType::Dynamic;
      t.both([&](World& w, std::vector<ShapeId>& s) {
        BodyDef def = d;
        def.shape = s[shape];
        w.create_body(def);
      });
    } else if (kind < 26 && bodies > 1) {
      t.both([&](World& w, std::vector<ShapeId>&) { w.destroy_body(body_at(w, pick)); });
    } else if (kind < 44 && bodies > 2) {
      // A joint of a random kind between two bodies, or a body and the world.
      const JointType type = JointType(rng.below(6));
      const bool to_world = rng.below(4) == 0;
      const Vec3 axis = rng.in_box(1) + Vec3(0, Real(0.1), 0);
      const Real lo = rng.between(-1, 0), hi = rng.between(0, 1);
      const bool limits = rng.below(2) == 0, motor = rng.below(3) == 0;
      const Real breaking = rng.below(4) == 0 ? rng.between(10, 2000) : Real(0);
      t.both([&](World& w, std::vector<ShapeId>&) {
        JointDef j;
        j.type = type;
        j.body_a = body_at(w, pick);
        j.body_b = to_world ? BodyId{} : body_at(w, pick2);
        // Between the bodies (a kinematic body's joints drag what they hold, as users use them).
        const Vec3 pa = w.position(j.body_a);
        const Vec3 pb = j.body_b.is_null() ? pa + Vec3(0, 1, 0) : w.position(j.body_b);
        j.anchor = (pa + pb) / 2;
        j.anchor_b = pb;
        j.axis = axis;
        j.limits = {limits, type == JointType::Slider ? lo : lo * 2, hi * 2};
        j.motor = {motor, hi * 3, 50};
        j.swing_limit = hi * 2;
        j.friction = Real(0.1) * hi;
        if (breaking > 0) j.break_force = breaking;
        w.create_joint(j);
      });
    } else if (kind < 48 && t.one.joint_count() > 0) {
      const std::size_t k = pick % t.one.joint_count();
      t.both([&](World& w, std::vector<ShapeId>&) { w.destroy_joint(w.joint_at(k)); });
    } else if (kind < 52 && t.one.joint_count() > 0) {
      const std::size_t k = pick % t.one.joint_count();
      const Real speed = rng.between(-4, 4);
      t.both([&](World& w, std::vector<ShapeId>&) {
        const JointId j = w.joint_at(k);
        w.set_joint_motor(j, {true, speed, 20});
        w.set_joint_limits(j, {true, Real(-0.5), Real(0.5)});
      });
    } else if (kind < 62 && bodies > 1) {
      const Vec3 f = rng.in_box(200), point = rng.in_box(Real(0.3));
      const uint32_t what = rng.below(4);
      t.both([&](World& w, std::vector<ShapeId>&) {
        const BodyId b = body_at(w, pick);
        if (what == 0) w.apply_force(b, f);
        if (what == 1) w.apply_impulse(b, f * Real(0.05), w.center_of_mass(b) + point);
        if (what == 2) w.apply_torque(b, f);
        if (what == 3) w.set_linear_velocity(b, f * Real(0.02));
      });
    } else if (kind < 66 && bodies > 1) {
      const bool sleep = rng.below(2) == 0;
      t.both([&](World& w, std::vector<ShapeId>&) {
        const BodyId b = body_at(w, pick);
        if (w.motion_type(b) != MotionType::Dynamic) return;
        if (sleep) {
          w.sleep(b);
        } else {
          w.wake(b);
        }
      });
    } else if (kind < 72 && bodies > 1) {
      // Teleports, kinematic moves, spins, impulses, masses and materials.
      const uint32_t what = rng.below(7);
      const Vec3 to = Vec3(rng.between(-4, 4), rng.between(Real(0.5), 5), rng.between(-4, 4));
      const Quat q =
          Quat(rng.between(-1, 1), rng.between(-1, 1), rng.between(-1, 1), 1).normalized();
      const Vec3 v = rng.in_box(4);
      const Real x = rng.between(Real(0.05), 5);
      t.both([&](World& w, std::vector<ShapeId>&) {
        const BodyId b = body_at(w, pick);
        const MotionType m = w.motion_type(b);
        if (what == 0 && m != MotionType::Static) w.set_transform(b, {to, q});
        if (what == 1 && m == MotionType::Kinematic) w.move_kinematic(b, {to, q}, test::kDt);
        if (what == 2) w.set_angular_velocity(b, v);
        if (what == 3) {
          w.apply_linear_impulse(b, v);
          w.apply_angular_impulse(b, v * Real(0.1));
        }
        if (what == 4 && m == MotionType::Dynamic) w.set_mass(b, x);
        if (what == 5) w.set_friction(b, x / 5);
        if (what == 6) w.set_restitution(b, x / 5);
      });
    } else if (kind < 73) {
      // Queries agree between the worlds: every hit along a ray, every box in a region.
      const Vec3 origin = rng.in_box(5) + Vec3(0, 3, 0), direction = rng.in_box(1);
      std::vector<RayHit> ha, hb;
      t.one.cast_ray_all(origin, direction, 30, ha);
      t.two.cast_ray_all(origin, direction, 30, hb);
      ASSERT_EQ(ha.size(), hb.size());
      for (std::size_t k = 0; k < ha.size(); ++k) {
        EXPECT_EQ(ha[k].body, hb[k].body);
        EXPECT_EQ(ha[k].distance, hb[k].distance);
      }
      const Vec3 lo = rng.in_box(4), hi = lo + rng.in_box(2).cwiseAbs();
      std::vector<BodyId> oa, ob;
      t.one.overlap_box(lo, hi, oa);
      t.two.overlap_box(lo, hi, ob);
      EXPECT_EQ(oa, ob);
    } else if (kind < 74) {
      // A snapshot of one world restored over both: they go on alike.
      const std::vector<uint8_t> snap = save_snapshot(t.one);
      t.both([&](World& w, std::vector<ShapeId>&) { restore_snapshot(w, snap); });
      ASSERT_EQ(t.one.state_hash(), t.two.state_hash());
    } else if (kind < 76) {
      // Queries agree between the worlds.
      const Vec3 origin = rng.in_box(5) + Vec3(0, 8, 0), direction = rng.in_box(1) - Vec3(0, 1, 0);
      const std::optional<RayHit> a = t.one.cast_ray(origin, direction, 50);
      const std::optional<RayHit> b = t.two.cast_ray(origin, direction, 50);
      ASSERT_EQ(a.has_value(), b.has_value());
      if (a) {
        EXPECT_EQ(a->body, b->body);
        EXPECT_EQ(a->distance, b->distance);
      }
    } else if (kind < 78) {
      rollback = save_rollback(t.one);
    } else if (kind < 79 && rollback) {
      // A rollback saved before bodies were created or destroyed is refused alike; otherwise
      // both worlds go back to it.
      t.both([&](World& w, std::vector<ShapeId>&) { restore_rollback(w, *rollback); });
    } else {
      t.both([](World& w, std::vector<ShapeId>&) { w.step(test::kDt); });
      ++steps;
      ASSERT_NO_FATAL_FAILURE(expect_finite(t.one));
      ASSERT_EQ(t.one.state_hash(), t.two.state_hash()) << "step " << steps;
      ASSERT_EQ(t.one.joint_count(), t.two.joint_count());
      if (steps % 25 == 0) {
        // A snapshot continues as the world does.
        World copy = load_snapshot(save_snapshot(t.one));
        ASSERT_EQ(copy.state_hash(), t.one.state_hash());
        t.both([](World& w, std::vector<ShapeId>&) { w.step(test::kDt); });
        copy.step(test::kDt);
        ASSERT_EQ(copy.state_hash(), t.one.state_hash());
        ASSERT_EQ(copy.state_hash(), t.two.state_hash());
        ASSERT_EQ(copy.joint_count(), t.one.joint_count());
      }
    }
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(steps, operations / 6);
  EXPECT_GT(t.one.joint_count() + t.one.body_count(), 10u);
}

INSTANTIATE_TEST_SUITE_P(Seeds, Soak, testing::Values(0x5eedull, 0xc0ffeeull, 0xfacadeull));

}  // namespace soak_test
}  // namespace elan
