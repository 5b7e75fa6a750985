// SPDX-License-Identifier: MIT
// The character mover: a vertical capsule moved by a desired displacement with the shape cast,
// collide-and-slide (Box2D's b2World_CastMover and Jolt's CharacterVirtual, simplified):
// advance to the first contact, keep a skin gap, slide what is left along the surface; a
// surface steeper than max_slope is a wall, which the slide may not climb; against a wall, try to
// step up (rise by step_height, move, settle down onto walkable ground). Reads the world only.
#include <algorithm>
#include <cmath>

#include "core/base/fixed_math.hpp"
#include "core/base/rotation_between.hpp"
#include "core/world/query_common.hpp"
#include "core/world/shape_queries.hpp"
#include "elan/world.hpp"

namespace elan::detail {

namespace {

struct MoverHit {
  uint32_t body = UINT32_MAX;
  Real fraction = 1;
  Vec3 normal = Vec3::UnitY();
};

struct Mover {
  const WorldState& s;
  const CharacterMoveDef& def;
  Shape capsule;
  Quat rotation;  // capsule's local +y to `up`
  Vec3 up;
  Real target;    // the casts stop this close: half the skin
  Real walkable;  // cos(max_slope)

  // The first body the capsule at `pos` meets moving by `delta` (ties: the lower index). A body
  // it already touches at the start and moves away from or along does not stop it.
  MoverHit cast(const Vec3& pos, const Vec3& delta) const {
    MoverHit best;
    const Transform x{pos, rotation};
    for_each_cast_hit(
        s, capsule, x, delta, target, def.filter, [&](uint32_t i, const CastContact& c) {
          if (c.fraction == 0 && c.normal.dot(delta) >= 0) return;
          if (c.fraction < best.fraction || (c.fraction == best.fraction && i < best.body)) {
            best = {i, c.fraction, c.normal};
          }
        });
    return best;
  }

  // How far along `delta` (of length len) the capsule may go before `hit`, leaving the skin:
  // the cast stopped `target` from the surface; back off so the gap along the normal is the
  // skin again (the back-off along the path is that over the cosine of the approach, capped).
  Real safe_travel(const MoverHit& hit, const Vec3& delta) const {
    const Real len = delta.norm();
    if (hit.body == UINT32_MAX) return len;
    const Real approach = std::max(-hit.normal.dot(delta / len), Real(0.25));
    return std::max(Real(0), hit.fraction * len - (def.skin - target) / approach);
  }

  // Moves by delta as far as the first hit allows; returns the hit.
  MoverHit advance(Vec3& pos, const Vec3& delta) const {
    if (!(delta.squaredNorm() > 0)) return {};
    const MoverHit hit = cast(pos, delta);
    pos += delta.normalized() * safe_travel(hit, delta);
    return hit;
  }

  bool is_walkable(const Vec3& n) const { return n.dot(up) >= walkable; }

  // The part of `rest` that slides along a surface of normal n. Ground: the projection onto
  // its plane. A wall: the projection too, but it may not rise more than `rest` asked for nor
  // push into the wall horizontally.
  Vec3 clip(const Vec3& rest, const Vec3& n) const {
    Vec3 r = rest - std::min(Real(0), rest.dot(n)) * n;
    if (is_walkable(n)) return r;
    const Real asked = std::max(Real(0), rest.dot(up));
    if (r.dot(up) > asked) r -= (r.dot(up) - asked) * up;
    Vec3 nh = n - n.dot(up) * up;
    if (nh.squaredNorm() > Real(1e-12)) {
      nh.normalize();
      r -= std::min(Real(0), r.dot(nh)) * nh;
    }
    return r;
  }

