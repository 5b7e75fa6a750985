// SPDX-License-Identifier: MIT
// The ragdoll generator: a humanoid 1.78 m tall, standing in a T-pose (arms out along x, so that
// no two parts overlap), facing +z with its left side toward +x. Each joint's anchor is where
// its two parts touch: the end of a capsule, a face of a box, the bottom of the head.
#include "core/scene/ragdoll.hpp"

#include <array>
#include <cmath>
#include <string>

namespace elan::detail::scene_file {
namespace {

struct Part {
  ShapeType type;
  double hx, hy, hz;  // box half extents; capsule and sphere: hx is the radius, hy half height
  double x, y, z;     // centre, standing, scale 1
  bool along_x;       // a capsule lying along x (the arms), else upright
};

// Parts 0 to 13, then the hands (14, 15) when asked for. Left parts at +x.
constexpr std::array<Part, 16> kParts = {{
    {ShapeType::Box, 0.16, 0.08, 0.10, 0, 1.00, 0, false},           // 0 pelvis
    {ShapeType::Box, 0.14, 0.10, 0.09, 0, 1.18, 0, false},           // 1 spine
    {ShapeType::Box, 0.17, 0.14, 0.10, 0, 1.42, 0, false},           // 2 chest
    {ShapeType::Sphere, 0.11, 0, 0, 0, 1.67, 0, false},              // 3 head
    {ShapeType::Capsule, 0.05, 0.10, 0, 0.32, 1.50, 0, true},        // 4 left upper arm
    {ShapeType::Capsule, 0.045, 0.09, 0, 0.605, 1.50, 0, true},      // 5 left forearm
    {ShapeType::Capsule, 0.05, 0.10, 0, -0.32, 1.50, 0, true},       // 6 right upper arm
    {ShapeType::Capsule, 0.045, 0.09, 0, -0.605, 1.50, 0, true},     // 7 right forearm
    {ShapeType::Capsule, 0.07, 0.14, 0, 0.10, 0.71, 0, false},       // 8 left thigh
    {ShapeType::Capsule, 0.05, 0.155, 0, 0.10, 0.295, 0, false},     // 9 left shin
    {ShapeType::Box, 0.05, 0.045, 0.12, 0.10, 0.045, 0.05, false},   // 10 left foot
    {ShapeType::Capsule, 0.07, 0.14, 0, -0.10, 0.71, 0, false},      // 11 right thigh
    {ShapeType::Capsule, 0.05, 0.155, 0, -0.10, 0.295, 0, false},    // 12 right shin
    {ShapeType::Box, 0.05, 0.045, 0.12, -0.10, 0.045, 0.05, false},  // 13 right foot
    {ShapeType::Box, 0.08, 0.025, 0.045, 0.82, 1.50, 0, false},      // 14 left hand
    {ShapeType::Box, 0.08, 0.025, 0.045, -0.82, 1.50, 0, false},     // 15 right hand
}};

// A joint of the child part (body A) to its parent (body B). Cone: axis along the child, away
// from the parent; `swing` its cone, [lo, hi] the twist. Hinge: [lo, hi] the bend, 0 straight.
struct Link {
  int child, parent;
  JointType type;
  double x, y, z;     // anchor, standing, scale 1
  double ax, ay, az;  // axis
  double swing, lo, hi;
};

// Ranges of motion of an adult, a little narrowed where a circular cone stands in for an oval
// one. The hinges' axes make a positive angle the natural bend: the knee's shin swings back
// (about +x), each forearm forward (the left about -y, the right about +y), the foot's toes down.
constexpr std::array<Link, 15> kLinks = {{
    {1, 0, JointType::Cone, 0, 1.08, 0, 0, 1, 0, 0.35, -0.3, 0.3},        // lower back
    {2, 1, JointType::Cone, 0, 1.28, 0, 0, 1, 0, 0.35, -0.3, 0.3},        // upper back
    {3, 2, JointType::Cone, 0, 1.56, 0, 0, 1, 0, 0.7, -1.2, 1.2},         // neck
    {4, 2, JointType::Cone, 0.17, 1.50, 0, 1, 0, 0, 1.6, -1.3, 1.3},      // left shoulder
    {5, 4, JointType::Hinge, 0.47, 1.50, 0, 0, -1, 0, 0, 0, 2.6},         // left elbow
    {6, 2, JointType::Cone, -0.17, 1.50, 0, -1, 0, 0, 1.6, -1.3, 1.3},    // right shoulder
    {7, 6, JointType::Hinge, -0.47, 1.50, 0, 0, 1, 0, 0, 0, 2.6},         // right elbow
    {8, 0, JointType::Cone, 0.10, 0.92, 0, 0, -1, 0, 1.2, -0.6, 0.6},     // left hip
    {9, 8, JointType::Hinge, 0.10, 0.50, 0, 1, 0, 0, 0, 0, 2.5},          // left knee
    {10, 9, JointType::Hinge, 0.10, 0.09, 0, 1, 0, 0, 0, -0.35, 0.87},    // left ankle
    {11, 0, JointType::Cone, -0.10, 0.92, 0, 0, -1, 0, 1.2, -0.6, 0.6},   // right hip
    {12, 11, JointType::Hinge, -0.10, 0.50, 0, 1, 0, 0, 0, 0, 2.5},       // right knee
    {13, 12, JointType::Hinge, -0.10, 0.09, 0, 1, 0, 0, 0, -0.35, 0.87},  // right ankle
    {14, 5, JointType::Cone, 0.74, 1.50, 0, 1, 0, 0, 0.9, -0.3, 0.3},     // left wrist
    {15, 7, JointType::Cone, -0.74, 1.50, 0, -1, 0, 0, 0.9, -0.3, 0.3},   // right wrist
}};

constexpr std::size_t kTorsoAndLimbs = 14;      // the parts and
constexpr std::size_t kTorsoAndLimbLinks = 13;  // the joints without the hands

// N m at scale 1: a tenth of a forearm's weight moment (1.5 kg at 13 cm): too little to hold a
// limb up, enough to stop it rocking once it lies.
constexpr double kJointFriction = 0.2;

}  // namespace

RagdollDef parse_ragdoll(const Ctx& ctx, const Json& j) {
  RagdollDef r;
  if (const auto it = j.find("orientation"); it != j.end()) {
    r.orientation = to_quat(ctx, *it, "orientation");
  }
  if (const auto it = j.find("scale"); it != j.end()) r.scale = positive(ctx, *it, "scale");
  if (const auto it = j.find("hands"); it != j.end()) r.hands = to_bool(ctx, *it, "hands");
  if (const auto it = j.find("joint_friction"); it != j.end()) {
    r.joint_friction = non_negative(ctx, *it, "joint_friction");
  }
  return r;
}

uint64_t ragdoll_bodies(const RagdollDef& r) {
  return r.hands ? kParts.size() : kTorsoAndLimbs;
}
uint64_t ragdoll_joints(const RagdollDef& r) {
  return r.hands ? kLinks.size() : kTorsoAndLimbLinks;
}

// Positions are computed in double and rounded once.
void expand_ragdoll(const RagdollDef& r, const Vec3& origin, std::vector<SceneBody>& bodies,
                    std::vector<SceneJoint>& joints) {
  const Eigen::Quaterniond q = r.orientation.cast<double>();
  const Eigen::Vector3d o = origin.cast<double>();
  const double s = double(r.scale);
  const auto place = [&](double x, double y, double z) -> Vec3 {
    return (o + q * (s * Eigen::Vector3d(x, y, z))).cast<Real>();
  };
  // A capsule's axis is its local Y: a quarter turn about z lays it along x.
  // (cos(-pi/4), 0, 0, sin(-pi/4)): exactly sqrt(1/2) each, without the C library's sin and cos,
  // whose last bit depends on the CPU (determinism, rule 7).
  const double half = std::sqrt(0.5);
  const Eigen::Quaterniond along_x(half, 0, 0, -half);
  const int first = int(bodies.size());
  const std::size_t parts = ragdoll_bodies(r);
  for (std::size_t i = 0; i < parts; ++i) {
    const Part& p = kParts[i];
    SceneBody b;
    b.shape.type = p.type;
    if (p.type == ShapeType::Box) {
      b.shape.half_extents = (s * Eigen::Vector3d(p.hx, p.hy, p.hz)).cast<Real>();
    } else {
      b.shape.radius = Real(s * p.hx);
      b.shape.half_height = Real(s * p.hy);
    }
    b.body.position = place(p.x, p.y, p.z);
    b.body.orientation = (p.along_x ? q * along_x : q).normalized().cast<Real>();
    bodies.push_back(std::move(b));
  }
  const std::size_t links = ragdoll_joints(r);
  for (std::size_t i = 0; i < links; ++i) {
    const Link& l = kLinks[i];
    SceneJoint j;
    j.body_a = first + l.child;
    j.body_b = first + l.parent;
    JointDef& d = j.def;
    d.type = l.type;
    d.anchor = place(l.x, l.y, l.z);
    d.axis = (q * Eigen::Vector3d(l.ax, l.ay, l.az)).normalized().cast<Real>();
    d.limits = JointLimits{true, Real(l.lo), Real(l.hi)};
    if (l.type == JointType::Cone) d.swing_limit = Real(l.swing);
    const double friction = r.joint_friction >= 0 ? double(r.joint_friction) : kJointFriction;
    d.friction = Real(friction * s * s * s * s);
    joints.push_back(std::move(j));
  }
}

}  // namespace elan::detail::scene_file
