// SPDX-License-Identifier: MIT
// The scene file's generators: validation and expansion into bodies (and joints).
#include "core/scene/generators.hpp"

#include <string>
#include <utility>

#include "core/scene/body_schema.hpp"

namespace elan::detail::scene_file {

namespace {

// count [nx, ny, nz] (integers >= 1) with at most kMaxBodies / `per_copy` copies: the grid's
// bodies, or the copies of a chain or a ragdoll.
void parse_count(const Ctx& ctx, const Json& j, Generator& g, uint64_t per_copy) {
  const Json& count = array_of(ctx, j, "count", 3);
  uint64_t total = per_copy;
  for (int i = 0; i < 3; ++i) {
    g.count[i] = to_int(ctx, count[i], "count[" + std::to_string(i) + "]", 1, kMaxBodies);
    total *= uint64_t(g.count[i]);
    if (total > kMaxBodies) {
      fail(ctx, "count",
           "too many bodies: at most " + std::to_string(kMaxBodies) + " bodies are allowed");
    }
  }
}

// Copies of a chain or a ragdoll: `count` and `spacing` as a grid's, both optional (one copy).
uint64_t parse_copies(const Ctx& ctx, const Json& j, Generator& g, uint64_t per_copy) {
  if (const auto it = j.find("count"); it != j.end()) {
    parse_count(ctx, *it, g, per_copy);
    g.spacing = to_vec3(ctx, require(ctx, j, "spacing", "spacing"), "spacing");
  } else if (const auto sp = j.find("spacing"); sp != j.end()) {
    g.spacing = to_vec3(ctx, *sp, "spacing");
  }
  return uint64_t(g.count[0]) * uint64_t(g.count[1]) * uint64_t(g.count[2]);
}

}  // namespace

Generator parse_generator(const Ctx& ctx, const Json& j) {
  object_of(ctx, j, "");
  const std::string type = to_string(ctx, require(ctx, j, "type", "type"), "type");
  Generator g;
  if (type == "grid") {
    check_keys(ctx, j, {"type", "count", "spacing", "origin", "body"}, "", "a grid generator");
    parse_count(ctx, require(ctx, j, "count", "count"), g, 1);
    g.bodies = uint64_t(g.count[0]) * uint64_t(g.count[1]) * uint64_t(g.count[2]);
    g.spacing = to_vec3(ctx, require(ctx, j, "spacing", "spacing"), "spacing");
    const Ctx body_ctx{ctx.file, ctx.where, "body."};
    g.body = parse_body(body_ctx, require(ctx, j, "body", "body"));
    if (!g.body.name.empty()) {
      fail(body_ctx, "name", "generated bodies cannot be named (names must be unique)");
    }
  } else if (type == "pyramid") {
    check_keys(ctx, j, {"type", "base", "half_extent", "origin"}, "", "a pyramid generator");
    // base(base+1)(2 base+1)/6 <= kMaxBodies needs base <= 310; 10^6 keeps the product exact.
    g.base = to_int(ctx, require(ctx, j, "base", "base"), "base", 1, 1'000'000);
    g.kind = GeneratorKind::Pyramid;
    g.bodies = uint64_t(g.base) * uint64_t(g.base + 1) * uint64_t(2 * g.base + 1) / 6;
    if (g.bodies > kMaxBodies) {
      fail(ctx, "base",
           "too many bodies: a pyramid of base " + std::to_string(g.base) + " has " +
               std::to_string(g.bodies) + " cubes, at most " + std::to_string(kMaxBodies) +
               " bodies are allowed");
    }
    if (const auto it = j.find("half_extent"); it != j.end()) {
      g.half_extent = positive(ctx, *it, "half_extent");
    }
  } else if (type == "chain") {
    check_keys(ctx, j,
               {"type", "links", "link", "origin", "direction", "link_spacing", "joint", "axis",
                "count", "spacing"},
               "", "a chain generator");
    g.kind = GeneratorKind::Chain;
    g.chain = parse_chain(ctx, j, g.body);
    const uint64_t copies = parse_copies(ctx, j, g, uint64_t(g.chain.links));
    g.bodies = copies * uint64_t(g.chain.links);
    g.joints = copies * chain_joints(g.chain);
  } else if (type == "ragdoll") {
    check_keys(
        ctx, j,
        {"type", "origin", "orientation", "scale", "hands", "joint_friction", "count", "spacing"},
        "", "a ragdoll generator");
    g.kind = GeneratorKind::Ragdoll;
    g.ragdoll = parse_ragdoll(ctx, j);
    const uint64_t copies = parse_copies(ctx, j, g, ragdoll_bodies(g.ragdoll));
    g.bodies = copies * ragdoll_bodies(g.ragdoll);
    g.joints = copies * ragdoll_joints(g.ragdoll);
  } else if (type == "joint_grid") {
    check_keys(ctx, j, {"type", "count", "spacing", "radius", "origin", "pinned"}, "",
               "a joint_grid generator");
    g.kind = GeneratorKind::JointGrid;
    g.joint_grid = parse_joint_grid(ctx, j);
    g.bodies = uint64_t(g.joint_grid.count) * uint64_t(g.joint_grid.count);
    g.joints = joint_grid_joints(g.joint_grid);
  } else if (type == "terrain") {
    check_keys(ctx, j,
               {"type", "shape", "cells", "spacing", "origin", "amplitude", "wavelength",
                "friction", "restitution"},
               "", "a terrain generator");
    g.kind = GeneratorKind::Terrain;
    g.terrain = parse_terrain(ctx, j);
    g.bodies = 1;
  } else {
    fail(ctx, "type",
         "unknown generator type \"" + type +
             "\" (allowed: grid, pyramid, chain, ragdoll, joint_grid, terrain)");
  }
  if (const auto it = j.find("origin"); it != j.end()) g.origin = to_vec3(ctx, *it, "origin");
  return g;
}

// Positions are computed in double and rounded once, so a pyramid's cubes touch exactly as far
// as Real can say.
void expand(const Generator& g, std::vector<SceneBody>& out, std::vector<SceneJoint>& joints) {
  const Vec3& o = g.origin;
  if (g.kind == GeneratorKind::Terrain) {
    out.push_back(make_terrain(g.terrain, o));
    return;
  }
  if (g.kind == GeneratorKind::JointGrid) {
    expand_joint_grid(g.joint_grid, o, out, joints);
    return;
  }
  if (g.kind == GeneratorKind::Chain || g.kind == GeneratorKind::Ragdoll) {
    // Copies x fastest, then y, then z, each copy's bodies together.
    for (int64_t k = 0; k < g.count[2]; ++k) {
      for (int64_t j = 0; j < g.count[1]; ++j) {
        for (int64_t i = 0; i < g.count[0]; ++i) {
          const Vec3 at(Real(double(o.x()) + double(i) * double(g.spacing.x())),
                        Real(double(o.y()) + double(j) * double(g.spacing.y())),
                        Real(double(o.z()) + double(k) * double(g.spacing.z())));
          if (g.kind == GeneratorKind::Chain) {
            expand_chain(g.chain, g.body, at, out, joints);
          } else {
            expand_ragdoll(g.ragdoll, at, out, joints);
          }
        }
      }
    }
    return;
  }
  if (g.kind == GeneratorKind::Grid) {
    for (int64_t k = 0; k < g.count[2]; ++k) {
      for (int64_t j = 0; j < g.count[1]; ++j) {
        for (int64_t i = 0; i < g.count[0]; ++i) {
          SceneBody b = g.body;
          b.body.position = Vec3(Real(double(o.x()) + double(i) * double(g.spacing.x())),
                                 Real(double(o.y()) + double(j) * double(g.spacing.y())),
                                 Real(double(o.z()) + double(k) * double(g.spacing.z())));
          out.push_back(std::move(b));
        }
      }
    }
    return;
  }
  const double h = double(g.half_extent);
  SceneBody cube;
  cube.shape.type = ShapeType::Box;
  cube.shape.half_extents = Vec3::Constant(g.half_extent);
  for (int64_t layer = 0; layer < g.base; ++layer) {
    const int64_t n = g.base - layer;
    // Cube centres of one layer sit 2h apart, symmetric about the origin: (2i - (n-1)) h.
    for (int64_t k = 0; k < n; ++k) {
      for (int64_t i = 0; i < n; ++i) {
        SceneBody b = cube;
        b.body.position = Vec3(Real(double(o.x()) + double(2 * i - (n - 1)) * h),
                               Real(double(o.y()) + double(2 * layer + 1) * h),
                               Real(double(o.z()) + double(2 * k - (n - 1)) * h));
        out.push_back(std::move(b));
      }
    }
  }
}

}  // namespace elan::detail::scene_file
