// SPDX-License-Identifier: MIT
#include "tools/viewer/picking.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace elan::viewer {

std::optional<PickHit> pick(const World& world, const PixelRay& ray) {
  QueryFilter filter;
  filter.include_sensors = true;
  const std::optional<RayHit> hit =
      world.cast_ray(ray.origin.cast<Real>(), ray.direction.cast<Real>(), Real(1e5), filter);
  if (!hit) return std::nullopt;
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId id = world.body_at(i);
    if (id.slot == hit->body.slot && id.generation == hit->body.generation) {
      return PickHit{i, hit->point};
    }
  }
  return std::nullopt;
}

Real drag_stiffness(const World& world) {
  std::vector<Real> masses;
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId id = world.body_at(i);
    if (world.motion_type(id) == MotionType::Dynamic) masses.push_back(world.mass(id));
  }
  Real m = 1;
  if (!masses.empty()) {
    std::nth_element(masses.begin(), masses.begin() + std::ptrdiff_t(masses.size() / 2),
                     masses.end());
    m = masses[masses.size() / 2];
  }
  const Real omega = Real(2 * 3.14159265358979 * 2.0);
  return m * omega * omega;
}

void Dragger::begin(const World& world, const PickHit& hit, const Camera& camera) {
  const BodyId id = world.body_at(hit.body);
  active_ = world.motion_type(id) == MotionType::Dynamic;
  if (!active_) return;
  body_ = hit.body;
  local_ = world.orientation(id).conjugate() * (hit.point - world.position(id));
  target_ = hit.point;
  plane_point_ = hit.point.cast<float>();
  plane_normal_ = (camera.target - camera.eye()).normalized();
}

void Dragger::move(const PixelRay& ray) {
  const float d = ray.direction.dot(plane_normal_);
  if (std::abs(d) < 1e-4f) return;
  const float t = (plane_point_ - ray.origin).dot(plane_normal_) / d;
  if (t > 0) target_ = (ray.origin + t * ray.direction).cast<Real>();
}

Vec3 Dragger::grab_point(const World& world) const {
  const BodyId id = world.body_at(body_);
  return world.position(id) + world.orientation(id) * local_;
}

void Dragger::apply(World& world, Real stiffness) const {
  if (!active_ || body_ >= world.body_count()) return;
  const BodyId id = world.body_at(body_);
  if (world.motion_type(id) != MotionType::Dynamic) return;
  const Vec3 p = grab_point(world);
  const Vec3 v =
      world.linear_velocity(id) + world.angular_velocity(id).cross(p - world.center_of_mass(id));
  const Real damping = 2 * std::sqrt(stiffness * world.mass(id));
  world.wake(id);
  world.apply_force_at(id, stiffness * (target_ - p) - damping * v, p);
}

}  // namespace elan::viewer
