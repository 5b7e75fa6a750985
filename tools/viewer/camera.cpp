// SPDX-License-Identifier: MIT
#include "tools/viewer/camera.hpp"

#include <algorithm>
#include <cmath>

namespace elan::viewer {
namespace {

constexpr float kMaxPitch = 1.55f;  // just under 90 degrees: the view's up stays defined

// The eye's right, up and forward axes for looking from `eye` to `target` with world Y up (or
// -Z up when looking straight along Y).
void basis(const Eigen::Vector3f& eye, const Eigen::Vector3f& target, Eigen::Vector3f& right,
           Eigen::Vector3f& up, Eigen::Vector3f& forward) {
  forward = (target - eye).normalized();
  Eigen::Vector3f world_up = Eigen::Vector3f::UnitY();
  if (std::abs(forward.dot(world_up)) > 0.999f) world_up = -Eigen::Vector3f::UnitZ();
  right = forward.cross(world_up).normalized();
  up = right.cross(forward);
}

}  // namespace

Eigen::Vector3f Camera::eye() const {
  const float c = std::cos(pitch);
  return target + distance * Eigen::Vector3f(c * std::sin(yaw), std::sin(pitch), c * std::cos(yaw));
}

void Camera::look_at(const Eigen::Vector3f& e, const Eigen::Vector3f& t) {
  const Eigen::Vector3f d = e - t;
  target = t;
  distance = d.norm();
  pitch = std::asin(std::clamp(d.y() / distance, -1.0f, 1.0f));
  yaw = std::atan2(d.x(), d.z());
}

Eigen::Matrix4f Camera::view() const {
  const Eigen::Vector3f e = eye();
  Eigen::Vector3f r, u, f;
  basis(e, target, r, u, f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -r.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m;
}

Eigen::Matrix4f Camera::projection(float aspect) const {
  // Near and far scale with the distance so that depth precision follows the scene's size.
  const float n = std::max(0.01f, distance * 0.01f);
  const float f = std::max(2000.0f, distance * 50.0f);
  const float t = 1.0f / std::tan(fov_y / 2);
  Eigen::Matrix4f p = Eigen::Matrix4f::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = (f + n) / (n - f);
  p(2, 3) = 2 * f * n / (n - f);
  p(3, 2) = -1;
  return p;
}

void Camera::orbit(float dx, float dy) {
  yaw -= dx * 0.006f;
  pitch = std::clamp(pitch + dy * 0.006f, -kMaxPitch, kMaxPitch);
}

void Camera::pan(float dx, float dy, int viewport_height) {
  Eigen::Vector3f r, u, f;
  basis(eye(), target, r, u, f);
  // One pixel is this many metres at the target's depth.
  const float metres = 2 * distance * std::tan(fov_y / 2) / float(std::max(viewport_height, 1));
  target += (-dx * r + dy * u) * metres;
}

void Camera::zoom(float clicks) {
  distance = std::clamp(distance * std::pow(0.85f, clicks), 0.05f, 1e5f);
}

void Camera::frame(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, float aspect) {
  target = (lo + hi) / 2;
  const float radius = std::max(0.5f * (hi - lo).norm(), 0.1f);
  const float half_x = std::atan(std::tan(fov_y / 2) * aspect);
  const float half = std::min(fov_y / 2, half_x);
  // The sphere touches the view's edges at its tangent points; a box fills less of it, so the
  // distance that puts the sphere's radius at the edge (r / tan) frames it snugly.
  distance = radius / std::tan(half);
}

PixelRay Camera::ray(double x, double y, int w, int h) const {
  const Eigen::Vector3f e = eye();
  Eigen::Vector3f r, u, f;
  basis(e, target, r, u, f);
  const float nx = float(2 * x / std::max(w, 1) - 1);
  const float ny = float(1 - 2 * y / std::max(h, 1));
  const float t = std::tan(fov_y / 2);
  const float aspect = float(w) / float(std::max(h, 1));
  return {e, (f + nx * t * aspect * r + ny * t * u).normalized()};
}

}  // namespace elan::viewer
