// SPDX-License-Identifier: MIT
// deep_contact(): a bounded separating-axis test on fixed candidate axes for a deep pair (see
// deep_contact.hpp).
#include "narrowphase/deep_contact.hpp"

#include <cmath>

namespace elan::detail {

namespace {

// Roberts' R3 sequence ("The unreasonable effectiveness of quasirandom sequences", 2018): the
// k-th point is frac(k alpha_i) per coordinate, alpha_i = 1 / g^i with g the plastic-like root
// of x^4 = x + 1, g = 1.2207440846. In 32-bit fixed point, k alpha_i is k C_i modulo 2^32 with
// C_i = round(alpha_i 2^32) made odd: an odd C_i is invertible modulo 2^32, so two distinct
// indices never share a coordinate, and the product is exact integer arithmetic.
constexpr uint32_t kR3[3] = {0xD1B54A33u, 0xABC98389u, 0x8CB92BA7u};

// Coordinate i of body k's virtual offset, centred on zero (a signed 32-bit fixed-point value).
int64_t offset_coordinate(uint32_t k, int i) {
  return int64_t(int32_t(k * kR3[i]));
}

// h(n) = max over the shape of n.x, about its centre of mass, for a world direction n.
Real support_height(const Shape& s, const Quat& rotation, const Vec3& n) {
  const Vec3 local = rotation.conjugate() * n;
  return local.dot(support(s, local));
}

}  // namespace

Vec3 spawn_direction(uint32_t index_a, uint32_t index_b) {
  // Exact integer differences (below 2^32 in size), each non-zero for distinct indices.
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    v[i] = Real(offset_coordinate(index_b, i) - offset_coordinate(index_a, i));
  }
  const Real norm = v.norm();
  return norm > 0 ? Vec3(v / norm) : Vec3::UnitY();
}

bool deep_contact(const Shape& a, const Transform& xa, uint32_t index_a, const Shape& b,
                  const Transform& xb, uint32_t index_b, Manifold& out) {
  const Vec3 d = xb.position - xa.position;
  const Real size = a.bounding_radius + b.bounding_radius;
  // Centres closer than this coincide: their line is lost in the rounding of the positions.
  const Real coincident = Real(1e-6) * size;
  const Real dd = d.squaredNorm();
  const Vec3 u =
      dd > coincident * coincident ? Vec3(d / std::sqrt(dd)) : spawn_direction(index_a, index_b);
  // Candidates: the line of centres, then A's and B's principal axes, each pointing along u.
  const Mat3 ra = xa.rotation.toRotationMatrix();
  const Mat3 rb = xb.rotation.toRotationMatrix();
  Vec3 axes[7];
  axes[0] = u;
  for (int i = 0; i < 3; ++i) {
    axes[1 + i] = ra.col(i);
    axes[4 + i] = rb.col(i);
  }
  // Overlaps within this of each other tie (a box's three faces for two coincident equal
  // boxes), and a tie goes to the earlier candidate: the line of centres, then A's axes in
  // order, so coincident equal boxes part along A's x axis, each pair's way by its virtual
  // direction. (Ties sent to the axis nearest that direction spread such a cloud over all three
  // axes, which on a floor stacks it into a tower of overlapping bodies that falls apart fast
  // once the budget lets go.)
  const Real tie = Real(1e-5) * size;
  Vec3 best_n = u;
  Real best_overlap = 0, best_a = 0, best_b = 0;
  for (int k = 0; k < 7; ++k) {
    const Vec3 n = axes[k].dot(u) < 0 ? Vec3(-axes[k]) : axes[k];
    const Real ha = support_height(a, xa.rotation, n);
    const Real hb = support_height(b, xb.rotation, -n);
    const Real overlap = ha + hb - n.dot(d);
    if (k == 0 || overlap < best_overlap - tie) {
      best_n = n;
      best_overlap = overlap;
      best_a = ha;
      best_b = hb;
    }
  }
  out.normal = best_n;
  out.point_count = 1;
  ContactPoint& p = out.points[0];
  // Across n: midway between the centres. Along n: the middle of the slab where A's extent
  // [-h_A, h_A] overlaps B's [n.d - h_B, n.d + h_B] (its lower end n.d - h_B, its upper h_A).
  const Real along = best_n.dot(d);
  p.anchor_a = Real(0.5) * (d - along * best_n) + Real(0.5) * (along - best_b + best_a) * best_n;
  p.separation = -best_overlap;
  p.feature_id = kDeepFeatureId;
  p.normal_impulse = 0;
  return true;
}

}  // namespace elan::detail
