// SPDX-License-Identifier: MIT
// Scalar and fixed-size math types of the public API: Eigen types over `Real`.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace elan {

#ifdef ELAN_DOUBLE
using Real = double;
#else
using Real = float;
#endif

using Vec3 = Eigen::Matrix<Real, 3, 1>;
using Mat3 = Eigen::Matrix<Real, 3, 3>;
/// Unit quaternion; Eigen stores (x, y, z, w), the scene file writes [w, x, y, z].
using Quat = Eigen::Quaternion<Real>;

/// A rigid transform: x_world = rotation * x_local + position.
struct Transform {
  Vec3 position = Vec3::Zero();      ///< m, world frame
  Quat rotation = Quat::Identity();  ///< local to world
  Vec3 apply(const Vec3& p) const { return rotation * p + position; }
  Vec3 apply_inverse(const Vec3& p) const { return rotation.conjugate() * (p - position); }
};

}  // namespace elan
