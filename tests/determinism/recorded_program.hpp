// SPDX-License-Identifier: MIT
// A program that changes its world between steps in every way the recorder must capture: it
// builds the world through the API, then creates and destroys bodies and joints, pushes bodies
// (forces, torques, impulses), drives a kinematic body and a motor, changes materials, gravity,
// solver and sleep settings, uses the bulk setters and rolls back once, all while being recorded.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "elan/recorder.hpp"
#include "elan/snapshot.hpp"
#include "elan/world.hpp"

namespace elan::test {

inline constexpr uint64_t kProgramSteps = 120;
inline constexpr Real kProgramDt = Real(1) / 60;
// The impulse the divergence tests edit: applied to body kPushedBody's id before step
// kPushStep + 1.
inline constexpr uint64_t kPushStep = 30;
// The edit: this many ulps more on the impulse's first component, J = 1.7 (ulp 2^-23). Less than
// one ulp of the velocity's sum v + J / m (m = 1) can round away. That sum lies between 4 and 8
// m/s there (ulp 2^-21: three ulps of J change it, two do not), so four are one ulp of it.
inline constexpr int kPushUlps = 4;
inline Real nudged_up(Real v) {
  for (int k = 0; k < kPushUlps; ++k) v = std::nextafter(v, std::numeric_limits<Real>::infinity());
  return v;
}

struct RecordedProgram {
  std::vector<uint8_t> recording;
  uint64_t final_hash = 0;
  std::size_t pushed_body = 0;  // dense index of the body the edited impulse pushes
};

// Runs the program on a world of `threads` workers, recording from the start with keyframes
// every `keyframe_every` steps.
inline RecordedProgram record_program(int threads, uint64_t keyframe_every = 10) {
  WorldDef def;
  def.threads = threads;
  World w(def);
  ShapeDef ground_shape;
  ground_shape.type = ShapeType::Box;
  ground_shape.half_extents = Vec3(20, Real(0.5), 20);
  BodyDef ground;
  ground.motion = MotionType::Static;
  ground.shape = w.create_shape(ground_shape);
  ground.position = Vec3(0, Real(-0.5), 0);
  w.create_body(ground);

  ShapeDef box_shape;
  box_shape.type = ShapeType::Box;
  box_shape.half_extents = Vec3(Real(0.25), Real(0.25), Real(0.25));
  const ShapeId box = w.create_shape(box_shape);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 6; ++i) {
    BodyDef b;
    b.shape = box;
    b.position = Vec3(Real(0.3) * Real(i % 2), Real(0.25) + Real(0.55) * Real(i), Real(0.1) * i);
    // The pushed box is light: its velocity change J / m is of the size of J, so a few ulps more
    // in J are an ulp more in the velocity (with 125 kg they could round away).
    if (i == 3) b.mass = Real(1);
    boxes.push_back(w.create_body(b));
  }
  ShapeDef paddle_shape;
  paddle_shape.type = ShapeType::Box;
  paddle_shape.half_extents = Vec3(1, Real(0.1), Real(0.3));
  BodyDef paddle;
  paddle.motion = MotionType::Kinematic;
  paddle.shape = w.create_shape(paddle_shape);
  paddle.position = Vec3(3, Real(0.3), 0);
  const BodyId kinematic = w.create_body(paddle);
  BodyDef wheel;
  wheel.shape = box;
  wheel.position = Vec3(-3, 2, 0);
  const BodyId motor_body = w.create_body(wheel);
  JointDef hinge;
  hinge.type = JointType::Hinge;
  hinge.body_a = motor_body;
  hinge.anchor = Vec3(-3, 2, 0);
  hinge.axis = Vec3(0, 0, 1);
  hinge.motor = JointMotor{true, 2, 50};
  const JointId motor = w.create_joint(hinge);

  RecordOptions options;
  options.keyframe_every = keyframe_every;
  options.name = "recorded_program";
  start_recording(w, options);

