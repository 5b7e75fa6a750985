// SPDX-License-Identifier: MIT
// Solver data: the compact per-body packet the substeps work on, per-body constants, and
// contact constraints in solver form, bundled across SIMD lanes.
#pragma once

#include <cstdint>

#include "core/base/contact.hpp"
#include "elan/math.hpp"
#include "solver/wide.hpp"

namespace elan::detail {

// Symmetric 3x3 matrix (world inverse inertia), 6 scalars.
struct SymMat3 {
  Real xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;
  Vec3 operator*(const Vec3& v) const {
    return {xx * v.x() + xy * v.y() + xz * v.z(), xy * v.x() + yy * v.y() + yz * v.z(),
            xz * v.x() + yz * v.y() + zz * v.z()};
  }
};

// R diag(d) R^T for a unit quaternion q.
SymMat3 rotate_diagonal(const Quat& q, const Vec3& d);

// The hot per-body record (Box2D v3's body state): velocities and the pose change since the
// start of the step. Packet 0 is a static dummy with zero velocity that is never written.
struct alignas(16) SolverBody {
  Vec3 v = Vec3::Zero();       // m/s, world
  Vec3 w = Vec3::Zero();       // rad/s, world
  Vec3 dp = Vec3::Zero();      // m: position change since the step began
  Vec3 dtheta = Vec3::Zero();  // rad: sum of h w over the substeps, the linearised rotation
  Quat dq = Quat::Identity();  // rotation since the step began (world: q = dq * q0)
};

// Whether the solver writes packet `packet` back: the awake dynamic bodies' packets, 1 up to
// `written_end` (SolverState::half_start[kHalves]); the static dummy (0) and the kinematic
// bodies' packets, which follow, are only read. One unsigned compare: packet 0 wraps around.
inline bool written_packet(uint32_t packet, uint32_t written_end) {
  return packet - 1u < written_end - 1u;
}

// What every constraint pass reads of a body besides its velocity: its inverse mass and world
// inverse inertia, 32 bytes a packet (zero for kinematic bodies and the static dummy, so a side
// that is not written gets none). perf: kept per packet and gathered by each pass, not copied
// into every constraint bundle, where they would take 14 values a lane: the passes stream the
// bundles from beyond L2, while the packets' masses, a body's once, stay in it.
//
// The row's eighth word, which the passes' 8-float gathers load and ignore, tells the substep
// integration which body the packet is and whether it turns gyroscopically. Gravity, forces and
// damping are read from the body store there (memory: not copied into a record per packet).
struct alignas(8 * sizeof(Real)) SolverBodyMass {
  Real inv_mass = 0;    // 1/kg
  SymMat3 inv_inertia;  // 1/(kg m^2), world; integrate_positions turns it for gyroscopic bodies
  uint32_t body : kManifoldBodyBits = 0;  // dense body index
  // Anisotropic inertia: keep L = I w through rotation (integrate_positions reads the principal
  // moments from the body store then, for these bodies only). Bodies with equal principal
  // moments (spheres, cubes) have no gyroscopic term.
  uint32_t gyroscopic : 1 = 0;
};
static_assert(sizeof(Real) != 4 || sizeof(SolverBodyMass) == 32, "SolverBodyMass: one 8-float row");

// Soft constraint coefficients (Box2D v3 "soft step", b2MakeSoft): a spring-damper of the
// given stiffness (Hz) and damping ratio expressed as a bias rate and two impulse scales.
struct Softness {
  Real bias_rate = 0;  // 1/s
  Real mass_scale = 1;
  Real impulse_scale = 0;
};
Softness make_softness(Real hertz, Real damping_ratio, Real h);

// Symmetric 3x3 matrices across the lanes (world inverse inertia).
struct WideSym3 {
  Wide xx{}, yy{}, zz{}, xy{}, xz{}, yz{};
};

inline WideVec3 operator*(const WideSym3& m, const WideVec3& v) {
  return {m.xx * v.x + m.xy * v.y + m.xz * v.z, m.xy * v.x + m.yy * v.y + m.yz * v.z,
          m.xz * v.x + m.yz * v.y + m.zz * v.z};
}

inline void set_lane(WideSym3& w, int l, const SymMat3& m) {
  w.xx[l] = m.xx;
  w.yy[l] = m.yy;
  w.zz[l] = m.zz;
  w.xy[l] = m.xy;
  w.xz[l] = m.xz;
  w.yz[l] = m.yz;
}

// One non-penetration row per lane in Jacobian form, J = [-n, -(ra x n), n, (rb x n)], but for
// its arms, which the passes derive (BundleArms in contact_solver.cpp). Points past a lane's
// count are zero, so they apply no impulse.
// perf: the angular responses I^-1 (r x n) are not stored but recomputed from the bundle's
// inverse inertias in every pass (15 operations a side, off the chain of dependent updates):
// stored, they would be 6 values a row, and the passes are bound by memory traffic.
struct WideNormalRow {
  Wide separation{};  // m at the step's start; s = this + J . (dp, dtheta)
  // m: s at the current pose. Positions change once per substep, so refresh_contacts computes
  // it then for every pass until the next (not 12 body values gathered per lane per pass).
  Wide current_separation{};
  Wide normal_mass{};     // kg: 1 / (J M^-1 J^T)
  Wide normal_impulse{};  // N s, accumulated over the substep (warm started)
};

// A point past the first of its lane. Its row's arms come from the manifold centre c
// (ContactBundle::center_ra, center_rb) and this offset: ra x n = c_a x n + offset_n, and
// rb x n = ra x n - (c_a - c_b) x n, since a point's two arms differ by the two centres' offset.
// The first point's offset is minus the others' sum (c is the points' mean), so it is not stored
// at all, and its row lives in the bundle: a bundle of one-point manifolds (most of a pile's) has
// no rows of its own. The offset's length is the point's lever about c (twist friction).
struct WideContactPoint {
  WideVec3 offset_n;  // m: (r - c) x n, r the point's arm from A's centre of mass
  WideNormalRow row;
};

// kLanes contact constraints of one colour (no two share a dynamic body), structure of arrays
// over the lanes, solved together (Box2D v3's b2ContactConstraintSIMD). Unused lanes have
// packet 0 (the static dummy), zero coefficients and are never written back.
//
// perf: every solver pass streams all bundles through the cache (megabytes a pass on a large
// scene), so a bundle keeps only what a pass cannot derive cheaply in registers, as bepuphysics2
// does: the friction Jacobians come from the manifold centre and the normal, the
// angular responses from the inverse inertias, the softness from whether B is written, the
// masses from the packets (SolverBodyMass), and the restitution inputs, read once per step, live
// apart (ContactSolverContext::restitution). Nor does it keep what its packets or the layout
// tell: which sides are written (written_packet), where its other point rows are
// (SolverState::row_start), which manifolds its lanes are and how many (SolverState::order and
// lane_start, read by the refresh and the impulses' storage only). So its header is its two packet
// arrays, 128 bytes, and the wide values start on the next cache line.
struct ContactBundle {
  uint32_t packet_a[kLanes] = {}, packet_b[kLanes] = {};  // 0 = static dummy, and unused lanes
  WideVec3 normal;  // the friction rows' axes are tangent_basis(normal)
  Wide friction{};
  // Central friction (Gregorius, GDC 2015): a coupled 2x2 tangent block at the mean of the
  // points and a twist row about the normal.
  WideVec3 center_ra, center_rb;         // m: the mean point minus each centre of mass
  Wide inv_k00{}, inv_k01{}, inv_k11{};  // inverse of the 2x2 tangent mass matrix
  Wide twist_mass{};                     // kg m^2
  Wide tangent_impulse[2] = {};          // N s
  Wide twist_impulse{};                  // N m s
  WideNormalRow first;                   // the lanes' first points (WideContactPoint)
};

static_assert(sizeof(Real) != 4 || kLanes != 16 || sizeof(ContactBundle) == 1472,
              "ContactBundle: the packet arrays, then 21 wide values");

// Read by the restitution pass only: the lane's restitution, and per row the approach speed and
// the largest impulse any pass applied (Box2D v3: only points that pushed bounce). Kept only
// when some body bounces, so the passes of an inelastic scene neither store nor stream it.
struct BundleRestitution {
  Wide restitution{};
  Wide relative_velocity[kMaxManifoldPoints] = {};   // m/s along n before the solve
  Wide max_normal_impulse[kMaxManifoldPoints] = {};  // N s
};

}  // namespace elan::detail
