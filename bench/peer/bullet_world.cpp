// SPDX-License-Identifier: MIT
// Builds a Bullet 3 world from an elan::Scene: Bullet's own shapes, mass from density x volume as
// elan computes it, elan's material mixing and damping law, sleeping as the scene asks.
#include "bench/peer/bullet_world.hpp"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <LinearMath/btConvexHullComputer.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
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

}  // namespace

struct BulletWorld::Impl {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<btVector3> com_ls;  // m, shape frame origin to centre of mass, shape frame
  struct Kinematic {
    btRigidBody* body;
    btVector3 v, w;
  };
  std::vector<Kinematic> kinematic;
  btScalar dt = 0;

  ~Impl() {
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
    btCollisionShape* shape = nullptr;
    double volume = 0;
    btVector3 com(0, 0, 0);
    if (s.type == ShapeType::ConvexHull) {
      Hull h = make_hull(s.points);
      auto* hull = new btConvexHullShape(&h.points[0].x(), int(h.points.size()), sizeof(btVector3));
      hull->setMargin(h.margin);
      m.shapes.emplace_back(hull);
      shape = hull;
      volume = h.volume;
      com = h.com;
    } else {
      const auto key = std::make_tuple(int(s.type), double(s.radius), double(s.half_height),
                                       double(s.half_extents.x()), double(s.half_extents.y()),
                                       double(s.half_extents.z()));
      auto it = shared.find(key);
      if (it != shared.end() && s.type != ShapeType::Plane) {
        shape = it->second;
      } else {
        switch (s.type) {
          case ShapeType::Sphere:
            shape = new btSphereShape(btScalar(s.radius));
            break;
          case ShapeType::Box:
            shape = new btBoxShape(to_bt(s.half_extents));
            break;
          // Bullet's capsule height is the segment length, 2 * half_height; axis Y as elan's.
          case ShapeType::Capsule:
            shape = new btCapsuleShape(btScalar(s.radius), btScalar(2 * s.half_height));
            break;
          case ShapeType::Cylinder:
            shape = new btCylinderShape(
                btVector3(btScalar(s.radius), btScalar(s.half_height), btScalar(s.radius)));
            break;
          default:
            shape = new btStaticPlaneShape(to_bt(s.normal).normalized(), btScalar(s.offset));
            break;
        }
        m.shapes.emplace_back(shape);
        shared[key] = shape;
      }
      volume = volume_of(s);
    }
    const bool dynamic = d.motion == MotionType::Dynamic;
    const btScalar mass = dynamic ? btScalar(d.mass ? double(*d.mass) : d.density * volume) : 0;
    btVector3 inertia(0, 0, 0);
    if (dynamic) shape->calculateLocalInertia(mass, inertia);
    const Quat& q = d.orientation;
    btQuaternion rotation(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w()));
    btTransform pose(rotation.normalize(), to_bt(d.position));
    pose.setOrigin(pose(com));
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
    m.com_ls.push_back(com);
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
  m.world.stepSimulation(m.dt, 0);  // maxSubSteps = 0: exactly one step of dt
}

std::size_t BulletWorld::body_count() const {
  return impl_->bodies.size();
}

Vec3 BulletWorld::position(std::size_t i) const {
  const btTransform& t = impl_->bodies[i]->getWorldTransform();
  const btVector3 p = t.getOrigin() - t.getBasis() * impl_->com_ls[i];
  return Vec3(Real(p.x()), Real(p.y()), Real(p.z()));
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
