// SPDX-License-Identifier: MIT
// The small world the snapshot target restores rollback states into, and its seed generator
// saves them from: a ground, a sphere, a box and a hull on it, and a hinge between two of them.
#pragma once

#include "elan/world.hpp"

namespace elan::fuzz {

inline World fixed_world() {
  WorldDef def;
  def.threads = 1;
  World w(def);
  ShapeDef ground;
  ground.type = ShapeType::Box;
  ground.half_extents = Vec3(10, Real(0.5), 10);
  BodyDef g;
  g.shape = w.create_shape(ground);
  g.motion = MotionType::Static;
  g.position = Vec3(0, Real(-0.5), 0);
  w.create_body(g);

  ShapeDef sphere;
  sphere.type = ShapeType::Sphere;
  sphere.radius = Real(0.4);
  ShapeDef box;
  box.type = ShapeType::Box;
  box.half_extents = Vec3(Real(0.4), Real(0.3), Real(0.2));
  ShapeDef hull;
  hull.type = ShapeType::ConvexHull;
  hull.points = {{0, 0, 0}, {Real(0.6), 0, 0}, {0, Real(0.5), 0}, {0, 0, Real(0.4)}};
  const ShapeDef* shapes[] = {&sphere, &box, &hull};
  BodyId bodies[3];
  for (int k = 0; k < 3; ++k) {
    BodyDef b;
    b.shape = w.create_shape(*shapes[k]);
    b.position = Vec3(Real(k) - 1, Real(0.45) + Real(0.1) * Real(k), 0);
    b.angular_velocity = Vec3(0, Real(k), 0);
    bodies[k] = w.create_body(b);
  }
  JointDef hinge;
  hinge.type = JointType::Hinge;
  hinge.body_a = bodies[1];
  hinge.body_b = bodies[2];
  hinge.anchor = Vec3(Real(0.5), Real(0.6), 0);
  hinge.axis = Vec3(0, 0, 1);
  w.create_joint(hinge);
  return w;
}

}  // namespace elan::fuzz
