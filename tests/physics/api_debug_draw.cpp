// SPDX-License-Identifier: MIT
// World::debug_draw and the body getters a drawer relies on (shape, shape_def, bounds, inertia):
// a recording drawer sees every body once with its shape and its shape-frame pose; the getters
// against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "elan/elan.hpp"

namespace elan {
namespace api_debug_draw_test {

constexpr Real kDt = Real(1.0 / 60.0);

struct Recorder : DebugDrawer {
  struct ShapeCall {
    BodyId body;
    ShapeDef shape;
    Transform pose;
    DebugColor color;
    bool awake;
  };
  std::vector<ShapeCall> shapes;
  std::vector<Aabb> boxes;
  std::size_t lines = 0, points = 0;
  void draw_shape(BodyId body, const ShapeDef& shape, const Transform& pose, DebugColor color,
                  bool awake) override {
    shapes.push_back({body, shape, pose, color, awake});
  }
  void draw_line(const Vec3&, const Vec3&, DebugColor) override { ++lines; }
  void draw_point(const Vec3&, float, DebugColor) override { ++points; }
  void draw_box(const Aabb& box, DebugColor) override { boxes.push_back(box); }
};

ShapeId sphere(World& w, Real r) {
  ShapeDef s;
  s.type = ShapeType::Sphere;
  s.radius = r;
  return w.create_shape(s);
}

ShapeId box(World& w, const Vec3& h) {
  ShapeDef s;
  s.type = ShapeType::Box;
  s.half_extents = h;
  return w.create_shape(s);
}

BodyId add(World& w, ShapeId shape, const Vec3& p, MotionType motion = MotionType::Dynamic,
           const Quat& q = Quat::Identity()) {
  BodyDef d;
  d.shape = shape;
  d.position = p;
  d.orientation = q;
  d.motion = motion;
  return w.create_body(d);
}

// A world of every kind of body: the shape types a drawer must handle, the three motion types,
// an off-centre hull and compound (whose shape frame is not the store's principal frame), a
// sleeping body.
struct Zoo {
  World w;
  std::vector<BodyId> bodies;
  Zoo() {
    ShapeDef plane;
    plane.type = ShapeType::Plane;
    bodies.push_back(add(w, w.create_shape(plane), Vec3::Zero(), MotionType::Static));
    bodies.push_back(add(w, sphere(w, Real(0.5)), Vec3(0, Real(0.5), 0)));
    bodies.push_back(add(w, box(w, Vec3(1, Real(0.5), Real(0.25))), Vec3(3, 2, 0),
                         MotionType::Kinematic,
                         Quat(Eigen::AngleAxis<Real>(Real(0.3), Vec3::UnitZ()))));
    ShapeDef hull;
    hull.type = ShapeType::ConvexHull;
    hull.points = {Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(2, 1, 0), Vec3(2, 0, 1), Vec3(3, 1, 1)};
    bodies.push_back(add(w, w.create_shape(hull), Vec3(-4, 3, 0), MotionType::Dynamic,
                         Quat(Eigen::AngleAxis<Real>(Real(0.7), Vec3(1, 1, 0).normalized()))));
    ShapeDef compound;
    compound.type = ShapeType::Compound;
    CompoundChild a, b;
    a.shape.type = ShapeType::Box;
    a.shape.half_extents = Vec3(Real(0.5), Real(0.1), Real(0.1));
    a.position = Vec3(1, 0, 0);
    b.shape.type = ShapeType::Capsule;
    b.shape.radius = Real(0.2);
    b.shape.half_height = Real(0.3);
    b.position = Vec3(0, 0, 1);
    b.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.5), Vec3::UnitX()));
    compound.children = {a, b};
    bodies.push_back(add(w, w.create_shape(compound), Vec3(6, 4, 1)));
    BodyDef sleeper;
    sleeper.shape = box(w, Vec3::Constant(Real(0.5)));
    sleeper.position = Vec3(-8, Real(0.5), 0);
    sleeper.awake = false;
    bodies.push_back(w.create_body(sleeper));
  }
};

TEST(DebugDraw, EveryBodyOnceWithItsShapeAndShapeFramePose) {
  Zoo z;
  z.w.step(kDt);
  Recorder r;
  z.w.debug_draw(r, kDrawShapes);
  ASSERT_EQ(r.shapes.size(), z.bodies.size());
  std::map<uint32_t, int> seen;
  for (std::size_t k = 0; k < r.shapes.size(); ++k) {
    const Recorder::ShapeCall& c = r.shapes[k];
    // Body index order.
    EXPECT_EQ(c.body, z.w.body_at(k));
    ++seen[c.body.slot];
    const ShapeDef& def = z.w.shape_def(z.w.shape(c.body));
    EXPECT_EQ(c.shape.type, def.type);
    EXPECT_EQ(c.shape.points.size(), def.points.size());
    EXPECT_EQ(c.shape.children.size(), def.children.size());
    // The pose is the shape frame's, as position() and orientation() report it.
    EXPECT_LT((c.pose.position - z.w.position(c.body)).norm(), Real(1e-5));
    EXPECT_GT(std::abs(c.pose.rotation.dot(z.w.orientation(c.body))), Real(1) - Real(1e-6));
    EXPECT_EQ(c.awake, z.w.is_awake(c.body) || z.w.motion_type(c.body) != MotionType::Dynamic);
  }
  EXPECT_EQ(seen.size(), z.bodies.size());
  EXPECT_FALSE(r.shapes.back().awake);  // the sleeper
  EXPECT_TRUE(r.boxes.empty());
  EXPECT_EQ(r.lines, 0u);
}

