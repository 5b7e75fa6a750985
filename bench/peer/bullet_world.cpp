// SPDX-License-Identifier: MIT
// Builds a Bullet 3 world from an elan::Scene: Bullet's own shapes, mass from density x volume as
// elan computes it, elan's material mixing and damping law, sleeping as the scene asks, and the
// scene's joints as Bullet's constraints (the mapping is in docs/benchmarks.md, "Joints in
// Bullet").
#include "bench/peer/bullet_world.hpp"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <LinearMath/btConvexHullComputer.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace elan::peer {
namespace {

btVector3 to_bt(const Vec3& v) {
  return {btScalar(v.x()), btScalar(v.y()), btScalar(v.z())};
}

// Bullet's default collision margin. A btConvexHullShape adds its margin outside the points, so
// the points are first shrunk by it (btConvexHullComputer's shrink, as Bullet's demos do): the
// collision hull is then the scene's hull with edges rounded by the margin.
constexpr btScalar kHullMargin = btScalar(0.04);

// elan mixes friction as sqrt(f1 f2) and restitution as max(e1, e2) (README); Bullet multiplies
// both by default, so the peer is given elan's rules through Bullet's global hooks.
btScalar mix_friction(const btCollisionObject* a, const btCollisionObject* b) {
  return std::sqrt(a->getFriction() * b->getFriction());
}
btScalar mix_restitution(const btCollisionObject* a, const btCollisionObject* b) {
  return std::max(a->getRestitution(), b->getRestitution());
}

struct Hull {
  std::vector<btVector3> points;  // shrunk, relative to the centre of mass
  double volume = 0;              // m^3, of the unshrunk hull
  btVector3 com{0, 0, 0};         // m, shape frame
  btScalar margin = kHullMargin;
};

// Volume and centroid of the hull as a sum of signed tetrahedra (origin, fan triangle of a face).
Hull make_hull(const std::vector<Vec3>& cloud) {
  std::vector<btScalar> xyz;
  for (const Vec3& p : cloud)
    xyz.insert(xyz.end(), {btScalar(p.x()), btScalar(p.y()), btScalar(p.z())});
  const int stride = 3 * sizeof(btScalar), n = int(cloud.size());
  btConvexHullComputer full;
  full.compute(xyz.data(), stride, n, 0, 0);
  Hull h;
  double cx = 0, cy = 0, cz = 0;
  for (int f = 0; f < full.faces.size(); ++f) {
    const btConvexHullComputer::Edge* first = &full.edges[full.faces[f]];
    const btVector3& a = full.vertices[first->getSourceVertex()];
    for (const btConvexHullComputer::Edge* e = first->getNextEdgeOfFace();
         e->getTargetVertex() != first->getSourceVertex(); e = e->getNextEdgeOfFace()) {
      const btVector3& b = full.vertices[e->getSourceVertex()];
      const btVector3& c = full.vertices[e->getTargetVertex()];
      const double v = double(a.dot(b.cross(c))) / 6;
      h.volume += v;
      cx += v * double(a.x() + b.x() + c.x()) / 4;
      cy += v * double(a.y() + b.y() + c.y()) / 4;
      cz += v * double(a.z() + b.z() + c.z()) / 4;
    }
  }
  if (h.volume == 0) throw std::runtime_error("bullet peer: degenerate convex hull");
  h.com = btVector3(btScalar(cx / h.volume), btScalar(cy / h.volume), btScalar(cz / h.volume));
  h.volume = std::abs(h.volume);
  btConvexHullComputer shrunk;
  const btScalar s = shrunk.compute(xyz.data(), stride, n, kHullMargin, btScalar(0.25));
  const btConvexHullComputer& use = s > 0 ? shrunk : full;
  h.margin = s > 0 ? s : btScalar(0.001);
  for (int i = 0; i < use.vertices.size(); ++i) h.points.push_back(use.vertices[i] - h.com);
  return h;
}

double volume_of(const ShapeDef& s) {
  constexpr double pi = std::numbers::pi;
  const double r = s.radius, hh = s.half_height;
  switch (s.type) {
    case ShapeType::Sphere:
      return 4.0 / 3.0 * pi * r * r * r;
    case ShapeType::Box:
      return 8.0 * s.half_extents.x() * s.half_extents.y() * s.half_extents.z();
    case ShapeType::Capsule:
      return pi * r * r * 2 * hh + 4.0 / 3.0 * pi * r * r * r;
    case ShapeType::Cylinder:
      return pi * r * r * 2 * hh;
    default:
      return 0;
  }
}

// A frame at `origin` whose column `column` (0: X, 2: Z) is `axis`, the other two any
// perpendicular pair: Bullet's hinge turns about its frames' Z, its slider, cone twist and the
// 6-DOF free axis used below are X.
btTransform axis_frame(const btVector3& origin, const btVector3& axis, int column) {
  btVector3 u, v;
  btPlaneSpace1(axis, u, v);  // u, v, axis right-handed
  btMatrix3x3 basis;
  if (column == 0) {
    basis.setValue(axis.x(), u.x(), v.x(), axis.y(), u.y(), v.y(), axis.z(), u.z(), v.z());
  } else {
    basis.setValue(u.x(), v.x(), axis.x(), u.y(), v.y(), axis.y(), u.z(), v.z(), axis.z());
  }
  return btTransform(basis, origin);
}

// Inverse effective mass of the two bodies along a linear direction at the given arms (m from the
// centre of mass, world) and about an angular direction: J M^-1 J^T of one constraint row.
btScalar inverse_mass_along(const btRigidBody& a, const btRigidBody& b, const btVector3& lin,
                            const btVector3& arm_a, const btVector3& arm_b, const btVector3& ang) {
  const auto one = [&](const btRigidBody& body, const btVector3& arm) {
    const btVector3 w = arm.cross(lin) + ang;
    return body.getInvMass() * lin.length2() + w.dot(body.getInvInertiaTensorWorld() * w);
  };
  return one(a, arm_a) + one(b, arm_b);
}

// A distance joint: one row along the line between the anchors, |pB - pA| kept in
// [min_length, max_length]. Bullet has no such constraint (a 6-DOF limit along a frame axis
// turns that axis with body A, so it constrains a projection, not the distance); this is the same
// row btPoint2PointConstraint writes, along the anchors' line only, solved by Bullet's own solver.
class DistanceConstraint final : public btTypedConstraint {
 public:
  DistanceConstraint(btRigidBody& a, btRigidBody& b, const btVector3& local_a,
                     const btVector3& local_b, btScalar min_length, btScalar max_length)
      // No Bullet type fits; the type is read only by debug drawing and serialization, which
      // skip a type they do not know.
      : btTypedConstraint(MAX_CONSTRAINT_TYPE, a, b),
        local_a_(local_a),
        local_b_(local_b),
        min_(min_length),
        max_(max_length) {}

