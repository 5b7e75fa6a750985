// SPDX-License-Identifier: MIT
// Clicking and dragging bodies: the body under the cursor (a ray cast through the world's own
// query), and a soft spring from a point of the grabbed body to the cursor. The spring's
// stiffness is fixed for the scene (set for its typical dynamic body), so a light body follows
// the cursor briskly and a heavy one barely moves; its damping is the body's own critical
// damping, so nothing oscillates.
#pragma once

#include <cstddef>
#include <optional>

#include "elan/world.hpp"
#include "tools/viewer/camera.hpp"

namespace elan::viewer {

struct PickHit {
  std::size_t body = 0;  ///< dense index
  Vec3 point = Vec3::Zero();
};

/// The first body the ray enters (sensors included), or none.
std::optional<PickHit> pick(const World& world, const PixelRay& ray);

/// The spring's stiffness for a scene: k = m (2 pi f)^2 with m the median dynamic body mass and
/// f = 2 Hz, so the scene's typical body follows the cursor as a 2 Hz oscillator would.
Real drag_stiffness(const World& world);

class Dragger {
 public:
  /// Grabs body `hit.body` at `hit.point`; the cursor's plane faces the camera through it.
  void begin(const World& world, const PickHit& hit, const Camera& camera);
  /// The cursor moved: the target is where the cursor's ray meets the grab plane.
  void move(const PixelRay& ray);
  void end() { active_ = false; }
  bool active() const { return active_; }
  std::size_t body() const { return body_; }
  /// Applies the spring force for the next step: F = k (target - p) - c v_p at the grab point p,
  /// c = 2 zeta sqrt(k m) with zeta = 1 (critical damping of that body on that spring).
  void apply(World& world, Real stiffness) const;
  /// The grab point and the target, m, world (for the line drawn between them).
  Vec3 grab_point(const World& world) const;
  const Vec3& target() const { return target_; }

 private:
  bool active_ = false;
  std::size_t body_ = 0;
  Vec3 local_ = Vec3::Zero();  // grab point in the body's shape frame
  Vec3 target_ = Vec3::Zero();
  Eigen::Vector3f plane_normal_ = Eigen::Vector3f::UnitZ();
  Eigen::Vector3f plane_point_ = Eigen::Vector3f::Zero();
};

}  // namespace elan::viewer
