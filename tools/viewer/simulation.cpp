// SPDX-License-Identifier: MIT
#include "tools/viewer/simulation.hpp"

#include "elan/recorder.hpp"
#include "elan/scene.hpp"
#include "elan/snapshot.hpp"

namespace elan::viewer {

Simulation::Simulation(Source source, World world)
    : source_(std::move(source)), world_(std::move(world)) {
  load_joints();
}

const ShapeDef& Simulation::body_shape(std::size_t index) const {
  const bool program = replaying() && source_.recording->is_program();
  if (!program && index < source_.scene.bodies.size()) return source_.scene.bodies[index].shape;
  return world_.shape_def(world_.shape(world_.body_at(index)));
}

void Simulation::load_joints() {
  joints_.clear();
  const Scene& scene = source_.scene;
  // Anchors are given in the world at creation; they are kept in the bodies' frames as the
  // scene placed them (R^T (anchor - p)).
  const auto local = [&](int body, const Vec3& anchor) -> Vec3 {
    if (body < 0) return anchor;
    const BodyDef& b = scene.bodies[std::size_t(body)].body;
    return b.orientation.normalized().conjugate() * (anchor - b.position);
  };
  for (std::size_t j = 0; j < scene.joints.size() && j < world_.joint_count(); ++j) {
    const SceneJoint& sj = scene.joints[j];
    JointLink link;
    link.id = world_.joint_at(j);
    link.body_a = sj.body_a;
    link.body_b = sj.body_b;
    Vec3 anchor_a = sj.def.anchor, anchor_b = sj.def.anchor;
    if (sj.def.type == JointType::Distance) anchor_b = sj.def.anchor_b;
    if (sj.def.type == JointType::Fixed && !sj.def.has_anchor) {
      const Vec3 pa = scene.bodies[std::size_t(sj.body_a)].body.position;
      const Vec3 pb = sj.body_b < 0 ? pa : scene.bodies[std::size_t(sj.body_b)].body.position;
      anchor_a = anchor_b = (pa + pb) / 2;
    }
    link.local_a = local(sj.body_a, anchor_a);
    link.local_b = local(sj.body_b, anchor_b);
    joints_.push_back(link);
  }
}

uint32_t Simulation::step() {
  const uint32_t status =
      replaying() ? replay_step(world_, *source_.recording, steps_) : world_.step(source_.timestep);
  ++steps_;
  return status;
}

World Simulation::start_world() const {
  if (replaying() && source_.recording->is_program()) {
    return recording_start_world(*source_.recording, world_.settings().threads,
                                 source_.def.broadphase);
  }
  WorldDef def = source_.def;
  def.threads = world_.settings().threads;
  World fresh(def);
  load_into(source_.scene, fresh, source_.name);
  return fresh;
}

void Simulation::reset() {
  // A scene keeps the settings changed live; a recording replays its own.
  const LiveSettings live = settings();
  world_ = start_world();
  if (!replaying()) apply(live);
  steps_ = 0;
  ++version_;
  load_joints();
}

void Simulation::restore(const cli::Keyframe& keyframe) {
  restore_snapshot(world_, keyframe.snapshot);
  steps_ = keyframe.step;
  ++version_;
}

void Simulation::shoot(const Vec3& origin, const Vec3& direction, Real radius, Real speed) {
  ShapeDef ball;
  ball.type = ShapeType::Sphere;
  ball.radius = radius;
  BodyDef body;
  body.shape = world_.create_shape(ball);
  body.position = origin;
  body.linear_velocity = direction * speed;
  world_.create_body(body);
  ++version_;
}

}  // namespace elan::viewer