  void getInfo1(btConstraintInfo1* info) override {
    const btScalar len = (world_b() - world_a()).length();
    info->m_numConstraintRows = (min_ == max_ || len <= min_ || len >= max_) ? 1 : 0;
    info->nub = 6 - info->m_numConstraintRows;
  }

  void getInfo2(btConstraintInfo2* info) override {
    const btVector3 pa = world_a(), pb = world_b();
    const btVector3 d = pb - pa;
    const btScalar len = d.length();
    if (len > btScalar(1e-6)) normal_ = d / len;
    const btVector3 ra = pa - m_rbA.getCenterOfMassPosition();
    const btVector3 rb = pb - m_rbB.getCenterOfMassPosition();
    const btVector3 ja = -ra.cross(normal_), jb = rb.cross(normal_);
    for (int k = 0; k < 3; ++k) {
      info->m_J1linearAxis[k] = -normal_[k];
      info->m_J1angularAxis[k] = ja[k];
      if (info->m_J2linearAxis) info->m_J2linearAxis[k] = normal_[k];
      info->m_J2angularAxis[k] = jb[k];
    }
    // J v = -erp/dt C drives the length back into range; a one-sided range (rope, strut) only
    // pulls or only pushes.
    const btScalar target = std::clamp(len, min_, max_);
    info->m_constraintError[0] = info->fps * info->erp * (target - len);
    if (min_ == max_) {
      info->m_lowerLimit[0] = -SIMD_INFINITY;
      info->m_upperLimit[0] = SIMD_INFINITY;
    } else if (len >= max_) {
      info->m_lowerLimit[0] = -SIMD_INFINITY;
      info->m_upperLimit[0] = 0;
    } else {
      info->m_lowerLimit[0] = 0;
      info->m_upperLimit[0] = SIMD_INFINITY;
    }
  }