  // Step up: rise by step_height (as far as the ceiling allows), move the horizontal part of
  // `rest`, and settle down onto walkable ground. Taken only when it gets somewhere and lands.
  bool try_step(Vec3& pos, const Vec3& rest) const {
    const Vec3 h = rest - rest.dot(up) * up;
    if (!(def.step_height > 0) || h.norm() < Real(1e-5)) return false;
    Vec3 p = pos;
    advance(p, up * def.step_height);
    const Real rise = (p - pos).dot(up);
    if (rise <= def.skin) return false;
    const Vec3 before = p;
    advance(p, h);
    if ((p - before).dot(h) / h.norm() < Real(1e-4)) return false;
    const MoverHit land = advance(p, -up * (rise + 2 * def.skin));
    if (land.body == UINT32_MAX || !is_walkable(land.normal)) return false;
    pos = p;
    return true;
  }
};

void check_move(const Vec3& position, const Vec3& displacement, const CharacterMoveDef& def) {
  check_arg(position.allFinite(), "position", "must be finite");
  check_arg(displacement.allFinite(), "displacement", "must be finite");
  check_arg(std::isfinite(def.radius) && def.radius > 0, "radius", "must be finite and > 0");
  check_arg(std::isfinite(def.half_height) && def.half_height >= 0, "half_height",
            "must be finite and >= 0");
  check_arg(std::isfinite(def.step_height) && def.step_height >= 0, "step_height",
            "must be finite and >= 0");
  check_arg(def.max_slope >= 0 && def.max_slope < Real(1.5707963267948966), "max_slope",
            "must be in [0, pi/2)");
  check_arg(std::isfinite(def.skin) && def.skin > 0, "skin", "must be finite and > 0");
  check_arg(def.max_iterations >= 1 && def.max_iterations <= 64, "max_iterations",
            "must be in [1, 64]");
}

}  // namespace

}  // namespace elan::detail

namespace elan {

CharacterMoveResult World::move_character(const Vec3& position, const Vec3& displacement,
                                          const CharacterMoveDef& def) const {
  detail::check_move(position, displacement, def);
  const detail::WorldState& s = *state_;
  ShapeDef capsule_def;
  capsule_def.type = ShapeType::Capsule;
  capsule_def.radius = def.radius;
  capsule_def.half_height = std::max(def.half_height, Real(1e-4));
  const Vec3 g = s.def.gravity;
  const Vec3 up = g.squaredNorm() > 0 ? Vec3(-g.normalized()) : Vec3::UnitY();
  detail::Mover m{s,
                  def,
                  detail::make_shape(capsule_def),
                  detail::rotation_between(Vec3::UnitY(), up),
                  up,
                  def.skin / 2,
                  Real(detail::fixed_cos(def.max_slope))};

  Vec3 pos = position;
  Vec3 remaining = displacement;
  Vec3 first_normal = Vec3::Zero();
  for (int iter = 0; iter < def.max_iterations && remaining.norm() > Real(1e-6); ++iter) {
    const detail::MoverHit hit = m.cast(pos, remaining);
    const Real travel = m.safe_travel(hit, remaining);
    const Vec3 dir = remaining.normalized();
    pos += dir * travel;
    if (hit.body == UINT32_MAX) break;
    Vec3 rest = remaining - dir * travel;
    if (!m.is_walkable(hit.normal) && m.try_step(pos, rest)) {
      rest = rest.dot(up) * up;  // the horizontal part was taken by the step
      remaining = rest.dot(up) < 0 ? rest : Vec3::Zero();
      continue;
    }
    rest = m.clip(rest, hit.normal);
    // In a crease between this surface and the last, slide along their common edge.
    if (first_normal.squaredNorm() > 0 && rest.dot(first_normal) < 0) {
      const Vec3 edge = first_normal.cross(hit.normal);
      const Real e2 = edge.squaredNorm();
      rest = e2 > Real(1e-12) ? Vec3(edge * (rest.dot(edge) / e2)) : Vec3::Zero();
    }
    first_normal = hit.normal;
    remaining = rest;
  }

  CharacterMoveResult result;
  result.position = pos;
  // Ground: what a short probe down (twice the skin) meets, if walkable.
  const detail::MoverHit ground = m.cast(pos, -up * (2 * def.skin));
  if (ground.body != UINT32_MAX && m.is_walkable(ground.normal)) {
    result.on_ground = true;
    result.ground_normal = ground.normal;
    result.ground_body = detail::body_id_at(s, ground.body);
  }
  return result;
}

}  // namespace elan
