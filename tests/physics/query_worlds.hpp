// SPDX-License-Identifier: MIT
// Random worlds of every shape kind and random rays through them: what the scene query tests
// (physics/scene_queries.cpp) and the concurrent query test (stage/queries_threads.cpp) share.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "elan/world.hpp"

namespace elan::query_worlds {

inline Real uniform(std::mt19937& rng, Real lo, Real hi) {
  return std::uniform_real_distribution<Real>(lo, hi)(rng);
}

inline Quat random_rotation(std::mt19937& rng) {
  return Quat{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)}
      .normalized();
}

// One shape of every kind a body may have.
inline std::vector<ShapeId> every_kind(World& w, std::vector<bool>& static_only) {
  std::vector<ShapeId> out;
  ShapeDef d;
  d.type = ShapeType::Sphere;
  d.radius = 0.6f;
  out.push_back(w.create_shape(d));
  d.type = ShapeType::Box;
  d.half_extents = Vec3(0.9f, 0.4f, 0.6f);
  out.push_back(w.create_shape(d));
  d.type = ShapeType::Capsule;
  d.radius = 0.35f;
  d.half_height = 0.6f;
  out.push_back(w.create_shape(d));
  d.type = ShapeType::Cylinder;
  d.radius = 0.5f;
  d.half_height = 0.4f;
  out.push_back(w.create_shape(d));
  ShapeDef hull;
  hull.type = ShapeType::ConvexHull;
  hull.points = {Vec3(-0.7f, -0.5f, -0.4f), Vec3(0.8f, -0.5f, -0.5f), Vec3(0, 0.9f, 0),
                 Vec3(0.1f, -0.4f, 0.8f), Vec3(-0.3f, 0.3f, -0.6f)};
  out.push_back(w.create_shape(hull));
  ShapeDef compound;
  compound.type = ShapeType::Compound;
  ShapeDef part;
  part.type = ShapeType::Box;
  part.half_extents = Vec3(0.5f, 0.2f, 0.2f);
  compound.children.push_back({part, Vec3(0.4f, 0, 0), Quat::Identity()});
  part.type = ShapeType::Sphere;
  part.radius = 0.4f;
  compound.children.push_back({part, Vec3(-0.5f, 0.3f, 0), Quat::Identity()});
  out.push_back(w.create_shape(compound));
  static_only.assign(out.size(), false);
  ShapeDef mesh;
  mesh.type = ShapeType::Mesh;
  mesh.vertices = {Vec3(-3, 0, -3), Vec3(3, 0, -3), Vec3(3, 0, 3), Vec3(-3, 0, 3), Vec3(0, 2, 0)};
  mesh.triangles = {{0, 4, 1}, {1, 4, 2}, {2, 4, 3}, {3, 4, 0}};
  out.push_back(w.create_shape(mesh));
  ShapeDef field;
  field.type = ShapeType::Heightfield;
  field.columns = 6;
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 6; ++i) field.heights.push_back(Real(0.3 * std::sin(i + 2.0 * j)));
  }
  out.push_back(w.create_shape(field));
  static_only.resize(out.size(), true);
  return out;
}

// A world of n bodies of every kind at random poses in a 24 m cube, a third static, with a
// ground plane under it all; a few bodies in their own category.
inline World random_world(uint32_t seed, int n, int threads = 1) {
  WorldDef def;
  def.threads = threads;
  World w(def);
  std::mt19937 rng(seed);
  std::vector<bool> static_only;
  const std::vector<ShapeId> shapes = every_kind(w, static_only);
  for (int k = 0; k < n; ++k) {
    const std::size_t s = rng() % shapes.size();
    BodyDef b;
    b.shape = shapes[s];
    b.motion = static_only[s] || rng() % 3 == 0 ? MotionType::Static : MotionType::Dynamic;
    b.position = Vec3{uniform(rng, -12, 12), uniform(rng, -12, 12), uniform(rng, -12, 12)};
    b.orientation = static_only[s] ? Quat::Identity() : random_rotation(rng);
    b.category_bits = rng() % 5 == 0 ? 2u : 1u;
    w.create_body(b);
  }
  ShapeDef plane;
  plane.type = ShapeType::Plane;
  plane.offset = -14;
  BodyDef g;
  g.motion = MotionType::Static;
  g.shape = w.create_shape(plane);
  w.create_body(g);
  return w;
}

struct RandomRay {
  Vec3 origin, dir;
};
inline RandomRay random_ray(std::mt19937& rng) {
  const Vec3 o{uniform(rng, -16, 16), uniform(rng, -16, 16), uniform(rng, -16, 16)};
  const Vec3 d = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)}.normalized();
  return {o, d};
}

}  // namespace elan::query_worlds
