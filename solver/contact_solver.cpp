// SPDX-License-Identifier: MIT
// Soft-step contact solver: non-penetration with soft position correction, Coulomb friction with
// a circular cone, restitution from the pre-solve approach speed.
#include "solver/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "solver/body_lanes.hpp"
#include "solver/direct_solve.hpp"

namespace elan::detail {
ELAN_ISA_BEGIN

namespace {

// Below these relative motions since the step's start refresh_contacts keeps a constraint's
// arms (m, rad): the angular momentum error left is at most this distance times the impulse.
constexpr Real kRefreshDistance = Real(1e-4);
constexpr Real kRefreshAngle = Real(1e-4);

// Relative velocity of B against A along a row with Jacobian [-d, -ra_d, d, rb_d].
inline Wide row_velocity(const WideBody& a, const WideBody& b, const WideVec3& d,
                         const WideVec3& ra_d, const WideVec3& rb_d) {
  return dot(d, b.v - a.v) + dot(rb_d, b.w) - dot(ra_d, a.w);
}

// The Jacobian arms of a bundle's points as its passes derive them (WideContactPoint): the
// centre's, once a bundle, then each point's from its offset. perf: bundle_arms is inlined into
// every pass; called, GCC returns its nine vectors through memory.
struct BundleArms {
  WideVec3 center_n;        // c_a x n
  WideVec3 b_offset_n;      // (c_a - c_b) x n: a point's rb x n is its ra x n minus this
  WideVec3 first_offset_n;  // the first point's offset: minus the sum of the others'
};

[[gnu::always_inline]] inline BundleArms bundle_arms(const ContactBundle& c,
                                                     const WideContactPoint* rows,
                                                     int point_count) {
  BundleArms arms;
  arms.center_n = cross(c.center_ra, c.normal);
  arms.b_offset_n = cross(c.center_ra - c.center_rb, c.normal);
  for (int k = 1; k < point_count; ++k) {
    arms.first_offset_n = arms.first_offset_n - rows[k - 1].offset_n;
  }
  return arms;
}

// Point k's row (the first is the bundle's own) and offset.
template <class Bundle, class Point>
auto& row_of(Bundle& c, Point* rows, int k) {
  return k == 0 ? c.first : rows[k - 1].row;
}
inline const WideVec3& offset_of(const BundleArms& arms, const WideContactPoint* rows, int k) {
  return k == 0 ? arms.first_offset_n : rows[k - 1].offset_n;
}

struct PointArms {
  WideVec3 ra_n, rb_n;  // ra x n, rb x n
};

// 1 / x where x > 0, else 0 (a constraint with no mass, or an unused lane): no lane divides by
// zero, so none raises a floating-point exception or makes a NaN.
inline Wide inverse_or_zero(Wide x) {
  const Wide zero{};
  const Wide one = splat(1);
  return x > zero ? one / (x > zero ? x : one) : zero;
}

// The mass of a non-penetration row, 1 / (J M^-1 J^T), or 0 where it has none; m_sum is the two
// sides' inverse masses.
inline Wide normal_mass_of(const PointArms& r, const WideMass& ma, const WideMass& mb, Wide m_sum) {
  return inverse_or_zero(m_sum + dot(r.ra_n, ma.inv_inertia * r.ra_n) +
                         dot(r.rb_n, mb.inv_inertia * r.rb_n));
}
inline PointArms arms_of(const BundleArms& arms, const WideContactPoint* rows, int k) {
  const WideVec3 ra_n = arms.center_n + offset_of(arms, rows, k);
  return {ra_n, ra_n - arms.b_offset_n};
}

// Applies impulse `lambda` along a non-penetration row: linear part along n, angular parts
// I^-1 (r x n). A side that is not written has zero inverse mass and inertia.
inline void apply_row(const ContactBundle& c, const WideMass& ma, const WideMass& mb, WideBody& a,
                      WideBody& b, const PointArms& r, Wide lambda) {
  const WideVec3 ia_ra_n = ma.inv_inertia * r.ra_n;
  const WideVec3 ib_rb_n = mb.inv_inertia * r.rb_n;
  a.v = a.v - (ma.inv_mass * lambda) * c.normal;
  a.w = a.w - lambda * ia_ra_n;
  b.v = b.v + (mb.inv_mass * lambda) * c.normal;
  b.w = b.w + lambda * ib_rb_n;
}

// The tangent impulse (t0, t1) at the centre, applied as one impulse p there: the angular
// parts are I^-1 (r x p), one product per side instead of one per tangent.
inline void apply_friction(const ContactBundle& c, const WideTangents& t, const WideMass& ma,
                           const WideMass& mb, WideBody& a, WideBody& b, Wide lambda0,
                           Wide lambda1) {
  const WideVec3 p = lambda0 * t.t0 + lambda1 * t.t1;
  a.v = a.v - ma.inv_mass * p;
  a.w = a.w - ma.inv_inertia * cross(c.center_ra, p);
  b.v = b.v + mb.inv_mass * p;
  b.w = b.w + mb.inv_inertia * cross(c.center_rb, p);
}

inline void apply_twist(const ContactBundle& c, const WideMass& ma, const WideMass& mb, WideBody& a,
                        WideBody& b, Wide twist) {
  const WideVec3 l = twist * c.normal;
  a.w = a.w - ma.inv_inertia * l;
  b.w = b.w + mb.inv_inertia * l;
}

// The inverse of the 2x2 mass matrix K = J M^-1 J^T of the friction rows at the manifold
// centre, in closed form, from the bundle's centre arms and the two sides' masses.
void set_friction_mass(ContactBundle& c, const WideMass& ma, const WideMass& mb) {
  const WideTangents t = tangents_of(c.normal);
  const WideVec3 tangent[2] = {t.t0, t.t1};
  WideVec3 ra_t[2], rb_t[2], ia_ra_t[2], ib_rb_t[2];
  for (int t = 0; t < 2; ++t) {
    ra_t[t] = cross(c.center_ra, tangent[t]);
    rb_t[t] = cross(c.center_rb, tangent[t]);
    ia_ra_t[t] = ma.inv_inertia * ra_t[t];
    ib_rb_t[t] = mb.inv_inertia * rb_t[t];
  }
  const Wide m_sum = ma.inv_mass + mb.inv_mass;
  const Wide k00 = m_sum + dot(ra_t[0], ia_ra_t[0]) + dot(rb_t[0], ib_rb_t[0]);
  const Wide k01 = dot(ra_t[0], ia_ra_t[1]) + dot(rb_t[0], ib_rb_t[1]);
  const Wide k11 = m_sum + dot(ra_t[1], ia_ra_t[1]) + dot(rb_t[1], ib_rb_t[1]);
  const Wide det = k00 * k11 - k01 * k01;
  const Wide inv_det = inverse_or_zero(det);
  c.inv_k00 = k11 * inv_det;
  c.inv_k01 = -k01 * inv_det;
  c.inv_k11 = k00 * inv_det;
}

}  // namespace

void prepare_bundle(const ContactSolverContext& ctx, const BodyStore& bodies,
                    std::span<const ManifoldHead> manifolds, std::span<const ManifoldTail> tails,
                    std::span<const uint32_t> packet_of, uint32_t bundle) {
  ContactBundle& c = ctx.bundles[bundle];
  const std::span<const uint32_t> lanes = ctx.manifolds_of(bundle);
  WideContactPoint* rows = ctx.rows_of(bundle);
  const int points = ctx.point_count(bundle);
  BundleRestitution unused;
  BundleRestitution& bounce = ctx.restitution.empty() ? unused : ctx.restitution[bundle];
  const int lane_count = int(lanes.size());
  // The heads, one sixteen-float row a lane, transposed (gather_rows): the normal, the carried
  // friction impulses and the first point in lanes at once. Unused lanes read a zero head.
  static_assert(sizeof(ManifoldHead) == 16 * sizeof(Real) &&
                offsetof(ManifoldHead, normal) % sizeof(Real) == 0 &&
                offsetof(ManifoldHead, first) % sizeof(Real) == 0 &&
                offsetof(ContactPoint, separation) % sizeof(Real) == 0 &&
                offsetof(ContactPoint, normal_impulse) % sizeof(Real) == 0);
  alignas(64) static constexpr Real kNoHead[sizeof(ManifoldHead) / sizeof(Real)] = {};
  const Real* head_row[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    head_row[l] = l < lane_count ? reinterpret_cast<const Real*>(&manifolds[lanes[l]]) : kNoHead;
  }
  Wide head[16];
  gather_rows(head_row, head);
  auto column = [&](std::size_t offset) -> const Wide& { return head[offset / sizeof(Real)]; };
  c.normal = {column(offsetof(ManifoldHead, normal)),
              column(offsetof(ManifoldHead, normal) + sizeof(Real)),
              column(offsetof(ManifoldHead, normal) + 2 * sizeof(Real))};
  c.tangent_impulse[0] = column(offsetof(ManifoldHead, tangent_impulse));
  c.tangent_impulse[1] = column(offsetof(ManifoldHead, tangent_impulse) + sizeof(Real));
  c.twist_impulse = column(offsetof(ManifoldHead, twist_impulse));
  // The rest lane by lane: what lies in the bodies and their traits. Unused lanes stay zero
  // (packet 0, no mass), so every product below is zero there.
  c.friction = bounce.restitution = Wide{};
  Wide point_count{};
  // B's centre from A's: the bodies are where the collide stage left them, so B's arm to a
  // point is A's arm minus this.
  WideVec3 b_from_a;
  uint32_t shared_lanes = 0;  // lanes whose cap is shared: a spawn's overlap, never a load
  for (int l = 0; ctx.bodies_separating && l < lane_count; ++l) {
    // Or a lane of a body still being pushed out of one (separating_mark.hpp): the chains of
    // overlapping bodies a spawn leaves are pressed in past kDirectDepth without a load, and
    // made direct systems of hundreds of rows.
    const ManifoldHead& m = manifolds[lanes[l]];
    if ((bodies.flags[m.body_a] | bodies.flags[m.body_b]) & kSeparating) shared_lanes |= 1u << l;
  }
  if (!ctx.push_cap.empty()) {
    // The push-out share (color_contacts.hpp): the cap over the larger deep count of the two.
    Wide& cap = ctx.push_cap[bundle].v;
    cap = splat(ctx.max_push_velocity);
    for (int l = 0; l < lane_count; ++l) {
      const ManifoldHead& m = manifolds[lanes[l]];
      const uint32_t n =
          std::max(ctx.deep_count[packet_of[m.body_a]], ctx.deep_count[packet_of[m.body_b]]);
      if (n > kPushShare) {
        cap[l] = ctx.max_push_velocity * (Real(kPushShare) / Real(n));
        shared_lanes |= 1u << l;
      }
    }
  }
  for (int l = 0; l < kLanes; ++l) {
    if (l >= lane_count) {
      c.packet_a[l] = c.packet_b[l] = 0;
      continue;
    }
    const ManifoldHead& m = manifolds[lanes[l]];
    const uint32_t a = m.body_a, b = m.body_b;
    const uint32_t packet_a = packet_of[a], packet_b = packet_of[b];
    c.packet_a[l] = packet_a;
    c.packet_b[l] = packet_b;
    const BodyTraits &traits_a = bodies.traits_of(a), &traits_b = bodies.traits_of(b);
    c.friction[l] = std::sqrt(traits_a.friction * traits_b.friction);
    bounce.restitution[l] = std::max(traits_a.restitution, traits_b.restitution);
    point_count[l] = Real(m.point_count);
    set_lane(b_from_a, l, bodies.position(b) - bodies.position(a));
  }
  // The packets' velocities and masses as the passes gather them (unused lanes read the static
  // dummy, packet 0: zero). perf: as whole rows where body_lanes.hpp can, not 26 lane inserts.
  WideBody va, vb;
  WideMass ma, mb;
  gather_velocity(ctx.bodies.data(), c.packet_a, va);
  gather_velocity(ctx.bodies.data(), c.packet_b, vb);
  gather_mass(ctx.masses.data(), c.packet_a, ma);
  gather_mass(ctx.masses.data(), c.packet_b, mb);
  const Wide zero{};
  const WideVec3& n = c.normal;
  const Wide m_sum = ma.inv_mass + mb.inv_mass;
  // The points' arms from A (zero in lanes without the point, and in unused lanes), and their
  // rows but for the arms.
  WideVec3 ra[kMaxManifoldPoints], center_ra;
  constexpr std::size_t first = offsetof(ManifoldHead, first);
  ra[0] = {column(first + offsetof(ContactPoint, anchor_a)),
           column(first + offsetof(ContactPoint, anchor_a) + sizeof(Real)),
           column(first + offsetof(ContactPoint, anchor_a) + 2 * sizeof(Real))};
  c.first.separation = column(first + offsetof(ContactPoint, separation));
  c.first.normal_impulse = column(first + offsetof(ContactPoint, normal_impulse));
  center_ra = center_ra + ra[0];  // from zero, as the lanes were summed before (a -0 becomes +0)
  for (int k = 1; k < points; ++k) {
    WideNormalRow& p = row_of(c, rows, k);
    p.separation = p.normal_impulse = Wide{};
    for (int l = 0; l < lane_count; ++l) {
      const ManifoldHead& m = manifolds[lanes[l]];
      if (k >= m.point_count) continue;
      const ContactPoint& q = point_of(m, tails, k);
      set_lane(ra[k], l, q.anchor_a);
      p.separation[l] = q.separation;
      p.normal_impulse[l] = q.normal_impulse;
    }
    center_ra = center_ra + ra[k];
  }
  const Wide inv_count = inverse_or_zero(point_count);
  c.center_ra = inv_count * center_ra;
  c.center_rb = c.center_ra - b_from_a;
  for (int k = 1; k < points; ++k) {
    const auto used = point_count > splat(Real(k));
    rows[k - 1].offset_n = select(used, cross(ra[k] - c.center_ra, n), WideVec3{});
  }
  const BundleArms arms = bundle_arms(c, rows, points);
  for (int k = 0; k < points; ++k) {
    WideNormalRow& p = row_of(c, rows, k);
    // Lanes with fewer points leave this row empty: zero mass applies no impulse.
    const auto used = point_count > splat(Real(k));
    const PointArms r = arms_of(arms, rows, k);
    p.normal_mass = used ? normal_mass_of(r, ma, mb, m_sum) : zero;
    p.current_separation = p.separation;
    bounce.max_normal_impulse[k] = zero;
    bounce.relative_velocity[k] =
        used ? dot(n, vb.v - va.v) + dot(r.rb_n, vb.w) - dot(r.ra_n, va.w) : zero;
  }
  set_friction_mass(c, ma, mb);
  const Wide k_twist = dot(n, ma.inv_inertia * n) + dot(n, mb.inv_inertia * n);
  c.twist_mass = inverse_or_zero(k_twist);
  if (!ctx.loaded_lanes.empty()) {
    // A row is loaded when its soft spring would give more than kDirectGive under the impulse it
    // carried last step, lambda gamma / m_eff > kDirectGive (direct_solve.hpp), or its face is
    // sinking (kDirectDepth): pressed into a static or kinematic body deeper than a landing
    // overshoots, and its patch centre still closing, slower than an impact but by more than
    // kDirectGive a step. Two dynamic bodies pressed that deep have met in an impact or been
    // spawned overlapping, and what their rows carry is the push-out, not a load (a load shows
    // in the give),
    const auto fixed_b = mb.inv_mass == zero;
    const Wide give = fixed_b ? splat(ctx.static_give) : splat(ctx.contact_give);
    const Wide limit = splat(kDirectGive);
    auto loaded = give < zero;  // all false
    auto deep = loaded;
    // Face contacts only (three points or more): the resting support of a stack or a load. The
    // contacts of round shapes roll and spin, and their rows are left to the passes.
    const auto face = point_count > splat(Real(2));
    Wide warm = zero;
    Wide approach = zero;  // the points' relative normal velocities, summed (unused: zero)
    auto resting = point_count > zero;
    for (int k = 0; k < points; ++k) {
      const WideNormalRow& p = row_of(c, rows, k);
      loaded = loaded | (give * p.normal_impulse > limit * p.normal_mass);
      deep = deep | ((p.separation < splat(-kDirectDepth)) & (p.normal_mass > zero) & fixed_b);
      warm = warm + p.normal_impulse;
      approach = approach + bounce.relative_velocity[k];
      resting = resting & (bounce.relative_velocity[k] > splat(-kDirectRestSpeed));
    }
    // The relative normal velocity is linear in the point, so the points' mean is the patch
    // centre's: it closes (negative) faster than sink_speed while no point comes in as fast as
    // an impact. A face deep after an impact is being pushed out (opening), one deep in an
    // impact comes in fast: neither is a load (kDirectDepth).
    deep = deep & resting & (inv_count * approach < splat(-ctx.sink_speed));
    // or placed: a face of a body the API has just placed (kPlaced), met slowly, is a support
    // about to take its load with nothing to warm start from. Gauss-Seidel would carry a tower's
    // weight up from the ground over many steps, and the tower sink meanwhile by the soft give of
    // every contact under the load it reaches; so it is taken on its first step. Only then: a
    // pile's new contacts come from bodies landing, whose rows the passes settle well.
    auto placed = give < zero;  // all false
    for (int l = 0; ctx.bodies_placed && l < lane_count; ++l) {
      const ManifoldHead& m = manifolds[lanes[l]];
      if ((bodies.flags[m.body_a] | bodies.flags[m.body_b]) & kPlaced) placed[l] = ~placed[l];
    }
    loaded = loaded | ((warm == zero) & resting & placed);
    loaded = (loaded | deep) & face;
    deep = deep & face;
    uint32_t bits = 0;
    for (int l = 0; l < lane_count; ++l) {
      bits |= loaded[l] ? 1u << l : 0u;
      bits |= deep[l] ? 1u << (kLanes + l) : 0u;
    }
    // Not the lanes of bodies spawned into many others (the push-out share): their rows are
    // pressed in deep, but what they carry is the push-out, not a load, and the cliques they
    // form (deep_pairs.hpp) would make dense systems of hundreds of rows.
    ctx.loaded_lanes[bundle] = bits & ~(shared_lanes | shared_lanes << kLanes);
  }
}

void refresh_contacts(ContactSolverContext& ctx, const BodyStore& bodies,
                      std::span<const ManifoldHead> manifolds, std::span<const ManifoldTail> tails,
                      uint32_t begin, uint32_t end) {
  const Wide zero{};
  const Wide half = splat(Real(0.5));
  for (uint32_t i = begin; i < end; ++i) {
    ContactBundle& c = ctx.bundles[i];
    WideContactPoint* rows = ctx.rows_of(i);
    const int points = ctx.point_count(i);
    // Current separation from the pose change since the step began, linearised in the
    // rotation: s = s0 + n.(dp_b - dp_a) + (rb x n).dtheta_b - (ra x n).dtheta_a.
    WideVec3 dp_a, dtheta_a, dp_b, dtheta_b;
    gather_pose(ctx.bodies.data(), c.packet_a, dp_a, dtheta_a);
    gather_pose(ctx.bodies.data(), c.packet_b, dp_b, dtheta_b);
    const WideVec3& n = c.normal;
    const Wide dp_n = dot(n, dp_b - dp_a);
    const BundleArms arms = bundle_arms(c, rows, points);
    for (int k = 0; k < points; ++k) {
      WideNormalRow& p = row_of(c, rows, k);
      const PointArms r = arms_of(arms, rows, k);
      p.current_separation = p.separation + dp_n + dot(r.rb_n, dtheta_b) - dot(r.ra_n, dtheta_a);
    }
    // Against a static or kinematic body (not written: no inverse mass) the impulse is external
    // anyway: keep the arms. perf: resting contacts (most of a pile or stack) have barely moved
    // since the step began; their arms are then the step's own, within 0.1 mm, and re-deriving
    // them buys nothing.
    const WideVec3 slid = dp_b - dp_a;
    WideMass ma, mb;
    gather_mass(ctx.masses.data(), c.packet_a, ma);
    gather_mass(ctx.masses.data(), c.packet_b, mb);
    const auto refresh = (ma.inv_mass > zero) & (mb.inv_mass > zero) &
                         ((dot(slid, slid) >= splat(kRefreshDistance * kRefreshDistance)) |
                          (dot(dtheta_a, dtheta_a) + dot(dtheta_b, dtheta_b) >=
                           splat(kRefreshAngle * kRefreshAngle)));
    if (!any_lane(refresh)) continue;
    // perf: the lanes' manifolds and their bodies' positions, read below, are scattered over
    // the contact list and the body columns (a bundle's lanes are one colour's, in no order of
    // memory). Where this bundle moved the next ones likely did too (a pile in motion, not a
    // stack at rest): theirs are fetched while this one is refreshed, the heads two bundles
    // ahead and what they point at one ahead.
    if (i + 2 < end) {
      for (const uint32_t m : ctx.manifolds_of(i + 2)) prefetch(manifolds[m]);
    }
    if (i + 1 < end) {
      for (const uint32_t m : ctx.manifolds_of(i + 1)) {
        const ManifoldHead& head = manifolds[m];
        for (const uint32_t body : {uint32_t(head.body_a), uint32_t(head.body_b)}) {
          __builtin_prefetch(&bodies.px[body]);
          __builtin_prefetch(&bodies.py[body]);
          __builtin_prefetch(&bodies.pz[body]);
        }
        if (head.point_count > 1) prefetch(tails[head.tail]);
      }
    }
    // Lane by lane, for the lanes refreshed only: B's centre from A's at the step's start, the
    // point count and the mean of the contact points of the step's start (A's arms then), summed
    // and scaled as prepare_bundle does, so that it is the centre the offsets were taken from.
    WideVec3 start_b, center_start;
    Wide count{};
    const std::span<const uint32_t> lanes = ctx.manifolds_of(i);
    for (int l = 0; l < kLanes; ++l) {
      if (!refresh[l]) continue;  // unused lanes have no mass, so they are never refreshed
      const ManifoldHead& m = manifolds[lanes[l]];
      set_lane(start_b, l, bodies.position(m.body_b) - bodies.position(m.body_a));
      count[l] = Real(m.point_count);
      Vec3 sum = Vec3::Zero();
      for (int k = 0; k < m.point_count; ++k) sum = sum + point_of(m, tails, k).anchor_a;
      set_lane(center_start, l, (Real(1) / Real(m.point_count)) * sum);
    }
    // The centre of the step's start, carried by the mean translation of the two bodies (not
    // their rotation: a rolling sphere's contact stays under its centre), seen from each
    // centre now (relative to A's centre at the step's start, which keeps the numbers small).
    // A point's offset from the centre does not change, so the points move with it.
    const WideVec3 shared = center_start + half * (dp_a + dp_b);
    c.center_ra = select(refresh, shared - dp_a, c.center_ra);
    c.center_rb = select(refresh, shared - (start_b + dp_b), c.center_rb);
    // The inertias are those of the current orientation (integrate_positions turns them for
    // gyroscopic bodies: the integrator keeps L = I w with them, so impulses must change w
    // through them too).
    const Wide m_sum = ma.inv_mass + mb.inv_mass;
    const BundleArms moved = bundle_arms(c, rows, points);
    for (int k = 0; k < points; ++k) {
      WideNormalRow& p = row_of(c, rows, k);
      const auto used = refresh & (count > splat(Real(k)));
      const PointArms r = arms_of(moved, rows, k);
      // The same current separation, expressed with the new arms.
      const Wide s0 = p.current_separation - (dp_n + dot(r.rb_n, dtheta_b) - dot(r.ra_n, dtheta_a));
      p.normal_mass = used ? normal_mass_of(r, ma, mb, m_sum) : p.normal_mass;
      p.separation = used ? s0 : p.separation;
    }
    // The refreshed lanes' friction mass, from the current inertias. determinism (rule 8): only
    // theirs; a lane left alone keeps its own, so whether it is recomputed never depends on
    // the other lanes of its bundle (which differ between 8 and 16 lanes).
    const Wide k00 = c.inv_k00, k01 = c.inv_k01, k11 = c.inv_k11;
    set_friction_mass(c, ma, mb);
    c.inv_k00 = refresh ? c.inv_k00 : k00;
    c.inv_k01 = refresh ? c.inv_k01 : k01;
    c.inv_k11 = refresh ? c.inv_k11 : k11;
  }
}

void warm_start_contacts(ContactSolverContext& ctx, uint32_t begin, uint32_t end) {
  SolverBody* bodies = ctx.bodies.data();
  for (uint32_t i = begin; i < end; ++i) {
    const ContactBundle& c = ctx.bundles[i];
    const WideContactPoint* rows = ctx.rows_of(i);
    const int points = ctx.point_count(i);
    WideBody a, b;
    WideMass ma, mb;
    gather_velocity(bodies, c.packet_a, a);
    gather_velocity(bodies, c.packet_b, b);
    gather_mass(ctx.masses.data(), c.packet_a, ma);
    gather_mass(ctx.masses.data(), c.packet_b, mb);
    // The points' impulses summed first: one angular response per side instead of one per point.
    const BundleArms arms = bundle_arms(c, rows, points);
    Wide total{};
    WideVec3 ra_n_sum;
    for (int k = 0; k < points; ++k) {
      const Wide lambda = row_of(c, rows, k).normal_impulse;
      total += lambda;
      ra_n_sum = ra_n_sum + lambda * arms_of(arms, rows, k).ra_n;
    }
    const WideVec3 rb_n_sum = ra_n_sum - total * arms.b_offset_n;
    a.v = a.v - (ma.inv_mass * total) * c.normal;
    a.w = a.w - ma.inv_inertia * ra_n_sum;
    b.v = b.v + (mb.inv_mass * total) * c.normal;
    b.w = b.w + mb.inv_inertia * rb_n_sum;
    apply_friction(c, tangents_of(c.normal), ma, mb, a, b, c.tangent_impulse[0],
                   c.tangent_impulse[1]);
    apply_twist(c, ma, mb, a, b, c.twist_impulse);
    scatter_velocity(bodies, c.packet_a, ctx.written_end, a);
    scatter_velocity(bodies, c.packet_b, ctx.written_end, b);
  }
}

void solve_contacts(ContactSolverContext& ctx, uint32_t begin, uint32_t end, bool use_bias) {
  SolverBody* bodies = ctx.bodies.data();
  const Wide zero{};
  const Wide one = splat(1);
  // Against a static or kinematic B (not written, so zero inverse mass) the stiffer softness.
  const Softness& dyn = ctx.contact_softness;
  const Softness& fix = ctx.static_softness;
  for (uint32_t i = begin; i < end; ++i) {
    ContactBundle& c = ctx.bundles[i];
    WideContactPoint* rows = ctx.rows_of(i);
    const int points = ctx.point_count(i);
    WideBody a, b;
    WideMass ma, mb;
    gather_velocity(bodies, c.packet_a, a);
    gather_velocity(bodies, c.packet_b, b);
    gather_mass(ctx.masses.data(), c.packet_a, ma);
    gather_mass(ctx.masses.data(), c.packet_b, mb);
    const WideVec3& n = c.normal;
    const BundleArms arms = bundle_arms(c, rows, points);
    {
      // Friction first, so the non-penetration rows, which carry the load, have the last word.
      // Coulomb limits from the accumulated normal impulses: the tangent impulse within
      // mu * sum(lambda_n), the twist within mu * sum(lever_k * lambda_n_k). A point's lever is
      // its distance from the centre in the contact plane, |offset_n|: zero for a lone point.
      Wide total_normal{}, twist_limit{};
      for (int k = 0; k < points; ++k) {
        const Wide lambda = row_of(c, rows, k).normal_impulse;
        total_normal += lambda;
        if (points > 1) {
          const WideVec3& offset = offset_of(arms, rows, k);
          twist_limit += wide_sqrt(dot(offset, offset)) * lambda;
        }
      }
      // Velocity of B's centre point against A's: t . (v_b + w_b x rb - v_a - w_a x ra) is the
      // row velocity t . (v_b - v_a) + (rb x t) . w_b - (ra x t) . w_a of each tangent.
      const WideTangents t = tangents_of(n);
      const WideVec3 dv = (b.v + cross(b.w, c.center_rb)) - (a.v + cross(a.w, c.center_ra));
      const Wide v0 = dot(t.t0, dv), v1 = dot(t.t1, dv);
      Wide f0 = c.tangent_impulse[0] - (c.inv_k00 * v0 + c.inv_k01 * v1);
      Wide f1 = c.tangent_impulse[1] - (c.inv_k01 * v0 + c.inv_k11 * v1);
      const Wide max_friction = c.friction * total_normal;
      const Wide len2 = f0 * f0 + f1 * f1;
      const auto outside = len2 > max_friction * max_friction;
      if (any_lane(outside)) {
        // Outside the cone len2 > 0, so the division is safe where it is used.
        const Wide len = wide_sqrt(outside ? len2 : one);
        const Wide scale = outside ? max_friction / len : one;
        f0 *= scale;
        f1 *= scale;
      }
      apply_friction(c, t, ma, mb, a, b, f0 - c.tangent_impulse[0], f1 - c.tangent_impulse[1]);
      c.tangent_impulse[0] = f0;
      c.tangent_impulse[1] = f1;

      const Wide spin = dot(n, b.w - a.w);
      const Wide max_twist = c.friction * wide_max(twist_limit, kTorsionPatch * total_normal);
      const Wide twist =
          wide_min(wide_max(c.twist_impulse - c.twist_mass * spin, -max_twist), max_twist);
      apply_twist(c, ma, mb, a, b, twist - c.twist_impulse);
      c.twist_impulse = twist;
    }
    const Wide inv_h = splat(ctx.inv_h);
    const Wide max_push =
        ctx.push_cap.empty() ? splat(-ctx.max_push_velocity) : Wide{} - ctx.push_cap[i].v;
    const auto fixed_b = mb.inv_mass == zero;
    const Wide bias_rate = fixed_b ? splat(fix.bias_rate) : splat(dyn.bias_rate);
    const Wide soft_mass = fixed_b ? splat(fix.mass_scale) : splat(dyn.mass_scale);
    const Wide soft_impulse = fixed_b ? splat(fix.impulse_scale) : splat(dyn.impulse_scale);
    Wide* max_impulse = ctx.restitution.empty() ? nullptr : ctx.restitution[i].max_normal_impulse;
    for (int k = 0; k < points; ++k) {
      WideNormalRow& p = row_of(c, rows, k);
      const PointArms r = arms_of(arms, rows, k);
      const Wide s = p.current_separation;
      // Speculative (s > 0): allow closing the gap within this substep only. Penetrating: the
      // soft spring pushes out, or nothing in the relax pass.
      const auto gap = s > zero;
      Wide bias = gap ? s * inv_h : zero, mass_scale = one, impulse_scale = zero;
      if (use_bias) {
        bias = gap ? bias : wide_max(bias_rate * s, max_push);
        mass_scale = gap ? one : soft_mass;
        impulse_scale = gap ? zero : soft_impulse;
      }
      const Wide vn = row_velocity(a, b, n, r.ra_n, r.rb_n);
      Wide impulse = -p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
      const Wide updated = wide_max(p.normal_impulse + impulse, zero);
      impulse = updated - p.normal_impulse;
      p.normal_impulse = updated;
      if (max_impulse != nullptr) max_impulse[k] = wide_max(max_impulse[k], impulse);
      apply_row(c, ma, mb, a, b, r, impulse);
    }
    scatter_velocity(bodies, c.packet_a, ctx.written_end, a);
    scatter_velocity(bodies, c.packet_b, ctx.written_end, b);
  }
}

void apply_restitution(ContactSolverContext& ctx, uint32_t begin, uint32_t end) {
  if (ctx.restitution.empty()) return;  // no body bounces
  SolverBody* bodies = ctx.bodies.data();
  const Wide zero{};
  const Wide threshold = splat(-ctx.restitution_threshold);
  for (uint32_t i = begin; i < end; ++i) {
    const BundleRestitution& bounce = ctx.restitution[i];
    if (!any_lane(bounce.restitution != zero)) continue;
    ContactBundle& c = ctx.bundles[i];
    WideContactPoint* rows = ctx.rows_of(i);
    const int points = ctx.point_count(i);
    WideBody a, b;
    WideMass ma, mb;
    gather_velocity(bodies, c.packet_a, a);
    gather_velocity(bodies, c.packet_b, b);
    gather_mass(ctx.masses.data(), c.packet_a, ma);
    gather_mass(ctx.masses.data(), c.packet_b, mb);
    const BundleArms arms = bundle_arms(c, rows, points);
    for (int k = 0; k < points; ++k) {
      WideNormalRow& p = row_of(c, rows, k);
      const PointArms r = arms_of(arms, rows, k);
      const Wide approach = bounce.relative_velocity[k];
      // Only points that approached faster than the threshold and actually pushed bounce.
      const auto bounces = (bounce.restitution != zero) & (approach <= threshold) &
                           (bounce.max_normal_impulse[k] != zero);
      const Wide vn = row_velocity(a, b, c.normal, r.ra_n, r.rb_n);
      Wide impulse = -p.normal_mass * (vn + bounce.restitution * approach);
      impulse = bounces ? impulse : zero;
      const Wide updated = wide_max(p.normal_impulse + impulse, zero);
      impulse = updated - p.normal_impulse;
      p.normal_impulse = updated;
      apply_row(c, ma, mb, a, b, r, impulse);
    }
    scatter_velocity(bodies, c.packet_a, ctx.written_end, a);
    scatter_velocity(bodies, c.packet_b, ctx.written_end, b);
  }
}

void store_impulses(const ContactSolverContext& ctx, uint32_t begin, uint32_t end,
                    std::span<ManifoldHead> manifolds, std::span<ManifoldTail> tails) {
  for (uint32_t i = begin; i < end; ++i) {
    const ContactBundle& c = ctx.bundles[i];
    const WideContactPoint* rows = ctx.rows_of(i);
    const std::span<const uint32_t> lanes = ctx.manifolds_of(i);
    for (std::size_t l = 0; l < lanes.size(); ++l) {
      ManifoldHead& m = manifolds[lanes[l]];
      for (int k = 0; k < m.point_count; ++k) {
        point_of(m, tails, k).normal_impulse = row_of(c, rows, k).normal_impulse[l];
      }
      m.tangent_impulse[0] = c.tangent_impulse[0][l];
      m.tangent_impulse[1] = c.tangent_impulse[1][l];
      m.twist_impulse = c.twist_impulse[l];
    }
  }
}

ELAN_ISA_END
}  // namespace elan::detail
