// SPDX-License-Identifier: MIT
// The substep integrator: the exponential map's polynomial against the closed form, and the
// lane-parallel position update against a double-precision evaluation of the same midpoint rule,
// lane by lane, whatever lane or block a body falls in.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "solver/integrate.hpp"

namespace elan::detail {
namespace solver_integrate_test {

constexpr Real kEps = std::numeric_limits<Real>::epsilon();

using Quatd = Eigen::Quaterniond;
using Vec3d = Eigen::Vector3d;

Quatd exact_exp(const Vec3d& w, double h) {
  const double angle = w.norm() * h;
  if (angle == 0) return Quatd::Identity();
  const Vec3d axis = w / w.norm();
  return Quatd(std::cos(angle / 2), std::sin(angle / 2) * axis.x(), std::sin(angle / 2) * axis.y(),
               std::sin(angle / 2) * axis.z());
}

double max_difference(const Quat& q, const Quatd& r) {
  return (q.coeffs().cast<double>() - r.coeffs()).cwiseAbs().maxCoeff();
}

TEST(ExponentialMap, MatchesTheClosedFormOnBothSidesOfThePolynomialsRange) {
  // The polynomial holds up to a turn of 1 rad in the substep; beyond, libm. Either way each
  // component is within a few roundings of the closed form: w h and |w|^2 round once each, the
  // series of degree 4 in y rounds at each of its four steps, the product by w once more.
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0, 1);
  const Real h = Real(1.0 / 240);
  for (double angle : {0.0, 1e-9, 1e-6, 1e-3, 0.05, 0.3, 0.7, 0.999, 1.0, 1.001, 1.5, 2.5, 3.1}) {
    for (int trial = 0; trial < 200; ++trial) {
      const Vec3d axis = Vec3d{n(rng), n(rng), n(rng)}.normalized();
      const Vec3 w = (axis * (angle / h)).cast<Real>();
      const Quat q = rotation_from_angular_velocity(w, h);
      const Quatd exact = exact_exp(w.cast<double>(), double(h));
      EXPECT_LE(max_difference(q, exact), 8 * kEps) << "angle " << angle;
      EXPECT_NEAR(q.norm(), 1.0, 8 * kEps) << "angle " << angle;
    }
  }
}

// The midpoint rule of integrate_positions, in double: the reference the float lanes follow.
struct Reference {
  Quatd dq;
  Vec3d w;
  Eigen::Matrix3d inv_inertia;
};

Reference reference_step(const SolverBody& b, const SolverBodyMass& p, const BodyStore& store,
                         double h) {
  const Quat& q0f = store.orientation(p.body);
  const Quatd q0 = q0f.cast<double>();
  const Vec3d w = b.w.cast<double>();
  const Quatd dq = b.dq.cast<double>();
  if (!p.gyroscopic) return {(exact_exp(w, h) * dq).normalized(), w, Eigen::Matrix3d::Zero()};
  const Vec3d d = principal_moments(store, p.body).cast<double>();
  const Quatd before = dq * q0;
  const Vec3d l_world = before * d.cwiseProduct(before.conjugate() * w);
  // A body turning more than 0.25 rad in the substep takes the rule in pieces of at most that
  // angle (integrate.cpp), and never ends with more energy w . L / 2 than it started with.
  const int pieces = std::max(1, int(std::ceil(w.norm() * h / 0.25)));
  const double hp = h / pieces;
  Quatd turned = dq, after = before;
  Vec3d wc = w;
  for (int k = 0; k < pieces; ++k) {
    const Quatd mid = (exact_exp(wc, hp / 2) * after).normalized();
    const Vec3d w_mid = mid * (mid.conjugate() * l_world).cwiseQuotient(d);
    turned = (exact_exp(w_mid, hp) * turned).normalized();
    after = turned * q0;
    wc = after * (after.conjugate() * l_world).cwiseQuotient(d);
  }
  if (pieces > 1 && wc.dot(l_world) > w.dot(l_world)) {
    wc *= std::sqrt(w.dot(l_world) / wc.dot(l_world));
  }
  const Eigen::Matrix3d r = after.toRotationMatrix();
  return {turned, wc, r * d.cwiseInverse().asDiagonal() * r.transpose()};
}

struct Bodies {
  BodyStore store;
  std::vector<SolverBody> packets;
  std::vector<SolverBodyMass> masses;
};

// Packet 0 is the static dummy, as in the solver; packets 1..n are a mix of spheres (isotropic),
// kinematic bodies and gyroscopic boxes, some spinning faster than the polynomial's range.
Bodies make_bodies(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1, 1);
  Bodies s;
  s.packets.resize(n + 1);
  s.masses.resize(n + 1);
  for (std::size_t k = 1; k <= n; ++k) {
    const std::size_t i = s.store.push_back();
    s.store.set_orientation(i, Quat{u(rng), u(rng), u(rng), u(rng)}.normalized());
    SolverBody& b = s.packets[k];
    SolverBodyMass& p = s.masses[k];
    const Real spin = k % 7 == 0 ? Real(300) : Real(20);  // 300 rad/s: the libm route at 1/240 s
    b.v = Vec3{u(rng), u(rng), u(rng)};
    b.w = spin * Vec3{u(rng), u(rng), u(rng)};
    if (k % 14 == 0) b.w = Vec3(0, spin, 0);  // about one axis: w.x and w.z are zero
    b.dp = Vec3{u(rng), u(rng), u(rng)};
    b.dtheta = Vec3{u(rng), u(rng), u(rng)};
    b.dq = Quat{1, Real(0.1) * u(rng), Real(0.1) * u(rng), Real(0.1) * u(rng)}.normalized();
    p.body = uint32_t(i);
    p.inv_mass = k % 5 == 0 ? 0 : 1;
    p.gyroscopic = k % 3 != 0 && p.inv_mass != 0;
    const Vec3 moments = p.gyroscopic ? Vec3{1 + u(rng) * Real(0.5), 2, 3 + u(rng)} : Vec3::Ones();
    s.store.inv_ix[i] = 1 / moments.x();
    s.store.inv_iy[i] = 1 / moments.y();
    s.store.inv_iz[i] = 1 / moments.z();
  }
  return s;
}