TEST(DebugDraw, FlagsSelectBoundsContactsJointsAndCentres) {
  Zoo z;
  JointDef j;
  j.type = JointType::Ball;
  j.body_a = z.bodies[1];
  j.body_b = z.bodies[3];
  z.w.create_joint(j);
  for (int k = 0; k < 5; ++k) z.w.step(kDt);
  Recorder r;
  z.w.debug_draw(r, kDrawBounds);
  ASSERT_EQ(r.boxes.size(), z.bodies.size());
  for (std::size_t k = 0; k < r.boxes.size(); ++k) {
    const Aabb b = z.w.bounds(z.w.body_at(k));
    EXPECT_EQ(r.boxes[k].lo, b.lo);
    EXPECT_EQ(r.boxes[k].hi, b.hi);
  }
  EXPECT_TRUE(r.shapes.empty());

  Recorder contacts;
  z.w.debug_draw(contacts, kDrawContacts);
  std::size_t points = 0;
  for (std::size_t k = 0; k < z.w.contact_count(); ++k) points += z.w.contact(k).point_count;
  ASSERT_GT(points, 0u);  // the sphere rests on the plane
  EXPECT_EQ(contacts.points, points);
  EXPECT_EQ(contacts.lines, points);  // a normal each

  Recorder joints;
  z.w.debug_draw(joints, kDrawJoints);
  EXPECT_EQ(joints.lines, 3u);  // centre A - anchor, anchor - anchor, anchor - centre B
  EXPECT_EQ(joints.points, 2u);

  Recorder centres;
  z.w.debug_draw(centres, kDrawCentersOfMass);
  EXPECT_EQ(centres.points, 4u);  // the dynamic bodies

  Recorder islands;
  z.w.debug_draw(islands, kDrawIslands);
  ASSERT_EQ(islands.shapes.size(), z.bodies.size());
  // The jointed sphere and hull are one island: one colour.
  EXPECT_EQ(islands.shapes[1].color.r, islands.shapes[3].color.r);
  EXPECT_EQ(islands.shapes[1].color.g, islands.shapes[3].color.g);
}

TEST(BodyGetters, ShapeDefRebuildsTheSameShape) {
  Zoo z;
  for (BodyId b : z.bodies) {
    const ShapeDef& def = z.w.shape_def(z.w.shape(b));
    const ShapeId again = z.w.create_shape(def);
    BodyDef d;
    d.shape = again;
    d.motion = z.w.motion_type(b);
    d.position = z.w.position(b);
    d.orientation = z.w.orientation(b);
    const BodyId copy = z.w.create_body(d);
    // Same geometry, same frames: the same centre of mass, mass and world inertia (a hull's or
    // compound's box is that of its principal frame, which a rebuild may pick otherwise).
    EXPECT_LT((z.w.center_of_mass(copy) - z.w.center_of_mass(b)).norm(), Real(1e-4));
    EXPECT_NEAR(z.w.mass(copy), z.w.mass(b), Real(1e-4) * z.w.mass(b));
    EXPECT_LT((z.w.inertia(copy) - z.w.inertia(b)).norm(),
              Real(1e-4) * (1 + z.w.inertia(b).norm()));
  }
  EXPECT_THROW(z.w.shape_def(ShapeId{}), Error);
  EXPECT_THROW(z.w.shape_def(ShapeId{999}), Error);
}

TEST(BodyGetters, BoundsAndInertiaOfARotatedBox) {
  World w;
  const Vec3 h(1, Real(0.5), Real(0.25));
  const Real angle = Real(0.4);
  const Quat q(Eigen::AngleAxis<Real>(angle, Vec3::UnitZ()));
  BodyDef d;
  d.shape = box(w, h);
  d.position = Vec3(1, 2, 3);
  d.orientation = q;
  d.mass = Real(6);
  const BodyId b = w.create_body(d);
  // A box turned by a about z: half extents |cos a| hx + |sin a| hy on x, and so on.
  const Real c = std::cos(angle), s = std::sin(angle);
  const Vec3 e(c * h.x() + s * h.y(), s * h.x() + c * h.y(), h.z());
  const Aabb box_ = w.bounds(b);
  EXPECT_LT((box_.lo - (d.position - e)).norm(), Real(1e-5));
  EXPECT_LT((box_.hi - (d.position + e)).norm(), Real(1e-5));
  // I = R diag(m/3 (hy^2 + hz^2), ...) R^T for half extents h.
  const Vec3 moments = Real(6) / 3 *
                       Vec3(h.y() * h.y() + h.z() * h.z(), h.x() * h.x() + h.z() * h.z(),
                            h.x() * h.x() + h.y() * h.y());
  const Mat3 r = q.toRotationMatrix();
  const Mat3 expected = r * moments.asDiagonal() * r.transpose();
  EXPECT_LT((w.inertia(b) - expected).norm(), Real(1e-4));
  EXPECT_EQ(w.inertia(add(w, d.shape, Vec3(5, 0, 0), MotionType::Kinematic)), Mat3::Zero());
  EXPECT_THROW(w.inertia(BodyId{}), Error);
  EXPECT_THROW(w.bounds(BodyId{}), Error);
}

}  // namespace api_debug_draw_test
}  // namespace elan
