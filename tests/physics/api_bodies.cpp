// SPDX-License-Identifier: MIT
// Body lifetime and control through the embedding API: stale ids, destroy with contacts and
// events, per-body setters against closed forms, bulk views and setters against per-body calls.
#include <gtest/gtest.h>

#include <vector>

#include "core/world/world_access.hpp"
#include "elan/elan.hpp"

namespace elan {
namespace api_bodies_test {

constexpr Real kDt = Real(1.0 / 60.0);

ShapeId make_box(World& w, const Vec3& h) {
  ShapeDef s;
  s.type = ShapeType::Box;
  s.half_extents = h;
  return w.create_shape(s);
}

BodyId add(World& w, ShapeId shape, const Vec3& p, MotionType motion = MotionType::Dynamic) {
  BodyDef d;
  d.shape = shape;
  d.position = p;
  d.motion = motion;
  return w.create_body(d);
}

TEST(WorldApi, StaleIdsAreReportedAfterDestroyAndSlotReuse) {
  World w;
  const ShapeId box = make_box(w, Vec3::Constant(Real(0.5)));
  const BodyId a = add(w, box, Vec3(0, 0, 0));
  const BodyId b = add(w, box, Vec3(3, 0, 0));
  w.destroy_body(a);
  EXPECT_FALSE(w.is_valid(a));
  EXPECT_THROW(w.position(a), Error);
  EXPECT_THROW(w.destroy_body(a), Error);
  const BodyId c = add(w, box, Vec3(6, 0, 0));
  EXPECT_EQ(c.slot, a.slot);  // slot reused, generation differs
  EXPECT_FALSE(w.is_valid(a));
  EXPECT_TRUE(w.is_valid(b) && w.is_valid(c));
  EXPECT_EQ(w.position(b), Vec3(3, 0, 0));  // b moved to index 0 and is still found
  EXPECT_EQ(w.position(c), Vec3(6, 0, 0));
  try {
    w.set_linear_velocity(a, Vec3::Zero());
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "body");
  }
}

// reserve() is a capacity hint: bodies and shapes up to it fit without the store growing, past it
// the world still grows, and absurd counts are refused naming the argument.
TEST(WorldApi, ReserveMakesRoomAndRejectsImpossibleCounts) {
  World w;
  w.reserve(100, 3);
  const ShapeId box = make_box(w, Vec3(0.5, 0.5, 0.5));
  const Real* px = nullptr;
  for (int i = 0; i < 100; ++i) {
    add(w, box, Vec3(Real(2 * i), 0, 0));
    if (i == 0) px = w.body_columns().px.data();
  }
  // The position column never moved: no reallocation up to the reserved count.
  EXPECT_EQ(w.body_columns().px.data(), px);
  add(w, box, Vec3(-5, 0, 0));
  EXPECT_EQ(w.body_count(), 101u);
  EXPECT_EQ(w.body_columns().px[100], Real(-5));
  // A world holds at most 2^29 bodies (their indices share a word with a manifold's point count).
  try {
    w.reserve((std::size_t{1} << 29) + 1, 1);
    ADD_FAILURE() << "reserve of 2^29 + 1 bodies accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "bodies");
  }
  try {
    w.reserve(1, std::size_t(UINT32_MAX) + 5);
    ADD_FAILURE() << "reserve of 2^32 + 4 shapes accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "shapes");
  }
}

TEST(WorldApi, ShapeInUseCannotBeDestroyedAndDestroyedShapeIsInvalid) {
  World w;
  const ShapeId box = make_box(w, Vec3::Constant(1));
  const BodyId a = add(w, box, Vec3::Zero());
  EXPECT_THROW(w.destroy_shape(box), Error);
  w.destroy_body(a);
  w.destroy_shape(box);
  EXPECT_FALSE(w.is_valid(box));
  EXPECT_THROW(add(w, box, Vec3::Zero()), Error);
  EXPECT_THROW(w.destroy_shape(box), Error);
}

TEST(WorldApi, DestroyingATouchingBodyDropsItsContactsWithEndEvents) {
  World w;
  const ShapeId ground = make_box(w, Vec3(10, 1, 10));
  const ShapeId box = make_box(w, Vec3::Constant(Real(0.5)));
  const BodyId floor = add(w, ground, Vec3(0, -1, 0), MotionType::Static);
  const BodyId low = add(w, box, Vec3(0, Real(0.5), 0));
  const BodyId high = add(w, box, Vec3(0, Real(1.5), 0));
  const BodyId other = add(w, box, Vec3(5, Real(0.5), 0));
  for (int k = 0; k < 30; ++k) w.step(kDt);
  ASSERT_EQ(w.last_step().manifolds, 3u);  // floor-low, low-high, floor-other
  w.destroy_body(low);
  ASSERT_EQ(w.contact_end_events().size(), 2u);
  for (const ContactEndEvent& e : w.contact_end_events()) {
    EXPECT_TRUE(e.body_a == low || e.body_b == low);
    EXPECT_TRUE(e.body_a == floor || e.body_b == floor || e.body_a == high || e.body_b == high);
  }
  // The manifolds' tails and body pair cache went with them: only floor-other is left, renamed
  // with `other`, which took `low`'s index (a box resting on a face has four points, and boxes
  // keep their poses).
  const detail::WorldState& s = detail::state_of(w);
  ASSERT_EQ(s.contacts.size(), 1u);
  ASSERT_EQ(s.contacts.heads()[0].point_count, 4u);
  ASSERT_EQ(s.contacts.tails().size(), 1u);
  EXPECT_EQ(s.contacts.tails()[0].key, s.contacts.heads()[0].key());
  ASSERT_EQ(s.contacts.pair_cache().size(), 1u);
  EXPECT_EQ(s.contacts.pair_cache()[0].key, s.contacts.heads()[0].key());
  // `high` now falls 1 m onto the floor; `other` keeps resting on it; nothing refers to `low`.
  for (int k = 0; k < 60; ++k) w.step(kDt);
  EXPECT_NEAR(w.position(high).y(), 0.5, 0.02);
  EXPECT_NEAR(w.position(other).y(), 0.5, 0.02);
  EXPECT_EQ(w.last_step().manifolds, 2u);
}

TEST(WorldApi, ImpulseAndForceMatchClosedForms) {
  WorldDef def;
  def.gravity = Vec3::Zero();
  World w(def);
  const Vec3 h(Real(0.5), Real(1), Real(1.5));
  BodyDef d;
  d.shape = make_box(w, h);
  d.mass = 6;
  const BodyId id = w.create_body(d);
  // Box inertia about x: m (hy^2 + hz^2) / 3 with half extents (full sizes 2h: m (4hy^2+4hz^2)/12).
  const Real ix = 6 * (h.y() * h.y() + h.z() * h.z()) / 3;
  w.apply_impulse(id, Vec3(0, 0, 3), Vec3(0, 1, 0));
  EXPECT_NEAR(w.linear_velocity(id).z(), 0.5, 1e-6);
  // r x J = (0,1,0) x (0,0,3) = (3,0,0).
  EXPECT_NEAR(w.angular_velocity(id).x(), 3 / ix, 1e-5);
  w.set_linear_velocity(id, Vec3::Zero());
  w.set_angular_velocity(id, Vec3::Zero());
  w.apply_force(id, Vec3(12, 0, 0));  // a = 2 m/s^2 for one step only
  w.step(kDt);
  EXPECT_NEAR(w.linear_velocity(id).x(), 2 * kDt, 1e-5);
  w.step(kDt);
  EXPECT_NEAR(w.linear_velocity(id).x(), 2 * kDt, 1e-5);  // cleared after the step
  w.set_mass(id, 12);
  EXPECT_NEAR(w.mass(id), 12, 1e-5);
}

// Forces are kept by body, so removing bodies (each removal moves the last body into the gap)
// must leave every force with its own body: a = F / m for one step, each on its own axis.
TEST(WorldApi, ForcesStayWithTheirBodiesWhenOthersAreDestroyed) {
  WorldDef def;
  def.gravity = Vec3::Zero();
  World w(def);
  const ShapeId box = make_box(w, Vec3::Constant(Real(0.5)));
  std::vector<BodyId> ids;
  for (int k = 0; k < 4; ++k) ids.push_back(add(w, box, Vec3(Real(3 * k), 0, 0)));
  const Real mass = w.mass(ids[0]);
  w.apply_force(ids[1], Vec3(mass, 0, 0));      // 1 m/s^2 along x
  w.apply_force(ids[2], Vec3(0, 2 * mass, 0));  // 2 m/s^2 along y
  w.apply_torque(ids[2], Vec3(0, 0, Real(1e-3)));
  w.apply_force(ids[3], Vec3(0, 0, 4 * mass));  // 4 m/s^2 along z
  w.destroy_body(ids[0]);  // no force; the last body, with one, takes its index
  w.destroy_body(ids[1]);  // has a force; the last body then takes its index
  w.step(kDt);
  EXPECT_NEAR(w.linear_velocity(ids[2]).y(), 2 * kDt, 1e-6);
  EXPECT_NEAR(w.linear_velocity(ids[2]).x(), 0, 1e-9);
  EXPECT_GT(w.angular_velocity(ids[2]).z(), 0);
  EXPECT_NEAR(w.linear_velocity(ids[3]).z(), 4 * kDt, 1e-6);
  EXPECT_NEAR(w.linear_velocity(ids[3]).x(), 0, 1e-9);
  EXPECT_EQ(detail::state_of(w).bodies.applied_forces.size(), 0u) << "spent by the step";
  w.step(kDt);
  EXPECT_NEAR(w.linear_velocity(ids[2]).y(), 2 * kDt, 1e-6);
  EXPECT_NEAR(w.linear_velocity(ids[3]).z(), 4 * kDt, 1e-6);
}

// Bodies made alike share their traits' entry; changing one body's must leave the others'.
TEST(WorldApi, ChangingOneBodysMaterialOrFilterLeavesTheOthers) {
  World w;
  const ShapeId box = make_box(w, Vec3::Constant(Real(0.5)));
  std::vector<BodyId> ids;
  for (int k = 0; k < 3; ++k) ids.push_back(add(w, box, Vec3(Real(3 * k), 0, 0)));
  w.set_friction(ids[1], Real(0.9));
  w.set_restitution(ids[2], Real(0.4));
  w.set_collision_filter(ids[0], 2, 4);
  EXPECT_EQ(w.friction(ids[0]), BodyDef{}.friction);
  EXPECT_EQ(w.friction(ids[1]), Real(0.9));
  EXPECT_EQ(w.friction(ids[2]), BodyDef{}.friction);
  EXPECT_EQ(w.restitution(ids[1]), 0);
  EXPECT_EQ(w.restitution(ids[2]), Real(0.4));
  EXPECT_EQ(w.category_bits(ids[0]), 2u);
  EXPECT_EQ(w.mask_bits(ids[0]), 4u);
  EXPECT_EQ(w.category_bits(ids[1]), 1u);
  EXPECT_EQ(w.mask_bits(ids[2]), UINT32_MAX);
  w.destroy_body(ids[0]);
  EXPECT_EQ(w.friction(ids[1]), Real(0.9));
  EXPECT_EQ(w.restitution(ids[2]), Real(0.4));
  EXPECT_EQ(w.category_bits(ids[2]), 1u);
  EXPECT_LE(detail::state_of(w).bodies.trait_table.entries().size(), 5u);
}

TEST(WorldApi, MoveKinematicReachesTheTargetInOneStep) {
  WorldDef def;
  def.gravity = Vec3::Zero();
  World w(def);
  const BodyId id =
      add(w, make_box(w, Vec3::Constant(Real(0.5))), Vec3(1, 2, 3), MotionType::Kinematic);
  const Transform target{Vec3(2, 2, 2), Quat(Eigen::AngleAxis<Real>(Real(0.3), Vec3::UnitZ()))};
  w.move_kinematic(id, target, kDt);
  w.step(kDt);
  EXPECT_LT((w.position(id) - target.position).norm(), 1e-4);
  EXPECT_LT(w.orientation(id).angularDistance(target.rotation), 1e-3);
  EXPECT_THROW(w.move_kinematic(id, target, 0), Error);
}

TEST(WorldApi, SettersRejectBadValuesNamingTheField) {
  World w;
  const BodyId id = add(w, make_box(w, Vec3::Constant(1)), Vec3::Zero());
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  auto field_of = [](auto&& call) {
    try {
      call();
    } catch (const Error& e) {
      return e.field();
    }
    return std::string("none");
  };
  EXPECT_EQ(field_of([&] { w.set_position(id, Vec3(nan, 0, 0)); }), "position");
  EXPECT_EQ(field_of([&] { w.set_orientation(id, Quat(0, 0, 0, 0)); }), "orientation");
  EXPECT_EQ(field_of([&] { w.set_friction(id, -1); }), "friction");
  EXPECT_EQ(field_of([&] { w.set_restitution(id, nan); }), "restitution");
  EXPECT_EQ(field_of([&] { w.set_mass(id, 0); }), "mass");
  EXPECT_EQ(field_of([&] { w.apply_force(id, Vec3(0, nan, 0)); }), "force");
  EXPECT_EQ(field_of([&] { w.move_kinematic(id, Transform{}, kDt); }), "body");
  std::vector<Real> short_column(0);
  EXPECT_EQ(field_of([&] { w.set_linear_velocities(short_column, short_column, short_column); }),
            "linear_velocities");
}

TEST(WorldApi, SleepAndWake) {
  World w;
  const BodyId id = add(w, make_box(w, Vec3::Constant(1)), Vec3(0, 5, 0));
  w.sleep(id);
  EXPECT_FALSE(w.is_awake(id));
  w.step(kDt);
  EXPECT_EQ(w.position(id).y(), 5);  // asleep: not falling
  w.wake(id);
  w.step(kDt);
  EXPECT_LT(w.position(id).y(), 5);
}

// Two identical worlds, one driven by bulk setters and one by per-body setters.
TEST(WorldApi, BulkViewsAndSettersEqualPerBodyCalls) {
  World bulk, single;
  for (World* w : {&bulk, &single}) {
    const ShapeId box = make_box(*w, Vec3(Real(0.5), Real(0.2), Real(0.3)));
    add(*w, make_box(*w, Vec3(10, 1, 10)), Vec3(0, -1, 0), MotionType::Static);
    for (int k = 0; k < 20; ++k) add(*w, box, Vec3(Real(k % 5), Real(1 + k / 5), 0));
    w->destroy_body(w->body_at(3));  // a swap-remove reorders the dense indices
    for (int k = 0; k < 20; ++k) w->step(kDt);
  }
  const std::size_t n = bulk.body_count();
  const World::BodyColumns c = bulk.body_columns();
  const std::span<const BodyId> ids = bulk.body_ids();
  ASSERT_EQ(ids.size(), n);
  ASSERT_EQ(c.px.size(), n);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(ids[i], bulk.body_at(i));
    EXPECT_EQ(Vec3(c.px[i], c.py[i], c.pz[i]), bulk.center_of_mass(ids[i]));
    EXPECT_EQ(Vec3(c.vx[i], c.vy[i], c.vz[i]), bulk.linear_velocity(ids[i]));
    EXPECT_EQ(Vec3(c.wx[i], c.wy[i], c.wz[i]), bulk.angular_velocity(ids[i]));
    EXPECT_TRUE(Quat(c.qw[i], c.qx[i], c.qy[i], c.qz[i]).isApprox(bulk.orientation(ids[i])));
  }
  std::vector<Real> x(n), y(n), z(n), vx(n), vy(n), vz(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = Real(i);
    y[i] = Real(2 + i % 3);
    z[i] = Real(0.5) * Real(i);
    vx[i] = Real(0.1) * Real(i);
    vy[i] = 1;
    vz[i] = -Real(i);
  }
  bulk.set_center_of_mass_positions(x, y, z);
  bulk.set_linear_velocities(vx, vy, vz);
  bulk.set_angular_velocities(vz, vx, vy);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyId id = single.body_at(i);
    single.set_position(id, Vec3(x[i], y[i], z[i]));  // boxes: shape frame = centre of mass
    single.set_linear_velocity(id, Vec3(vx[i], vy[i], vz[i]));
    single.set_angular_velocity(id, Vec3(vz[i], vx[i], vy[i]));
  }
  EXPECT_EQ(bulk.state_hash(), single.state_hash());
  for (int k = 0; k < 10; ++k) {
    bulk.step(kDt);
    single.step(kDt);
  }
  EXPECT_EQ(bulk.state_hash(), single.state_hash());
  EXPECT_EQ(c.px.data(), bulk.body_columns().px.data());  // steps do not reallocate
}

TEST(WorldApi, CollisionFilterAndPairFilterDropPairs) {
  World w;
  const ShapeId box = make_box(w, Vec3::Constant(Real(0.5)));
  const BodyId floor = add(w, make_box(w, Vec3(10, 1, 10)), Vec3(0, -1, 0), MotionType::Static);
  const BodyId a = add(w, box, Vec3(-2, 1, 0));
  const BodyId b = add(w, box, Vec3(2, 1, 0));
  w.set_collision_filter(a, 2, ~2u);
  w.set_collision_filter(floor, 1, ~2u);  // the floor ignores category 2: a falls through
  w.set_pair_filter([b](BodyId x, BodyId y) { return !(x == b || y == b); });  // and b
  for (int k = 0; k < 60; ++k) w.step(kDt);
  EXPECT_LT(w.position(a).y(), -1);
  EXPECT_LT(w.position(b).y(), -1);
  w.set_pair_filter({});
  const BodyId c = add(w, box, Vec3(0, 1, 0));
  for (int k = 0; k < 60; ++k) w.step(kDt);
  EXPECT_NEAR(w.position(c).y(), 0.5, 0.02);
}

}  // namespace api_bodies_test
}  // namespace elan