  void setParam(int, btScalar, int) override {}
  btScalar getParam(int, int) const override { return 0; }

  btVector3 world_a() const { return m_rbA.getCenterOfMassTransform() * local_a_; }
  btVector3 world_b() const { return m_rbB.getCenterOfMassTransform() * local_b_; }

 private:
  btVector3 local_a_, local_b_;
  btScalar min_, max_;
  btVector3 normal_{0, 1, 0};
};

// A spring-damper between two anchor points along their line, as a force applied before each
// step: Bullet's springs (btGeneric6DofSpring2Constraint) act along a frame axis of body A, not
// along the line, so they cannot pull toward a rest length.
struct DistanceSpring {
  DistanceConstraint* joint;
  btScalar stiffness, damping, rest;
};

// A triangle mesh's arrays, in the layout btTriangleIndexVertexArray reads.
struct MeshArrays {
  std::vector<int> indices;
  std::vector<btScalar> vertices;
  std::unique_ptr<btTriangleIndexVertexArray> array;
};

// A Bullet shape made from a scene shape: its volume (m^3, 0 for surfaces), its frame in the
// scene's shape frame, and for a compound the inertia per kg in that frame.
struct BuiltShape {
  btCollisionShape* shape = nullptr;
  double volume = 0;
  btTransform frame = btTransform::getIdentity();
  bool has_unit_inertia = false;
  btVector3 unit_inertia{0, 0, 0};
};

btTransform pose_of(const Vec3& position, const Quat& q) {
  btQuaternion rotation(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w()));
  return btTransform(rotation.normalize(), to_bt(position));
}

// A compound's identity for sharing: every number of every child, in order, as hex floats.
std::string compound_key(const ShapeDef& s) {
  std::string key;
  char buf[64];
  const auto add = [&](double v) {
    std::snprintf(buf, sizeof buf, "%a,", v);
    key += buf;
  };
  for (const CompoundChild& c : s.children) {
    add(double(int(c.shape.type)));
    add(c.shape.radius);
    add(c.shape.half_height);
    for (int i = 0; i < 3; ++i) add(c.shape.half_extents[i]);
    for (const Vec3& p : c.shape.points)
      for (int i = 0; i < 3; ++i) add(p[i]);
    for (int i = 0; i < 3; ++i) add(c.position[i]);
    for (int i = 0; i < 4; ++i) add(c.orientation.coeffs()[i]);
    key += ';';
  }
  return key;
}

}  // namespace

struct BulletWorld::Impl {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  // The arrays Bullet's mesh and heightfield shapes read in place; declared before `shapes` so
  // they outlive them.
  std::vector<std::unique_ptr<MeshArrays>> meshes;
  std::vector<std::unique_ptr<std::vector<float>>> heights;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  // Body i's frame (Bullet's body frame: the centre of mass, principal axes for a compound, the
  // centre of a heightfield's bounds) in the scene's shape frame.
  std::vector<btTransform> frames;
  // Identical compounds share one Bullet shape (the scenes' grids copy one compound many times).
  std::map<std::string, BuiltShape> compounds;

  BuiltShape build(const ShapeDef& s);
  BuiltShape build_compound(const ShapeDef& s);
  struct Kinematic {
    btRigidBody* body;
    btVector3 v, w;
  };
  std::vector<Kinematic> kinematic;
  std::vector<std::unique_ptr<btTypedConstraint>> joints;
  std::vector<DistanceSpring> springs;
  btScalar dt = 0;

  void add_joints(const Scene& scene);

