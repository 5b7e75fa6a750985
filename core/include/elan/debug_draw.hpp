// SPDX-License-Identifier: MIT
// The debug-draw interface of the public API: World::debug_draw calls a caller's drawer for
// what it was asked to show (Box2D's b2DebugDraw, Jolt's DebugRenderer). The viewer is one such
// drawer; an embedder plugs in their own renderer.
#pragma once

#include <cstdint>

#include "elan/defs.hpp"
#include "elan/ids.hpp"
#include "elan/math.hpp"
#include "elan/queries.hpp"

namespace elan {

/// Linear RGBA, each in [0, 1].
struct DebugColor {
  float r = 1, g = 1, b = 1, a = 1;
};

/// What World::debug_draw shows: an OR of these bits.
enum DebugDrawFlags : uint32_t {
  kDrawShapes = 1u << 0,    ///< every body's shape, once, coloured by motion type (sleep dimmed)
  kDrawBounds = 1u << 1,    ///< every body's bounding box
  kDrawContacts = 1u << 2,  ///< contact points and their normals
  kDrawJoints = 1u << 3,    ///< joint anchors and the lines to the bodies
  kDrawIslands = 1u << 4,   ///< shapes coloured by island instead of by motion type
  kDrawCentersOfMass = 1u << 5,
  /// The last step's split of the solve in two (the simulated bodies cut at the median of their
  /// centres along the axis of largest spread; each half solved by one thread, then the
  /// contacts across the cut): every awake dynamic body's shape in the colour of its half
  /// (kSolverHalfColors), and the contact points of the cut, with their normals, in
  /// kSolverCutColor (drawn whether or not kDrawContacts is set, and instead of its colour).
  /// Bodies the last step did not split (asleep, static, kinematic, or any body before the
  /// first step) keep their colour by motion type; over kDrawIslands, a split body takes its
  /// half's colour. Only read from the last step, never recomputed: between a body's creation
  /// or destruction and the next step, the halves shown are absent or stale.
  kDrawSolverHalves = 1u << 6,
};

/// kDrawSolverHalves' colours: half 0 (the lower coordinates along the cut's axis) teal, half 1
/// purple, the contacts across the cut amber.
inline constexpr DebugColor kSolverHalfColors[2] = {{0.15f, 0.75f, 0.7f, 1}, {0.7f, 0.3f, 0.9f, 1}};
inline constexpr DebugColor kSolverCutColor{1, 0.75f, 0, 1};

/// The caller's renderer. Calls come from the thread that calls World::debug_draw, in body index
/// order, then contacts in pair order, then joints in index order.
class DebugDrawer {
 public:
  virtual ~DebugDrawer() = default;
  /// A body's whole shape (its definition, in the shape's own frame) at `pose` (shape frame to
  /// world). `awake` is false for a sleeping body. A heightfield's NaN heights are holes: the
  /// triangles with one at a corner are not there.
  virtual void draw_shape(BodyId body, const ShapeDef& shape, const Transform& pose,
                          DebugColor color, bool awake) = 0;
  virtual void draw_line(const Vec3& a, const Vec3& b, DebugColor color) = 0;
  virtual void draw_point(const Vec3& p, float size_pixels, DebugColor color) = 0;
  virtual void draw_box(const Aabb& box, DebugColor color) = 0;
};

}  // namespace elan