  ShapeDef ball_shape;
  ball_shape.type = ShapeType::Sphere;
  ball_shape.radius = Real(0.2);
  std::vector<BodyId> balls;
  JointId rope;
  std::vector<uint8_t> rollback;
  RecordedProgram out;
  for (uint64_t step = 0; step < kProgramSteps; ++step) {
    const Real t = Real(step) * kProgramDt;
    // Drive: the kinematic paddle sweeps, the motor speeds up, one box is pushed every step.
    Transform target;
    target.position = Vec3(3 + std::sin(t * 2), Real(0.3), 0);
    target.rotation = Quat(Eigen::AngleAxis<Real>(t, Vec3::UnitY()));
    w.move_kinematic(kinematic, target, kProgramDt);
    w.apply_force(boxes[1], Vec3(Real(3.5), 0, Real(-1.25)));
    if (step % 7 == 0) w.apply_torque(boxes[2], Vec3(0, Real(0.75), 0));
    if (step == 5) {
      const ShapeId ball = w.create_shape(ball_shape);
      for (int i = 0; i < 3; ++i) {
        BodyDef b;
        b.shape = ball;
        b.position = Vec3(Real(-1) + Real(0.5) * Real(i), 4, Real(0.3));
        b.restitution = Real(0.3);
        balls.push_back(w.create_body(b));
      }
    }
    if (step == 12) w.apply_force_at(balls[0], Vec3(0, 0, 6), Vec3(-1, 4, Real(0.5)));
    if (step == 15) {
      JointDef d;
      d.type = JointType::Distance;
      d.body_a = balls[1];
      d.body_b = boxes[5];
      d.anchor = w.position(balls[1]);
      d.anchor_b = w.position(boxes[5]);
      rope = w.create_joint(d);
    }
    if (step == 20) w.destroy_body(balls[2]);  // swap-removes: dense indices change
    if (step == 25) w.set_joint_motor(motor, JointMotor{true, -4, 80});
    if (step == kPushStep) {
      const BodyId pushed = boxes[3];
      w.apply_impulse(pushed, Vec3(Real(1.7), Real(0.4), Real(-0.9)), w.center_of_mass(pushed));
      out.pushed_body = 0;
      while (w.body_at(out.pushed_body) != pushed) ++out.pushed_body;
    }
    if (step == 33) w.apply_linear_impulse(boxes[0], Vec3(0, 2, 0));
    if (step == 34) w.apply_angular_impulse(boxes[4], Vec3(Real(0.2), 0, 0));
    if (step == 40) {
      w.set_friction(boxes[2], Real(0.9));
      w.set_restitution(balls[0], Real(0.6));
      w.set_gravity(Vec3(Real(0.4), Real(-9.5), 0));
      w.set_damping(boxes[4], Real(0.1), Real(0.2));
    }
    if (step == 50) {
      w.set_linear_velocity(balls[1], Vec3(1, 0, 0));
      w.set_angular_velocity(boxes[5], Vec3(0, 3, 0));
      w.set_transform(boxes[0], Transform{Vec3(0, 3, 1), Quat::Identity()});
    }
    if (step == 55) {
      std::vector<Real> x(w.body_count()), y(w.body_count()), z(w.body_count());
      const World::BodyColumns c = w.body_columns();
      for (std::size_t i = 0; i < w.body_count(); ++i) {
        x[i] = c.vx[i] * Real(0.5);
        y[i] = c.vy[i];
        z[i] = c.vz[i] * Real(0.5);
      }
      w.set_linear_velocities(x, y, z);
    }
    if (step == 60) w.set_substeps(6);
    if (step == 62) rollback = save_rollback(w);
    if (step == 64) restore_rollback(w, rollback);
    if (step == 70) w.destroy_joint(rope);
    if (step == 75) w.sleep(boxes[2]);
    if (step == 80) w.wake(boxes[2]);
    if (step == 85) w.set_mass(boxes[4], Real(3));
    if (step == 90) w.set_motion_type(balls[0], MotionType::Kinematic);
    if (step == 95) w.set_collision_filter(boxes[1], 2, ~uint32_t(0));
    if (step == 100) w.set_gravity_scale(boxes[5], Real(0.5));
    if (step == 105) w.set_sleep_enabled(false);
    if (step == 112) w.set_sleep_enabled(true);
    w.step(kProgramDt);
  }
  out.final_hash = w.state_hash();
  out.recording = stop_recording(w);
  return out;
}

}  // namespace elan::test
