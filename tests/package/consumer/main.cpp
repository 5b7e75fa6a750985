// SPDX-License-Identifier: MIT
// Drops a ball for one second and checks it fell as v = g t says (the embedding example).
#include <elan/elan.hpp>

#include <cmath>
#include <cstdio>

int main() {
  elan::World world(elan::WorldDef{});
  elan::ShapeDef ball;
  ball.type = elan::ShapeType::Sphere;
  ball.radius = 0.5f;
  elan::BodyDef def;
  def.shape = world.create_shape(ball);
  def.position = elan::Vec3(0, 10, 0);
  const elan::BodyId id = world.create_body(def);
  for (int i = 0; i < 60; ++i) world.step(1.0f / 60.0f);
  const float vy = world.linear_velocity(id).y();
  std::printf("vy after 1 s: %.4f m/s, state hash %016llx\n", vy,
              static_cast<unsigned long long>(world.state_hash()));
  return std::abs(vy + 9.81f) < 1e-3f ? 0 : 1;
}