  ~Impl() {
    // Constraints first: removing one drops its references from both bodies, and Bullet's shared
    // fixed body (the world side of a joint to the world) outlives this world.
    for (auto& j : joints) world.removeConstraint(j.get());
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
};

BulletWorld::BulletWorld(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  gCalculateCombinedFrictionCallback = &mix_friction;
  gCalculateCombinedRestitutionCallback = &mix_restitution;
  Impl& m = *impl_;
  m.dt = btScalar(scene.timestep);
  m.world.setGravity(to_bt(scene.world.gravity));
  // Identical primitive shapes are shared, as elan's load_into shares identical definitions.
  std::map<std::tuple<int, double, double, double, double, double>, btCollisionShape*> shared;
  for (const SceneBody& sb : scene.bodies) {
    const ShapeDef& s = sb.shape;
    const BodyDef& d = sb.body;
    BuiltShape built;
    if (s.type == ShapeType::Sphere || s.type == ShapeType::Box || s.type == ShapeType::Capsule ||
        s.type == ShapeType::Cylinder) {
      const auto key = std::make_tuple(int(s.type), double(s.radius), double(s.half_height),
                                       double(s.half_extents.x()), double(s.half_extents.y()),
                                       double(s.half_extents.z()));
      auto it = shared.find(key);
      if (it != shared.end()) {
        built.shape = it->second;
        built.volume = volume_of(s);
      } else {
        built = m.build(s);
        shared[key] = built.shape;
      }
    } else if (s.type == ShapeType::Compound) {
      built = m.build_compound(s);
    } else {
      built = m.build(s);
    }
    btCollisionShape* shape = built.shape;
    const double volume = built.volume;
    const bool dynamic = d.motion == MotionType::Dynamic;
    const btScalar mass = dynamic ? btScalar(d.mass ? double(*d.mass) : d.density * volume) : 0;
    btVector3 inertia(0, 0, 0);
    if (dynamic && built.has_unit_inertia) {
      inertia = built.unit_inertia * mass;
    } else if (dynamic) {
      shape->calculateLocalInertia(mass, inertia);
    }
    const btTransform pose = pose_of(d.position, d.orientation) * built.frame;
    btDefaultMotionState* motion_state = nullptr;
    if (d.motion == MotionType::Kinematic) {
      motion_state = new btDefaultMotionState(pose);
      m.motion_states.emplace_back(motion_state);
    }
    btRigidBody::btRigidBodyConstructionInfo info(mass, motion_state, shape, inertia);
    info.m_startWorldTransform = pose;
    info.m_friction = btScalar(d.friction);
    info.m_restitution = btScalar(d.restitution);
    // elan's damping d (1/s) means dv/dt = -d v, so v *= exp(-d dt); Bullet applies
    // v *= (1 - c)^dt, hence c = 1 - exp(-d).
    info.m_linearDamping = btScalar(1 - std::exp(-double(d.linear_damping)));
    info.m_angularDamping = btScalar(1 - std::exp(-double(d.angular_damping)));
    auto* body = new btRigidBody(info);
    m.bodies.emplace_back(body);
    m.frames.push_back(built.frame);
    if (dynamic) {
      body->setLinearVelocity(to_bt(d.linear_velocity));
      body->setAngularVelocity(to_bt(d.angular_velocity));
      if (!scene.world.allow_sleep) {
        body->setActivationState(DISABLE_DEACTIVATION);
      } else if (!d.awake) {
        body->setActivationState(ISLAND_SLEEPING);
      }
    } else if (d.motion == MotionType::Kinematic) {
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      body->setActivationState(DISABLE_DEACTIVATION);
      m.kinematic.push_back({body, to_bt(d.linear_velocity), to_bt(d.angular_velocity)});
    }
    if (d.category_bits == 1 && d.mask_bits == UINT32_MAX) {
      m.world.addRigidBody(body);  // Bullet's default groups: static bodies skip each other
    } else {
      m.world.addRigidBody(body, int(d.category_bits), int(d.mask_bits));
    }
  }
  m.add_joints(scene);
}

BuiltShape BulletWorld::Impl::build(const ShapeDef& s) {
  BuiltShape b;
  switch (s.type) {
    case ShapeType::Sphere:
      b.shape = new btSphereShape(btScalar(s.radius));
      break;
    case ShapeType::Box:
      b.shape = new btBoxShape(to_bt(s.half_extents));
      break;
    // Bullet's capsule height is the segment length, 2 * half_height; axis Y as elan's.
    case ShapeType::Capsule:
      b.shape = new btCapsuleShape(btScalar(s.radius), btScalar(2 * s.half_height));
      break;
    case ShapeType::Cylinder:
      b.shape = new btCylinderShape(
          btVector3(btScalar(s.radius), btScalar(s.half_height), btScalar(s.radius)));
      break;
    case ShapeType::ConvexHull: {
      const Hull h = make_hull(s.points);
      auto* hull = new btConvexHullShape(&h.points[0].x(), int(h.points.size()), sizeof(btVector3));
      hull->setMargin(h.margin);
      b.shape = hull;
      b.volume = h.volume;
      b.frame.setOrigin(h.com);
      shapes.emplace_back(b.shape);
      return b;
    }
    case ShapeType::Plane:
      b.shape = new btStaticPlaneShape(to_bt(s.normal).normalized(), btScalar(s.offset));
      break;
    case ShapeType::Mesh: {
      // btBvhTriangleMeshShape over the scene's own arrays (Bullet reads them in place).
      auto arrays = std::make_unique<MeshArrays>();
      for (const Vec3& v : s.vertices)
        arrays->vertices.insert(arrays->vertices.end(),
                                {btScalar(v.x()), btScalar(v.y()), btScalar(v.z())});
      for (const auto& t : s.triangles)
        arrays->indices.insert(arrays->indices.end(), {int(t[0]), int(t[1]), int(t[2])});
      arrays->array = std::make_unique<btTriangleIndexVertexArray>(
          int(s.triangles.size()), arrays->indices.data(), int(3 * sizeof(int)),
          int(s.vertices.size()), arrays->vertices.data(), int(3 * sizeof(btScalar)));
      b.shape = new btBvhTriangleMeshShape(arrays->array.get(), true);
      meshes.push_back(std::move(arrays));
      break;
    }
    case ShapeType::Heightfield: {
      // Bullet's heightfield puts its local origin at the centre of its bounds, so the body's
      // frame is that centre in the scene's shape frame; flipQuadEdges splits each cell along the
      // diagonal (i, j) - (i+1, j+1), as elan's heightfield does, so both are one surface.
      // btHeightfieldTerrainShape has no holes: a scene with one is not a scene both can run.
      if (std::any_of(s.heights.begin(), s.heights.end(), [](Real h) { return std::isnan(h); })) {
        throw std::runtime_error("bullet peer: a heightfield with holes (Bullet's has none)");
      }
      auto data = std::make_unique<std::vector<float>>(s.heights.begin(), s.heights.end());
      const auto [lo, hi] = std::minmax_element(data->begin(), data->end());
      const int columns = int(s.columns), rows = int(s.heights.size() / s.columns);
      auto* field = new btHeightfieldTerrainShape(columns, rows, data->data(), btScalar(*lo),
                                                  btScalar(*hi), 1, true);
      field->setLocalScaling(btVector3(btScalar(s.spacing_x), 1, btScalar(s.spacing_z)));
      b.frame.setOrigin(btVector3(btScalar(0.5 * (columns - 1) * double(s.spacing_x)),
                                  btScalar(0.5 * (double(*lo) + double(*hi))),
                                  btScalar(0.5 * (rows - 1) * double(s.spacing_z))));
      b.shape = field;
      heights.push_back(std::move(data));
      break;
    }
    case ShapeType::Compound:
      return build_compound(s);
  }
  if (s.type <= ShapeType::Cylinder) b.volume = volume_of(s);
  shapes.emplace_back(b.shape);
  return b;
}

// A btCompoundShape of the children at their poses, moved to its principal frame
// (calculatePrincipalAxisTransform over the children's masses at unit density), so that Bullet's
// body frame is the centre of mass with the compound's principal inertia, as elan's is.
BuiltShape BulletWorld::Impl::build_compound(const ShapeDef& s) {
  const std::string key = compound_key(s);
  if (const auto it = compounds.find(key); it != compounds.end()) return it->second;
  auto* compound = new btCompoundShape(true, int(s.children.size()));
  std::vector<btScalar> masses;
  double volume = 0;
  for (const CompoundChild& c : s.children) {
    const BuiltShape child = build(c.shape);
    compound->addChildShape(pose_of(c.position, c.orientation) * child.frame, child.shape);
    masses.push_back(btScalar(child.volume));
    volume += child.volume;
  }
  btTransform principal;
  btVector3 inertia;
  compound->calculatePrincipalAxisTransform(masses.data(), principal, inertia);
  const btTransform to_principal = principal.inverse();
  for (int k = 0; k < compound->getNumChildShapes(); ++k) {
    compound->updateChildTransform(k, to_principal * compound->getChildTransform(k), false);
  }
  compound->recalculateLocalAabb();
  shapes.emplace_back(compound);
  BuiltShape b;
  b.shape = compound;
  b.volume = volume;
  b.frame = principal;
  b.has_unit_inertia = true;
  b.unit_inertia = inertia / btScalar(volume);  // the masses were the volumes (density 1)
  compounds.emplace(key, b);
  return b;
}

void BulletWorld::Impl::add_joints(const Scene& scene) {
  for (const SceneJoint& sj : scene.joints) {
    const JointDef& d = sj.def;
    btRigidBody& a = *bodies.at(std::size_t(sj.body_a));
    // The world side: Bullet's shared static body at the origin, so a frame in it is a world
    // frame (what the single-body constructors use internally).
    btRigidBody& b =
        sj.body_b < 0 ? btTypedConstraint::getFixedBody() : *bodies.at(std::size_t(sj.body_b));
    // Bullet's body frame is the centre of mass (a hull's is off its shape origin): a world frame
    // seen from each body.
    const btTransform ta_inv = a.getCenterOfMassTransform().inverse();
    const btTransform tb_inv = b.getCenterOfMassTransform().inverse();
    const btVector3 anchor = to_bt(d.anchor);
    const btVector3 axis = to_bt(d.axis).normalized();
    const JointLimits& lim = d.limits;
    const JointMotor& motor = d.motor;
    const JointSpring& spring = d.spring;
    // The spring's stiffness and damping from its frequency and damping ratio over the joint's
    // effective mass along the driven coordinate at load.
    const auto spring_gains = [&](btScalar inv_mass) {
      const double omega = 2 * std::numbers::pi * double(spring.frequency);
      const double mass = inv_mass > 0 ? 1 / double(inv_mass) : 0;
      return std::make_pair(btScalar(mass * omega * omega),
                            btScalar(2 * double(spring.damping_ratio) * mass * omega));
    };
    // A hinge or slider with a spring: btHingeConstraint and btSliderConstraint have none, so a
    // btGeneric6DofSpring2Constraint with every axis locked but the joint's (`free`: 0 = X
    // translation, 3 = X rotation). Its X rotation is elan's angle (A relative to B); its X
    // translation is B's relative to A, elan's negated, so linear limits and target are negated.
    // Its motor drives A relative to B along both, and its bound is a force (this Bullet divides
    // it by the step rate).
    const auto six_dof = [&](int free, btScalar inv_mass) {
      const btScalar sign = free < 3 ? -1 : 1;
      const btTransform f = axis_frame(anchor, axis, 0);
      auto g = std::make_unique<btGeneric6DofSpring2Constraint>(a, b, ta_inv * f, tb_inv * f);
      g->setLinearLowerLimit(btVector3(0, 0, 0));
      g->setLinearUpperLimit(btVector3(0, 0, 0));
      g->setAngularLowerLimit(btVector3(0, 0, 0));
      g->setAngularUpperLimit(btVector3(0, 0, 0));
      if (lim.enabled) {
        const btScalar x = sign * btScalar(lim.lower), y = sign * btScalar(lim.upper);
        g->setLimit(free, std::min(x, y), std::max(x, y));
      } else {
        g->setLimit(free, 1, -1);  // lower > upper: free
      }
      if (motor.enabled) {
        g->enableMotor(free, true);
        g->setTargetVelocity(free, btScalar(motor.speed));
        g->setMaxMotorForce(free, btScalar(motor.max_force));
      }
      const auto [k, c] = spring_gains(inv_mass);
      g->enableSpring(free, true);
      g->setStiffness(free, k);
      g->setDamping(free, c);
      g->setEquilibriumPoint(free, sign * btScalar(spring.target));
      return g;
    };
    const btVector3 arm_a = anchor - a.getCenterOfMassPosition();
    const btVector3 arm_b = anchor - b.getCenterOfMassPosition();
    const btVector3 zero(0, 0, 0);
    std::unique_ptr<btTypedConstraint> c;
    switch (d.type) {
      case JointType::Ball:
        c = std::make_unique<btPoint2PointConstraint>(a, b, ta_inv(anchor), tb_inv(anchor));
        break;
      case JointType::Hinge:
        if (spring.enabled) {
          c = six_dof(3, inverse_mass_along(a, b, zero, arm_a, arm_b, axis));
        } else {
          // Bullet's hinge angle (useReferenceFrameA = false) is A's about Z relative to B, and
          // its motor drives A's rate relative to B: elan's convention, no sign change.
          const btTransform f = axis_frame(anchor, axis, 2);
          auto h = std::make_unique<btHingeConstraint>(a, b, ta_inv * f, tb_inv * f, false);
          if (lim.enabled) h->setLimit(btScalar(lim.lower), btScalar(lim.upper));
          // Bullet's bound is an impulse per step.
          if (motor.enabled)
            h->enableAngularMotor(true, btScalar(motor.speed), btScalar(motor.max_force) * dt);
          c = std::move(h);
        }
        break;
      case JointType::Slider:
        if (spring.enabled) {
          c = six_dof(0, inverse_mass_along(a, b, axis, zero, zero, zero));
        } else {
          // Bullet's slider axis is its frames' X, and its position is B's relative to A along
          // it (useLinearReferenceFrameA = true): limits and motor speed negated.
          const btTransform f = axis_frame(anchor, axis, 0);
          auto sl = std::make_unique<btSliderConstraint>(a, b, ta_inv * f, tb_inv * f, true);
          sl->setLowerAngLimit(0);
          sl->setUpperAngLimit(0);
          if (lim.enabled) {
            sl->setLowerLinLimit(-btScalar(lim.upper));
            sl->setUpperLinLimit(-btScalar(lim.lower));
          } else {
            sl->setLowerLinLimit(1);  // lower > upper: free
            sl->setUpperLinLimit(-1);
          }
          if (motor.enabled) {
            sl->setPoweredLinMotor(true);
            sl->setTargetLinMotorVelocity(-btScalar(motor.speed));
            // A force: this Bullet bounds the motor's impulse by it over the step rate.
            sl->setMaxLinMotorForce(btScalar(motor.max_force));
          }
          c = std::move(sl);
        }
        break;
      case JointType::Fixed: {
        // Without an anchor, elan welds at the midpoint of the two shape frames (A's alone when
        // B is the world); where the weld's frame sits changes only how errors are shared.
        btVector3 at = anchor;
        if (!d.has_anchor) {
          const Vec3 pa = scene.bodies[std::size_t(sj.body_a)].body.position;
          const Vec3 pb = sj.body_b < 0 ? pa : scene.bodies[std::size_t(sj.body_b)].body.position;
          at = to_bt(Vec3((pa + pb) / 2));
        }
        const btTransform f(btMatrix3x3::getIdentity(), at);
        c = std::make_unique<btFixedConstraint>(a, b, ta_inv * f, tb_inv * f);
        break;
      }
      case JointType::Distance: {
        const btVector3 on_b = to_bt(d.anchor_b);
        const btScalar at_load = (on_b - anchor).length();
        const btScalar lo = d.min_length < 0 ? at_load : btScalar(d.min_length);
        const btScalar hi = d.max_length < 0 ? at_load : btScalar(d.max_length);
        auto dc = std::make_unique<DistanceConstraint>(a, b, ta_inv(anchor), tb_inv(on_b), lo, hi);
        if (spring.enabled) {
          const btVector3 n = at_load > 0 ? (on_b - anchor) / at_load : btVector3(0, 1, 0);
          const auto [k, cd] = spring_gains(
              inverse_mass_along(a, b, n, arm_a, on_b - b.getCenterOfMassPosition(), zero));
          springs.push_back(
              {dc.get(), k, cd, spring.target < 0 ? at_load : btScalar(spring.target)});
        }
        c = std::move(dc);
        break;
      }
      case JointType::Cone: {
        // Bullet's twist axis is its frames' X and its twist limit is symmetric, +-span about
        // the frames' zero: B's frame is turned about X by the middle of elan's [lower, upper],
        // so +-(upper - lower) / 2 about it is elan's range. Swing: both spans = swing_limit
        // (a circular cone). Unlimited twist: a span of pi, since the twist is in (-pi, pi].
        const btTransform fa = axis_frame(anchor, axis, 0);
        btTransform fb = fa;
        btScalar span = SIMD_PI;
        if (lim.enabled) {
          span = btScalar(lim.upper - lim.lower) / 2;
          fb.setBasis(
              fa.getBasis() *
              btMatrix3x3(btQuaternion(btVector3(1, 0, 0), btScalar(lim.upper + lim.lower) / 2)));
        }
        auto cone = std::make_unique<btConeTwistConstraint>(a, b, ta_inv * fa, tb_inv * fb);
        cone->setLimit(btScalar(d.swing_limit), btScalar(d.swing_limit), span);
        c = std::move(cone);
        break;
      }
    }
    // Bullet compares each row's impulse of one step with the threshold; elan, the joint's force.
    if (std::isfinite(double(d.break_force)))
      c->setBreakingImpulseThreshold(btScalar(d.break_force) * dt);
    world.addConstraint(c.get(), !d.collide_connected);
    joints.push_back(std::move(c));
  }
}

BulletWorld::~BulletWorld() = default;

void BulletWorld::step() {
  Impl& m = *impl_;
  // A kinematic body in Bullet follows its motion state: it is given its pose at the end of the
  // step and Bullet derives the velocity from the change (btRigidBody::saveKinematicState).
  for (const auto& k : m.kinematic) {
    btTransform next;
    btTransformUtil::integrateTransform(k.body->getWorldTransform(), k.v, k.w, m.dt, next);
    k.body->getMotionState()->setWorldTransform(next);
  }
  for (const DistanceSpring& sp : m.springs) {
    if (!sp.joint->isEnabled()) continue;
    btRigidBody &a = sp.joint->getRigidBodyA(), &b = sp.joint->getRigidBodyB();
    const btVector3 pa = sp.joint->world_a(), pb = sp.joint->world_b();
    const btVector3 d = pb - pa;
    const btScalar len = d.length();
    if (len < btScalar(1e-6)) continue;
    const btVector3 n = d / len;
    const btVector3 ra = pa - a.getCenterOfMassPosition(), rb = pb - b.getCenterOfMassPosition();
    const btScalar rate = n.dot(b.getVelocityInLocalPoint(rb) - a.getVelocityInLocalPoint(ra));
    const btVector3 f = n * (sp.stiffness * (len - sp.rest) + sp.damping * rate);
    a.applyForce(f, ra);  // pulls A toward B when stretched
    b.applyForce(-f, rb);
    a.activate();
    b.activate();
  }
  m.world.stepSimulation(m.dt, 0);  // maxSubSteps = 0: exactly one step of dt
}

std::size_t BulletWorld::body_count() const {
  return impl_->bodies.size();
}

Vec3 BulletWorld::position(std::size_t i) const {
  const btTransform t = impl_->bodies[i]->getWorldTransform() * impl_->frames[i].inverse();
  const btVector3& p = t.getOrigin();
  return Vec3(Real(p.x()), Real(p.y()), Real(p.z()));
}

std::size_t BulletWorld::joint_count() const {
  std::size_t n = 0;
  for (const auto& j : impl_->joints) n += j->isEnabled();
  return n;
}

BulletCounts BulletWorld::counts() const {
  BulletCounts c;
  btCollisionDispatcher& disp = impl_->dispatcher;
  for (int i = 0; i < disp.getNumManifolds(); ++i) {
    const int n = disp.getManifoldByIndexInternal(i)->getNumContacts();
    c.manifolds += n > 0;
    c.contacts += std::size_t(n);
  }
  for (const auto& b : impl_->bodies) c.awake += !b->isStaticOrKinematicObject() && b->isActive();
  return c;
}

}  // namespace elan::peer
