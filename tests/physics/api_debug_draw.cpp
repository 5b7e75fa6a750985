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
  std::vector<Vec3> point_at;
  std::vector<DebugColor> point_colors, line_colors;
  void draw_shape(BodyId body, const ShapeDef& shape, const Transform& pose, DebugColor color,
                  bool awake) override {
    shapes.push_back({body, shape, pose, color, awake});
  }
  void draw_line(const Vec3&, const Vec3&, DebugColor c) override {
    ++lines;
    line_colors.push_back(c);
  }
  void draw_point(const Vec3& p, float, DebugColor c) override {
    ++points;
    point_at.push_back(p);
    point_colors.push_back(c);
  }
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

bool same(DebugColor a, DebugColor b) {
  return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a;
}

// Unit boxes resting on a static ground slab (top face at y = 0), centred at x = xs[k], z = 0.
World boxes_on_ground(const std::vector<Real>& xs) {
  World w;
  add(w, box(w, Vec3(20, 1, 5)), Vec3(0, -1, 0), MotionType::Static);
  const ShapeId cube = box(w, Vec3::Constant(Real(0.5)));
  for (const Real x : xs) add(w, cube, Vec3(x, Real(0.5), 0));
  return w;
}

TEST(DebugDraw, SolverHalvesColourEachHalfAndTheCutsContacts) {
  // Two rows of three touching boxes, 8 m apart along x: the centres spread 10 m along x and
  // (nearly) nothing along y and z, so the cut is at the median along x, in the gap: the first
  // n / 2 = 3 bodies by x (the left row) are half 0, the right row half 1. No contact joins them.
  World w = boxes_on_ground({-6, -5, -4, 4, 5, 6});
  Recorder before;
  w.debug_draw(before, kDrawSolverHalves);
  Recorder plain_before;
  w.debug_draw(plain_before, kDrawShapes);
  ASSERT_EQ(before.shapes.size(), 7u);
  // Before any step nothing was split: every body keeps its colour by motion type.
  for (std::size_t k = 0; k < 7; ++k) {
    EXPECT_TRUE(same(before.shapes[k].color, plain_before.shapes[k].color)) << k;
  }
  EXPECT_EQ(before.points, 0u);

  w.step(kDt);
  Recorder halves;
  w.debug_draw(halves, kDrawSolverHalves);
  ASSERT_EQ(halves.shapes.size(), 7u);
  const DebugColor left = halves.shapes[1].color, right = halves.shapes[4].color;
  EXPECT_TRUE(same(left, kSolverHalfColors[0]));
  EXPECT_TRUE(same(right, kSolverHalfColors[1]));
  EXPECT_FALSE(same(left, right));
  for (std::size_t k = 1; k <= 3; ++k) {
    EXPECT_TRUE(same(halves.shapes[k].color, left)) << k;
    EXPECT_TRUE(same(halves.shapes[k + 3].color, right)) << k + 3;
  }
  // The static ground is not split: its colour by motion type.
  Recorder plain;
  w.debug_draw(plain, kDrawShapes);
  EXPECT_TRUE(same(halves.shapes[0].color, plain.shapes[0].color));
  // The rows touch the ground only (not split): no contact of the cut.
  EXPECT_EQ(halves.points, 0u);
  EXPECT_EQ(halves.lines, 0u);

  // The flag off: colours by motion type, one for every dynamic box, none a half's.
  for (std::size_t k = 2; k <= 6; ++k) {
    EXPECT_TRUE(same(plain.shapes[k].color, plain.shapes[1].color)) << k;
  }
  EXPECT_FALSE(same(plain.shapes[1].color, plain.shapes[0].color));
  EXPECT_FALSE(same(plain.shapes[1].color, kSolverHalfColors[0]));
  EXPECT_FALSE(same(plain.shapes[1].color, kSolverHalfColors[1]));
}

TEST(DebugDraw, SolverHalvesDrawTheContactsAcrossTheCutInTheirOwnColour) {
  // One row of four touching boxes: the median along x falls between the second and the third,
  // whose shared face (x = 0) holds the only contacts joining the two halves.
  World w = boxes_on_ground({Real(-1.5), Real(-0.5), Real(0.5), Real(1.5)});
  w.step(kDt);
  std::size_t all_points = 0, cut_points = 0;
  const BodyId b1 = w.body_at(2), b2 = w.body_at(3);
  for (std::size_t k = 0; k < w.contact_count(); ++k) {
    const ContactView c = w.contact(k);
    all_points += std::size_t(c.point_count);
    const bool cut = (c.body_a == b1 && c.body_b == b2) || (c.body_a == b2 && c.body_b == b1);
    if (cut) cut_points += std::size_t(c.point_count);
  }
  ASSERT_GT(cut_points, 0u) << "the middle boxes touch";

  Recorder halves;
  w.debug_draw(halves, kDrawSolverHalves);
  EXPECT_TRUE(same(halves.shapes[2].color, kSolverHalfColors[0]));
  EXPECT_TRUE(same(halves.shapes[3].color, kSolverHalfColors[1]));
  // Only the cut's contacts, each a point and its normal in the cut's colour, on the face x = 0
  // (within the solver's softness: a few mm).
  ASSERT_EQ(halves.points, cut_points);
  EXPECT_EQ(halves.lines, cut_points);
  for (std::size_t k = 0; k < halves.points; ++k) {
    EXPECT_TRUE(same(halves.point_colors[k], kSolverCutColor));
    EXPECT_TRUE(same(halves.line_colors[k], kSolverCutColor));
    EXPECT_NEAR(halves.point_at[k].x(), 0, Real(0.01));
  }

  // With the contacts drawn as well: every contact once, the cut's in the cut's colour.
  Recorder both;
  w.debug_draw(both, kDrawSolverHalves | kDrawContacts);
  ASSERT_EQ(both.points, all_points);
  std::size_t in_cut_colour = 0;
  for (const DebugColor c : both.point_colors) in_cut_colour += same(c, kSolverCutColor);
  EXPECT_EQ(in_cut_colour, cut_points);

  // Without the flag no point takes the cut's colour.
  Recorder contacts;
  w.debug_draw(contacts, kDrawContacts);
  ASSERT_EQ(contacts.points, all_points);
  for (const DebugColor c : contacts.point_colors) EXPECT_FALSE(same(c, kSolverCutColor));
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
