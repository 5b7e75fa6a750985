// SPDX-License-Identifier: MIT
// The viewer's camera: an orbit around a target point (yaw, pitch, distance), Y up, with a
// perspective projection; pixel rays for picking.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace elan::viewer {

struct PixelRay {
  Eigen::Vector3f origin;
  Eigen::Vector3f direction;  ///< unit
};

struct Camera {
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  float distance = 10;      ///< m, eye to target
  float yaw = 0.6f;         ///< rad about +Y; 0 looks along -Z
  float pitch = 0.4f;       ///< rad above the horizon
  float fov_y = 0.785398f;  ///< vertical field of view, rad (45 degrees)

  Eigen::Vector3f eye() const;
  /// Places the eye and the target exactly (as --camera gives them).
  void look_at(const Eigen::Vector3f& eye, const Eigen::Vector3f& target);
  Eigen::Matrix4f view() const;
  Eigen::Matrix4f projection(float aspect) const;
  /// Mouse motion in pixels: orbit turns about the target, pan moves it in the view plane.
  void orbit(float dx, float dy);
  void pan(float dx, float dy, int viewport_height);
  /// Wheel clicks: each one moves the eye 15% of the distance closer (positive) or farther.
  void zoom(float clicks);
  /// Frames the box [lo, hi]: the target at its centre, the eye far enough that the box's
  /// bounding sphere fits the narrower field of view.
  void frame(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, float aspect);
  /// The ray from the eye through pixel (x, y) (origin top left) of a w x h viewport.
  PixelRay ray(double x, double y, int w, int h) const;
};

}  // namespace elan::viewer
