// SPDX-License-Identifier: MIT
// World::debug_draw: walks the bodies, contacts and joints and calls the caller's drawer
// (elan/debug_draw.hpp) for what the flags select. Reads the world only; what it derives (boxes,
// colours) is computed per call, never cached.
#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>

#include "broadphase/bounds.hpp"
#include "core/world/events.hpp"
#include "core/world/world_access.hpp"
#include "elan/world.hpp"

namespace elan {

namespace {

constexpr DebugColor kStaticColor{0.5f, 0.5f, 0.55f, 1};
constexpr DebugColor kKinematicColor{0.35f, 0.55f, 0.95f, 1};
constexpr DebugColor kDynamicColor{0.95f, 0.6f, 0.25f, 1};
constexpr DebugColor kSensorColor{0.3f, 0.9f, 0.4f, 0.35f};
constexpr DebugColor kBoundsColor{0.9f, 0.9f, 0.2f, 1};
constexpr DebugColor kContactColor{1, 0.2f, 0.2f, 1};
constexpr DebugColor kNormalColor{1, 1, 1, 1};
constexpr DebugColor kJointColor{0.2f, 0.9f, 0.9f, 1};
constexpr DebugColor kCenterColor{1, 0.2f, 1, 1};
// m: a drawn contact normal's length.
constexpr Real kNormalLength = Real(0.2);

// A sleeping body's colour: the same hue at 40 % brightness.
DebugColor dimmed(DebugColor c) {
  return {0.4f * c.r, 0.4f * c.g, 0.4f * c.b, c.a};
}

// A colour per island, fixed by its root (lowest body index) alone: the golden-ratio walk round
// the hue circle keeps neighbouring roots apart. HSV to RGB at saturation 0.7, value 0.95.
DebugColor island_color(uint32_t root) {
  const double hue = std::fmod(double(root) * 0.6180339887498949, 1.0) * 6.0;
  const int sector = int(hue) % 6;
  const float f = float(hue - std::floor(hue));
  const float v = 0.95f, s = 0.7f;
  const float p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (sector) {
    case 0:
      return {v, t, p, 1};
    case 1:
      return {q, v, p, 1};
    case 2:
      return {p, v, t, 1};
    case 3:
      return {p, q, v, 1};
    case 4:
      return {t, p, v, 1};
    default:
      return {v, p, q, 1};
  }
}

// The half the last step's solver put body i in (0 or 1), or -1 when it was not split: not an
// awake dynamic body now, or not one of the last step's packets of the halves (split_halves:
// packet_of[i] in [half_start[0], half_start[kHalves]), and that packet's body is i; the packets
// are kept between steps, so nothing is recomputed or stored here).
int solver_half(const detail::WorldState& s, std::size_t i) {
  const detail::BodyStore& b = s.bodies;
  const detail::SolverState& st = s.solver;
  if (!b.is_dynamic(i) || !b.is_awake(i) || st.packet_of.size() != b.size()) return -1;
  const uint32_t p = st.packet_of[i];
  if (p < st.half_start[0] || p >= st.half_start[detail::kHalves] || p >= st.masses.size() ||
      st.masses[p].body != i) {
    return -1;
  }
  return p >= st.half_start[1] ? 1 : 0;
}

DebugColor body_color(const detail::WorldState& s, std::size_t i, bool by_island, bool by_half) {
  const detail::BodyStore& b = s.bodies;
  const bool sensor = (b.traits_of(i).flags & detail::kTraitSensor) != 0;
  if (by_half) {
    if (const int h = solver_half(s, i); h >= 0) {
      DebugColor c = kSolverHalfColors[h];
      if (sensor) c.a = kSensorColor.a;
      return c;
    }
  }
  if (sensor) return kSensorColor;
  const auto& root = s.solver.island_scratch.root;
  if (by_island && root.size() == b.size() && root[i] != UINT32_MAX) return island_color(root[i]);
  switch (MotionType(b.motion[i])) {
    case MotionType::Static:
      return kStaticColor;
    case MotionType::Kinematic:
      return kKinematicColor;
    case MotionType::Dynamic:
      break;
  }
  return kDynamicColor;
}

// A joint side's anchor in the world: the body's centre plus its principal-frame anchor turned
// to the world, or the world point itself for the static world.
Vec3 anchor_world(const detail::WorldState& s, uint32_t slot, const Vec3& anchor) {
  if (slot == detail::kWorldSlot) return anchor;
  const uint32_t i = s.slot_index[slot];
  return s.bodies.position(i) + s.bodies.orientation(i) * anchor;
}

}  // namespace

void World::debug_draw(DebugDrawer& drawer, uint32_t what) const {
  const detail::WorldState& s = *state_;
  const detail::BodyStore& b = s.bodies;
  const std::size_t n = b.size();
  for (std::size_t i = 0; i < n; ++i) {
    const detail::Shape& shape = s.shapes[b.shape[i]];
    const Quat q = b.orientation(i);
    const Vec3 p = b.position(i);
    const bool sleeping = b.is_dynamic(i) && !b.is_awake(i);
    if (what & (kDrawShapes | kDrawIslands | kDrawSolverHalves)) {
      // The shape frame: the store keeps the principal frame, x_principal = frame^-1 x_shape.
      const Quat user_q = (q * shape.frame_rotation.conjugate()).normalized();
      const Transform pose{p - user_q * shape.frame_position, user_q};
      DebugColor color =
          body_color(s, i, (what & kDrawIslands) != 0, (what & kDrawSolverHalves) != 0);
      if (sleeping) color = dimmed(color);
      const BodyId id = detail::body_id_at(s, uint32_t(i));
      drawer.draw_shape(id, shape_def(ShapeId{b.shape[i]}), pose, color, !sleeping);
    }
    if (what & kDrawBounds) {
      const detail::Aabb box = detail::shape_box(shape, p, q);
      drawer.draw_box(Aabb{box.min, box.max}, kBoundsColor);
    }
    if ((what & kDrawCentersOfMass) && b.is_dynamic(i)) drawer.draw_point(p, 6, kCenterColor);
  }
  if (what & (kDrawContacts | kDrawSolverHalves)) {
    const auto heads = s.contacts.heads();
    const auto tails = s.contacts.tails();
    std::size_t cursor = 0;
    for (const detail::ManifoldHead& h : heads) {
      // A contact of the cut joins two dynamic bodies of different halves (color_contacts'
      // kCutGroup).
      bool cut = false;
      if (what & kDrawSolverHalves) {
        const int half_a = solver_half(s, h.body_a), half_b = solver_half(s, h.body_b);
        cut = half_a >= 0 && half_b >= 0 && half_a != half_b;
      }
      if (!cut && !(what & kDrawContacts)) continue;
      const detail::Manifold m = detail::whole_at(h, tails, cursor);
      const Vec3 centre_a = b.position(m.body_a);
      for (uint32_t k = 0; k < m.point_count; ++k) {
        const Vec3 point = centre_a + m.points[k].anchor_a;
        drawer.draw_point(point, 5, cut ? kSolverCutColor : kContactColor);
        drawer.draw_line(point, point + kNormalLength * m.normal,
                         cut ? kSolverCutColor : kNormalColor);
      }
    }
  }
  if (what & kDrawJoints) {
    for (const detail::Joint& j : s.joints.joints) {
      const Vec3 a = anchor_world(s, j.slot_a, j.anchor_a);
      const Vec3 c = anchor_world(s, j.slot_b, j.anchor_b);
      if (j.slot_a != detail::kWorldSlot) {
        drawer.draw_line(b.position(s.slot_index[j.slot_a]), a, kJointColor);
      }
      if (j.slot_b != detail::kWorldSlot) {
        drawer.draw_line(b.position(s.slot_index[j.slot_b]), c, kJointColor);
      }
      drawer.draw_line(a, c, kJointColor);
      drawer.draw_point(a, 5, kJointColor);
      drawer.draw_point(c, 5, kJointColor);
    }
  }
}

}  // namespace elan