TEST(IntegratePositions, LanesFollowTheMidpointRuleInDouble) {
  std::mt19937 rng(3);
  Bodies s = make_bodies(101, rng);
  const std::vector<SolverBody> start = s.packets;
  const Real h = Real(1.0 / 240);
  integrate_positions(s.packets, s.masses, s.store, h, 1, uint32_t(s.packets.size()));
  for (std::size_t k = 1; k < s.packets.size(); ++k) {
    const SolverBody& b0 = start[k];
    const SolverBody& b = s.packets[k];
    const SolverBodyMass& p = s.masses[k];
    const Reference r = reference_step(b0, p, s.store, h);
    EXPECT_LE((b.dp - (b0.dp + h * b0.v)).cwiseAbs().maxCoeff(), 4 * kEps) << k;
    EXPECT_LE((b.dtheta - (b0.dtheta + h * b0.w)).cwiseAbs().maxCoeff(), 4 * kEps) << k;
    // Two rotations, a normalisation and their product: a few tens of roundings at most.
    EXPECT_LE(max_difference(b.dq, r.dq), 32 * kEps) << k;
    // w' = I(q')^-1 L runs through three products and a quotient by moments of size 1..4.
    EXPECT_LE((b.w.cast<double>() - r.w).norm(), 64 * kEps * r.w.norm()) << k;
    if (!p.gyroscopic) {
      EXPECT_EQ(b.w, b0.w) << k;
      continue;
    }
    const SymMat3& m = s.masses[k].inv_inertia;
    Eigen::Matrix3d got;
    got << m.xx, m.xy, m.xz, m.xy, m.yy, m.yz, m.xz, m.yz, m.zz;
    EXPECT_LE((got - r.inv_inertia).cwiseAbs().maxCoeff(), 32 * kEps) << k;
  }
}

TEST(IntegratePositions, ABodyGetsTheSameBitsInAnyLaneAndBlock) {
  // The solver's body blocks are fixed, but which lane a packet takes depends on where its block
  // starts: the result may not.
  std::mt19937 rng(8);
  const Bodies s = make_bodies(77, rng);
  const Real h = Real(1.0 / 240);
  Bodies whole = s;
  integrate_positions(whole.packets, whole.masses, whole.store, h, 1, 78);
  for (uint32_t chunk : {1u, 3u, 5u, 17u, 40u}) {
    Bodies parts = s;
    for (uint32_t begin = 1; begin < 78; begin += chunk) {
      integrate_positions(parts.packets, parts.masses, parts.store, h, begin,
                          std::min<uint32_t>(78, begin + chunk));
    }
    EXPECT_EQ(std::memcmp(parts.packets.data(), whole.packets.data(),
                          sizeof(SolverBody) * whole.packets.size()),
              0)
        << "chunk " << chunk;
    for (std::size_t k = 1; k < 78; ++k) {
      const SymMat3& a = parts.masses[k].inv_inertia;
      const SymMat3& b = whole.masses[k].inv_inertia;
      EXPECT_EQ(std::memcmp(&a, &b, sizeof(SymMat3)), 0) << "chunk " << chunk << " packet " << k;
    }
  }
}

}  // namespace solver_integrate_test
}  // namespace elan::detail
