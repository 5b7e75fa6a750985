// SPDX-License-Identifier: MIT
// Bullet 3 world built from an elan::Scene (same shapes, masses, materials, poses and joints),
// stepped the way Bullet users step it, so both engines can be timed on the same scene in one
// process.
#pragma once

#include <cstddef>
#include <memory>

#include "elan/scene.hpp"

namespace elan::peer {

struct BulletCounts {
  std::size_t manifolds = 0;  ///< persistent manifolds with at least one point
  std::size_t contacts = 0;   ///< contact points in all manifolds
  std::size_t awake = 0;      ///< active dynamic bodies
};

/// btDiscreteDynamicsWorld with btDbvtBroadphase and btSequentialImpulseConstraintSolver at its
/// default 10 iterations; one step of the scene's timestep per step() with no substeps. Bullet's
/// headers stay inside bullet_world.cpp.
class BulletWorld {
 public:
  explicit BulletWorld(const Scene& scene);
  ~BulletWorld();
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  void step();
  std::size_t body_count() const;
  /// Joints still in the world: those a break threshold has not disabled.
  std::size_t joint_count() const;
  /// Origin of body i's shape frame (as given in the scene), world, m.
  Vec3 position(std::size_t i) const;
  BulletCounts counts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace elan::peer
