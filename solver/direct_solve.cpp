// SPDX-License-Identifier: MIT
// The direct solve of loaded contact and joint rows (direct_solve.hpp).
#include "solver/direct_solve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace elan::detail {

namespace {

using Vec3d = Eigen::Vector3d;

// A joint row's rows as items: its order key is past every manifold's.
constexpr uint64_t kJointOrder = uint64_t(1) << 31;

// Active-set rounds: a resting stack needs one, a box tipping onto an edge two or three.
constexpr int kMaxRounds = 8;
// m/s: a row left out of the set whose velocity misses its target by less is satisfied.
constexpr double kVelocityTolerance = 1e-6;
// A system whose impulse exceeds this many times its scale is rejected (solve_direct).
constexpr double kSaneImpulse = 16;
// A body may leave a direct system faster than the fastest came in plus the push-out cap by this
// many m/s and this share of that speed.
constexpr double kSaneSpeedMargin = 1;
constexpr double kSaneSpeedShare = 0.01;

// |v| of slot s of a velocity array (6 a slot, linear first).
double linear_speed(const std::vector<double>& v, uint32_t s) {
  const double* x = &v[6 * std::size_t(s)];
  return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}
// A pivot below this fraction of its diagonal marks a row dependent on those before it.
constexpr double kDependentPivot = 1e-12;
// The compliance each row keeps, as a fraction of its diagonal: (A + eps diag A) lambda = b.
// It makes the system definite (a face's four points have three independent rows), so the
// split of a load between coplanar points is the least-squares one and the active-set rounds
// do not cycle between equal splits; it costs a give of eps A_ii lambda / beta: 2 micrometres
// for 500 kg on 1 kg, 4 cm for 1e6 kg on 1 kg (which then stands).
constexpr double kCompliance = 1e-6;
// A system's whole envelope (below the diagonal) is kept for its active-set rounds up to this
// many entries: the small systems of stacks and piles, whose rounds it spares the assembly.
constexpr std::size_t kWholeEnvelope = 16 * 1024;

// Capacity for n, a quarter past it when it must grow: the buffers are sized to what a step can
// need at most (every manifold of a small island and every joint loaded, a system of
// kDirectMaxRows), so a warm step allocates nothing.
template <class V>
void reserve_for(V& v, std::size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 4);
}

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];  // path halving
    i = parent[i];
  }
  return i;
}

double dot6(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
}

// The entry A_ij = sum over the sides of i and j on one packet of J_i,s M^-1 J_j,t^T.
double entry(const DirectScratch& ws, const DirectRow& ri, const DirectRow& rj, uint32_t i,
             uint32_t j) {
  double sum = 0;
  for (int s = 0; s < 2; ++s) {
    if (ri.slot[s] < 0) continue;
    for (int t = 0; t < 2; ++t) {
      if (rj.slot[t] != ri.slot[s]) continue;
      sum += dot6(&ws.jac[12 * i + 6 * s], &ws.mjac[12 * j + 6 * t]);
    }
  }
  return sum;
}

// Solves A_SS x = rhs_S for the active rows (ws.active, in row order) of the system whose rows
// start at `base`: assembles the envelope, factors it by Cholesky (dependent rows get x = 0),
// and writes ws.delta for the active rows. Returns false when the envelope is too large.
bool solve_active(const DirectState& ds, DirectScratch& ws, uint32_t base, uint32_t slot_begin,
                  uint32_t slot_end) {
  const std::size_t n = ws.active.size();
  for (uint32_t s = slot_begin; s < slot_end; ++s) ws.slot_first[s] = -1;
  ws.first.resize(n);
  ws.offset.resize(n + 1);
  ws.offset[0] = 0;
  for (std::size_t a = 0; a < n; ++a) {
    const DirectRow& r = ds.rows[base + ws.active[a]];
    int32_t f = int32_t(a);
    for (int s = 0; s < 2; ++s) {
      if (r.slot[s] < 0) continue;
      int32_t& first = ws.slot_first[r.slot[s]];
      if (first < 0) first = int32_t(a);
      f = std::min(f, first);
    }
    ws.first[a] = f;
    ws.offset[a + 1] = ws.offset[a] + (a - std::size_t(f) + 1);
  }
  if (ws.offset[n] > kDirectMaxEnvelope) return false;
  ws.factor.resize(ws.offset[n]);
  ws.dependent.assign(n, 0);
  auto at = [&](std::size_t i, std::size_t j) -> double& {
    return ws.factor[ws.offset[i] + (j - std::size_t(ws.first[i]))];
  };
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t ri = ws.active[i];
    if (ws.whole_ready) {
      // The active rows of i's envelope are rows of its envelope over all rows (the first active
      // row on a slot of i comes no earlier than the first row on it).
      const double* whole = ws.whole.data() + ws.whole_offset[ri];
      const uint32_t whole_first = ws.whole_first[ri];
      for (std::size_t j = std::size_t(ws.first[i]); j < i; ++j) {
        at(i, j) = whole[ws.active[j] - whole_first];
      }
    } else {
      for (std::size_t j = std::size_t(ws.first[i]); j < i; ++j) {
        const uint32_t rj = ws.active[j];
        at(i, j) = entry(ws, ds.rows[base + ri], ds.rows[base + rj], ri, rj);
      }
    }
    at(i, i) = ws.diagonal[ri];
    at(i, i) *= 1 + kCompliance;
  }
  // Cholesky in the envelope (Jennings): L_ij = (A_ij - sum_k L_ik L_jk) / L_jj over the common
  // envelope, L_ii = sqrt(A_ii - sum_k L_ik^2). A dependent row's column is zero.
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t fi = std::size_t(ws.first[i]);
    for (std::size_t j = fi; j < i; ++j) {
      double v = at(i, j);
      if (ws.dependent[j]) {
        at(i, j) = 0;
        continue;
      }
      const std::size_t k0 = std::max(fi, std::size_t(ws.first[j]));
      for (std::size_t k = k0; k < j; ++k) v -= at(i, k) * at(j, k);
      at(i, j) = v / at(j, j);
    }
    const double diagonal = at(i, i);
    double d = diagonal;
    for (std::size_t k = fi; k < i; ++k) d -= at(i, k) * at(i, k);
    if (!(d > kDependentPivot * diagonal) || !(diagonal > 0)) {
      ws.dependent[i] = 1;
      at(i, i) = 1;
      for (std::size_t k = fi; k < i; ++k) at(i, k) = 0;
    } else {
      at(i, i) = std::sqrt(d);
    }
  }
  // L y = b, then L^T x = y (column-wise, in the envelope).
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t ri = ws.active[i];
    if (ws.dependent[i]) {
      ws.delta[ri] = 0;
      continue;
    }
    double v = ws.rhs[ri];
    for (std::size_t k = std::size_t(ws.first[i]); k < i; ++k)
      v -= at(i, k) * ws.delta[ws.active[k]];
    ws.delta[ri] = v / at(i, i);
  }
  for (std::size_t i = n; i-- > 0;) {
    const uint32_t ri = ws.active[i];
    if (ws.dependent[i]) continue;
    const double x = ws.delta[ri] / at(i, i);
    ws.delta[ri] = x;
    for (std::size_t k = std::size_t(ws.first[i]); k < i; ++k) {
      ws.delta[ws.active[k]] -= at(i, k) * x;
    }
  }
  return true;
}

// Row velocity J v over the slots' velocities `v` (6 a slot).
double row_velocity(const DirectScratch& ws, const DirectRow& r, uint32_t i, const double* v) {
  double sum = 0;
  for (int s = 0; s < 2; ++s) {
    if (r.slot[s] >= 0) sum += dot6(&ws.jac[12 * i + 6 * s], v + 6 * r.slot[s]);
  }
  return sum;
}

void set6(double* out, const Vec3& a, const Vec3& b, double sign) {
  for (int k = 0; k < 3; ++k) {
    out[k] = sign * double(a[k]);
    out[3 + k] = sign * double(b[k]);
  }
}

// The blocks of the direct stage: runs of systems of about equal rows (a system's cost grows with
// its rows), each a set of whole groups of systems that share a contact bundle (two systems'
// lanes of one bundle are solved by one block: a store into one lane of a SIMD vector may be a
// read-modify-write of the whole vector). Groups go to the first block until its rows reach
// 1 / kDirectBlocks of all, and so on; within a block systems keep their order. Systems share no
// written body, so their order and blocks change no bit of their solutions.
// Its buffers are reserved by build_direct_systems.
void deal_systems(DirectState& ds) {
  const uint32_t count = uint32_t(ds.systems.size());
  // Groups by union-find over the systems, each system linked to the first that used its
  // bundles; linked toward the lower index (determinism: roots do not depend on visit order).
  ds.group.resize(count);
  for (uint32_t si = 0; si < count; ++si) ds.group[si] = si;
  for (uint32_t si = 0; si < count; ++si) {
    for (uint32_t r = ds.systems[si].row_begin; r < ds.systems[si].row_end; ++r) {
      const DirectRow& row = ds.rows[r];
      if (row.kind == kDirectJoint) continue;
      uint32_t& owner = ds.system_of_bundle[row.source];
      if (owner == UINT32_MAX) {
        owner = si;
        continue;
      }
      const uint32_t ra = find_root(ds.group, owner), rb = find_root(ds.group, si);
      if (ra < rb) ds.group[rb] = ra;
      if (rb < ra) ds.group[ra] = rb;
    }
  }
  for (const DirectRow& row : ds.rows) {
    if (row.kind != kDirectJoint) ds.system_of_bundle[row.source] = UINT32_MAX;
  }
  for (uint32_t si = 0; si < count; ++si) ds.group[si] = find_root(ds.group, si);
  for (uint32_t& b : ds.block_begin) b = 0;
  if (kDirectBlocks == 1 || count == 0) {
    for (uint32_t b = 1; b <= kDirectBlocks; ++b) ds.block_begin[b] = count;
    return;
  }
  // A group's rows, at its root (its first system), then the root's block: in root order, block b
  // while the rows of the groups before are under (b + 1) / kDirectBlocks of all.
  ds.group_rows.assign(count, 0);
  for (uint32_t si = 0; si < count; ++si) {
    ds.group_rows[ds.group[si]] += ds.systems[si].row_end - ds.systems[si].row_begin;
  }
  const uint64_t total = ds.rows.size();
  uint64_t before = 0;
  for (uint32_t si = 0; si < count; ++si) {
    if (ds.group[si] != si) continue;
    const uint64_t rows = ds.group_rows[si];
    ds.group_rows[si] = std::min<uint64_t>(kDirectBlocks - 1, before * kDirectBlocks / total);
    before += rows;
  }
  // The systems in block order, each block's in their own order.
  ds.dealt.clear();
  for (uint32_t b = 0; b < kDirectBlocks; ++b) {
    ds.block_begin[b] = uint32_t(ds.dealt.size());
    for (uint32_t si = 0; si < count; ++si) {
      if (ds.group_rows[ds.group[si]] == b) ds.dealt.push_back(ds.systems[si]);
    }
  }
  ds.block_begin[kDirectBlocks] = count;
  ds.systems.swap(ds.dealt);
}

}  // namespace

Real give_per_impulse(const Softness& s) {
  const Real denominator = s.mass_scale * s.bias_rate;
  return denominator > 0 ? s.impulse_scale / denominator : Real(0);
}

bool build_direct_systems(const ContactSolverContext& ctx, std::span<const ManifoldHead> contacts,
                          std::span<const JointRow> joints, std::size_t joint_grain,
                          std::span<const uint32_t> island_root,
                          std::span<const uint32_t> island_size, DirectState& ds) {
  ds.systems.clear();
  ds.rows.clear();
  ds.packets.clear();
  ds.item_source.clear();
  for (uint32_t& b : ds.block_begin) b = 0;
  const uint32_t written_end = ctx.written_end;
  // An item's island: that of its written side (a loaded row has one).
  auto root_of = [&](uint32_t a, uint32_t b) -> uint32_t {
    const uint32_t p = written_packet(a, written_end) ? a : b;
    if (!written_packet(p, written_end)) return UINT32_MAX;
    return island_root[ctx.masses[p].body];
  };
  // The loaded rows of islands small enough: items (bundle << 8 | lane) and
  // (kJointOrder << 32 | joint row).
  auto small = [&](uint32_t root) {
    return root != UINT32_MAX && island_size[root] <= kDirectMaxBodies;
  };
  // At most every manifold of an island of at most kDirectMaxBodies bodies is an item, and every
  // joint row. memory: bounded by those manifolds, not by all of them, since a pile of large
  // islands has none (its buffers would hold about a quarter of the world's bytes unused).
  std::size_t small_manifolds = 0;
  for (const ManifoldHead& m : contacts) small_manifolds += small(island_root[m.body_a]);
  const std::size_t item_bound =
      std::min(small_manifolds, ctx.lane_manifolds.size()) + joints.size();
  reserve_for(ds.item_source, item_bound);
  const std::size_t bundles = std::min(ds.loaded_lanes.size(), ctx.bundles.size());
  for (std::size_t j = 0; j < bundles; ++j) {
    const uint32_t mask = ds.loaded_lanes[j] & kLaneBits;
    if (mask == 0) continue;
    const ContactBundle& c = ctx.bundles[j];
    for (int l = 0; l < kLanes; ++l) {
      if ((mask & (1u << l)) && small(root_of(c.packet_a[l], c.packet_b[l]))) {
        ds.item_source.push_back(uint64_t(j) << 8 | uint64_t(l));
      }
    }
  }
  for (std::size_t b = 0; b < ds.loaded_joint_blocks.size(); ++b) {
    if (!ds.loaded_joint_blocks[b]) continue;
    const std::size_t end = std::min(joints.size(), (b + 1) * joint_grain);
    for (std::size_t r = b * joint_grain; r < end; ++r) {
      if ((joints[r].flags & kJointLoaded) &&
          small(root_of(joints[r].packet_a, joints[r].packet_b))) {
        ds.item_source.push_back(kJointOrder << 32 | r);
      }
    }
  }
  // Reserved every step, as the contact store grows, not on the first step with a system: a
  // new face contact may bring a pile's first system on any step (prepare_bundle).
  reserve_for(ds.items, 2 * item_bound);
  reserve_for(ds.systems, item_bound);
  reserve_for(ds.group, item_bound);
  reserve_for(ds.group_rows, item_bound);
  reserve_for(ds.dealt, item_bound);
  if (ds.system_of_bundle.size() < ctx.bundles.size()) {
    reserve_for(ds.system_of_bundle, ctx.bundles.size());
    ds.system_of_bundle.resize(ctx.bundles.size(), UINT32_MAX);
  }
  reserve_for(ds.rows, (3 + kMaxManifoldPoints) * (item_bound - joints.size()) + 3 * joints.size());
  reserve_for(ds.packets, ctx.bodies.size());
  reserve_for(ds.order, std::max<std::size_t>(item_bound, kDirectMaxRows));
  if (ds.item_source.empty()) return false;
  auto packets_of = [&](uint64_t item, uint32_t& a, uint32_t& b) {
    if (item >> 32) {
      const JointRow& r = joints[uint32_t(item)];
      a = r.packet_a;
      b = r.packet_b;
    } else {
      const ContactBundle& c = ctx.bundles[item >> 8];
      a = c.packet_a[item & 0xff];
      b = c.packet_b[item & 0xff];
    }
    if (!written_packet(a, written_end)) a = 0;
    if (!written_packet(b, written_end)) b = 0;
  };
  // Systems: the loaded rows linked through their written bodies (union-find over packets).
  if (ds.parent.size() < ctx.bodies.size()) {
    reserve_for(ds.parent, ctx.bodies.size());
    ds.parent.resize(ctx.bodies.size());
  }
  if (ds.slot_of.size() < ctx.bodies.size()) {
    reserve_for(ds.slot_of, ctx.bodies.size());
    ds.slot_of.resize(ctx.bodies.size(), -1);
  }
  for (const uint64_t item : ds.item_source) {
    uint32_t a, b;
    packets_of(item, a, b);
    ds.parent[a] = a;
    ds.parent[b] = b;
  }
  for (const uint64_t item : ds.item_source) {
    uint32_t a, b;
    packets_of(item, a, b);
    if (a == 0 || b == 0) continue;
    // determinism: link toward the lower packet, so a root does not depend on item order.
    const uint32_t ra = find_root(ds.parent, a), rb = find_root(ds.parent, b);
    if (ra < rb) ds.parent[rb] = ra;
    if (rb < ra) ds.parent[ra] = rb;
  }
  // Keyed (root << 32 | order): manifolds by their index in the contact list (key order: a
  // column of bodies is a band), joints by joint order after them (a chain is a band).
  ds.items.clear();
  for (std::size_t k = 0; k < ds.item_source.size(); ++k) {
    const uint64_t item = ds.item_source[k];
    uint32_t a, b;
    packets_of(item, a, b);
    const uint64_t root = find_root(ds.parent, a != 0 ? a : b);
    const uint64_t order = (item >> 32)
                               ? kJointOrder | joints[uint32_t(item)].joint
                               : ctx.lane_manifolds[ctx.lane_start[item >> 8] + (item & 0xff)];
    ds.items.push_back(root << 32 | order);
    ds.items.push_back(k);
  }
  // Pairs (key, index): sort the keys with their indices by sorting indices by key.
  const std::size_t count = ds.item_source.size();
  ds.order.resize(count);
  for (std::size_t k = 0; k < count; ++k) ds.order[k] = uint32_t(k);
  std::sort(ds.order.begin(), ds.order.end(),
            [&](uint32_t x, uint32_t y) { return ds.items[2 * x] < ds.items[2 * y]; });
  std::size_t k = 0;
  while (k < count) {
    const uint64_t root = ds.items[2 * ds.order[k]] >> 32;
    std::size_t end = k;
    uint32_t row_count = 0;
    // One manifold, not sinking into a static surface (kDirectDepth).
    bool lone = false;
    uint32_t manifolds = 0;
    bool joint = false, deep = false;
    Real most_inv = 0, least_inv = std::numeric_limits<Real>::max();
    while (end < count && (ds.items[2 * ds.order[end]] >> 32) == root) {
      const uint64_t item = ds.item_source[ds.order[end]];
      const bool item_deep =
          !(item >> 32) && ((ds.loaded_lanes[item >> 8] >> (kLanes + (item & 0xff))) & 1u);
      lone = end == k && !(item >> 32) && !item_deep;
      joint = joint || (item >> 32);
      deep = deep || item_deep;
      manifolds += (item >> 32) ? 0u : 1u;
      uint32_t pa, pb;
      packets_of(item, pa, pb);
      for (const uint32_t p : {pa, pb}) {
        if (p == 0) continue;
        most_inv = std::max(most_inv, ctx.masses[p].inv_mass);
        least_inv = std::min(least_inv, ctx.masses[p].inv_mass);
      }
      row_count +=
          (item >> 32)
              ? 3u
              : uint32_t(contacts[ctx.lane_manifolds[ctx.lane_start[item >> 8] + (item & 0xff)]]
                             .point_count);
      ++end;
    }
    // A lone manifold is left to the passes. With no other loaded row on its bodies, no load
    // reaches it through a chain of bodies or a light body, which is what Gauss-Seidel cannot
    // carry within its passes; its give is one contact's, F / (m_eff omega^2), F at most the
    // weight of its bodies and of the unloaded rows around them (a table on a table or on the
    // ground). Such a row is past kDirectGive mostly for a step or two after an impact, and an
    // active set that chases a bouncing body seldom settles. A mass ratio has a second loaded
    // row (the light body's support), a tower many. A face sinking into a static surface
    // (kDirectDepth: deep, and still closing) is solved alone all the same.
    // So is a short stack of even masses (kDirectShortStack, kDirectEvenMass): no light body
    // under a heavy one and no long chain, so the passes carry its load within a step or two,
    // and its rows give what kDirectGive allows a few bodies' weight. The active set of such a
    // system is mostly chasing landing bodies (a pile's columns as they fall onto each other),
    // whose speculative rows the passes let close within the substep.
    const bool short_even = !joint && !deep && manifolds <= kDirectShortStack &&
                            most_inv <= kDirectEvenMass * least_inv;
    if (row_count <= kDirectMaxRows && !lone && !short_even) {
      DirectSystem system;
      system.row_begin = uint32_t(ds.rows.size());
      system.packet_begin = uint32_t(ds.packets.size());
      auto slot = [&](uint32_t packet) -> int32_t {
        if (packet == 0) return -1;
        int32_t& s = ds.slot_of[packet];
        if (s < 0) {
          s = int32_t(ds.packets.size() - system.packet_begin);
          ds.packets.push_back(packet);
        }
        return s;
      };
      for (std::size_t e = k; e < end; ++e) {
        const uint64_t item = ds.item_source[ds.order[e]];
        uint32_t a, b;
        packets_of(item, a, b);
        DirectRow row;
        row.slot[0] = slot(a);
        row.slot[1] = slot(b);
        if (item >> 32) {
          row.source = uint32_t(item);
          row.kind = kDirectJoint;
          for (uint8_t axis = 0; axis < 3; ++axis) {
            row.point = axis;
            ds.rows.push_back(row);
          }
        } else {
          row.source = uint32_t(item >> 8);
          row.lane = uint8_t(item & 0xff);
          const ManifoldHead& m =
              contacts[ctx.lane_manifolds[ctx.lane_start[row.source] + row.lane]];
          row.head = uint32_t(ds.rows.size()) - system.row_begin;
          row.count = m.point_count;
          for (uint8_t p = 0; p < m.point_count; ++p) {
            row.point = p;
            ds.rows.push_back(row);
          }
          row.point = 0;
          for (const uint8_t kind : {kDirectTangent0, kDirectTangent1, kDirectTwist}) {
            row.kind = kind;
            ds.rows.push_back(row);
          }
        }
      }
      system.row_end = uint32_t(ds.rows.size());
      system.packet_end = uint32_t(ds.packets.size());
      for (uint32_t p = system.packet_begin; p < system.packet_end; ++p) {
        ds.slot_of[ds.packets[p]] = -1;
      }
      ds.systems.push_back(system);
    }
    k = end;
  }
  deal_systems(ds);
  return !ds.systems.empty();
}

void solve_direct(ContactSolverContext& ctx, std::span<JointRow> joints, bool use_bias,
                  DirectState& ds, uint32_t block) {
  DirectScratch& ws = ds.scratch[block];
  const double max_push = double(ctx.max_push_velocity);
  // A normal row joins the first active set when its closing speed is above this (see below).
  const double open_below = ctx.bodies_placed ? -kVelocityTolerance : 0.0;
  // The largest system's buffers, once (a system has at most kDirectMaxRows rows and
  // kDirectMaxBodies packets).
  constexpr std::size_t rows_max = kDirectMaxRows, slots_max = 2 * kDirectMaxBodies;
  reserve_for(ws.jac, 12 * rows_max);
  reserve_for(ws.mjac, 12 * rows_max);
  for (std::vector<double>* v :
       {&ws.target, &ws.lambda, &ws.rhs, &ws.delta, &ws.fixed, &ws.lever, &ws.diagonal}) {
    reserve_for(*v, rows_max);
  }
  reserve_for(ws.in_set, rows_max);
  reserve_for(ws.dependent, rows_max);
  reserve_for(ws.first, rows_max);
  reserve_for(ws.offset, rows_max + 1);
  reserve_for(ws.factor, kDirectMaxEnvelope);
  reserve_for(ws.whole, kWholeEnvelope);
  reserve_for(ws.whole_first, rows_max);
  reserve_for(ws.whole_offset, rows_max);
  reserve_for(ws.velocity, 6 * slots_max);
  reserve_for(ws.trial, 6 * slots_max);
  reserve_for(ws.slot_first, slots_max);
  for (uint32_t si = ds.block_begin[block]; si < ds.block_begin[block + 1]; ++si) {
    const DirectSystem& system = ds.systems[si];
    const uint32_t n = system.row_end - system.row_begin;
    const uint32_t slots = system.packet_end - system.packet_begin;
    const DirectRow* rows = ds.rows.data() + system.row_begin;
    ws.jac.resize(12 * std::size_t(n));
    ws.mjac.resize(12 * std::size_t(n));
    for (std::vector<double>* v :
         {&ws.target, &ws.lambda, &ws.rhs, &ws.delta, &ws.fixed, &ws.lever, &ws.diagonal}) {
      v->resize(n);
    }
    ws.in_set.resize(n);
    ws.whole_first.resize(n);
    ws.whole_offset.resize(n);
    ws.velocity.resize(6 * std::size_t(slots));
    ws.trial.resize(6 * std::size_t(slots));
    if (ws.slot_first.size() < slots) ws.slot_first.resize(slots);
    for (uint32_t s = 0; s < slots; ++s) {
      const SolverBody& b = ctx.bodies[ds.packets[system.packet_begin + s]];
      for (int k = 0; k < 3; ++k) {
        ws.velocity[6 * s + k] = double(b.v[k]);
        ws.velocity[6 * s + 3 + k] = double(b.w[k]);
      }
    }
    // Each row's Jacobian (per side sigma (d, r x d)), its M^-1 J^T, target and impulse.
    for (uint32_t i = 0; i < n; ++i) {
      const DirectRow& r = rows[i];
      Vec3 lin_a, ang_a, lin_b, ang_b;  // J = [-lin_a, -ang_a, lin_b, ang_b]
      double lambda = 0;
      ws.target[i] = 0;
      ws.lever[i] = 0;
      if (r.kind == kDirectJoint) {
        const JointRow& j = joints[r.source];
        const Vec3 d = Vec3::Unit(r.point);
        lin_a = lin_b = d;
        ang_a = j.pose.r_a.cross(d);
        ang_b = j.pose.r_b.cross(d);
        lambda = double(j.point_impulse[r.point]);
        if (use_bias) {
          ws.target[i] = -double(j.softness.bias_rate) * double(j.pose.separation[r.point]);
        }
      } else {
        const ContactBundle& c = ctx.bundles[r.source];
        const WideContactPoint* points = ctx.rows_of(r.source);
        const int count = ctx.point_count(r.source);
        const int l = r.lane;
        auto lane3 = [&](const WideVec3& w) { return Vec3(w.x[l], w.y[l], w.z[l]); };
        const Vec3 n = lane3(c.normal);
        const Vec3 center_ra = lane3(c.center_ra), center_rb = lane3(c.center_rb);
        if (r.kind == kDirectNormal) {
          // The arms as the passes derive them (WideContactPoint): the first point's offset is
          // minus the sum of the others'.
          Vec3 offset = Vec3::Zero();
          if (r.point == 0) {
            for (int k = 1; k < count; ++k) offset -= lane3(points[k - 1].offset_n);
          } else {
            offset = lane3(points[r.point - 1].offset_n);
          }
          lin_a = lin_b = n;
          ang_a = center_ra.cross(n) + offset;
          ang_b = ang_a - (center_ra - center_rb).cross(n);
          ws.lever[i] = r.count > 1 ? double(offset.norm()) : 0.0;
          const WideNormalRow& p = r.point == 0 ? c.first : points[r.point - 1].row;
          const double s = double(p.current_separation[l]);
          lambda = double(p.normal_impulse[l]);
          const bool fixed_b = !written_packet(c.packet_b[l], ctx.written_end);
          const double beta =
              double(fixed_b ? ctx.static_softness.bias_rate : ctx.contact_softness.bias_rate);
          // One linear law on both sides of contact, -beta s (a gap closes at beta s, not
          // within the substep as the passes let it): the targets of a face's points are then
          // those of one rigid motion, consistent with its three independent rows. Relaxed: 0.
          if (use_bias) ws.target[i] = std::min(-beta * s, max_push);
        } else if (r.kind == kDirectTwist) {
          lin_a = lin_b = Vec3::Zero();
          ang_a = ang_b = n;
          lambda = double(c.twist_impulse[l]);
        } else {
          const int t = r.kind == kDirectTangent0 ? 0 : 1;
          // The passes' tangent basis (tangents_of), for this lane.
          const WideTangents basis = tangents_of(c.normal);
          const Vec3 d = lane3(t == 0 ? basis.t0 : basis.t1);
          lin_a = lin_b = d;
          ang_a = center_ra.cross(d);
          ang_b = center_rb.cross(d);
          lambda = double(c.tangent_impulse[t][l]);
        }
      }
      double* jac = &ws.jac[12 * std::size_t(i)];
      double* mjac = &ws.mjac[12 * std::size_t(i)];
      set6(jac, lin_a, ang_a, -1);
      set6(jac + 6, lin_b, ang_b, 1);
      for (int s = 0; s < 2; ++s) {
        double* out = mjac + 6 * s;
        if (r.slot[s] < 0) {
          for (int k = 0; k < 6; ++k) out[k] = 0;
          continue;
        }
        const SolverBodyMass& m = ctx.masses[ds.packets[system.packet_begin + r.slot[s]]];
        const double* in = jac + 6 * s;
        const SymMat3& I = m.inv_inertia;
        for (int k = 0; k < 3; ++k) out[k] = double(m.inv_mass) * in[k];
        out[3] = double(I.xx) * in[3] + double(I.xy) * in[4] + double(I.xz) * in[5];
        out[4] = double(I.xy) * in[3] + double(I.yy) * in[4] + double(I.yz) * in[5];
        out[5] = double(I.xz) * in[3] + double(I.yz) * in[4] + double(I.zz) * in[5];
      }
      ws.lambda[i] = lambda;
      ws.delta[i] = 0;
      // The first set: every row but the normal rows that neither push nor are being closed,
      // which are held at zero. After bodies were placed, rows closing at no speed join too: a
      // column placed at rest falls as one under gravity, so its upper rows close only once the
      // rows below them push, which the set would otherwise find one round each.
      ws.in_set[i] = 1;
      ws.fixed[i] = 0;
      if (r.kind == kDirectNormal) {
        const double closing = ws.target[i] - row_velocity(ws, r, i, ws.velocity.data());
        ws.in_set[i] = uint8_t(lambda > 0 || closing > open_below);
      }
    }
    // perf: A's diagonal, read by every active-set round (the compliance term and the
    // envelope), once a pass: entry() of the same rows, so the same bits.
    for (uint32_t i = 0; i < n; ++i) ws.diagonal[i] = entry(ws, rows[i], rows[i], i, i);
    // perf: and A's envelope over all the rows, once a pass rather than once an active-set round
    // (the same entry() of the same rows, so the rounds factor the same bits), when it fits.
    ws.whole_ready = false;
    {
      for (uint32_t s = 0; s < slots; ++s) ws.slot_first[s] = -1;
      std::size_t size = 0;
      for (uint32_t i = 0; i < n; ++i) {
        int32_t f = int32_t(i);
        for (int s = 0; s < 2; ++s) {
          if (rows[i].slot[s] < 0) continue;
          int32_t& first = ws.slot_first[rows[i].slot[s]];
          if (first < 0) first = int32_t(i);
          f = std::min(f, first);
        }
        ws.whole_first[i] = uint32_t(f);
        ws.whole_offset[i] = size;
        size += i - uint32_t(f);
      }
      if (size <= kWholeEnvelope) {
        ws.whole.resize(size);
        for (uint32_t i = 0; i < n; ++i) {
          double* out = &ws.whole[ws.whole_offset[i]];
          for (uint32_t j = ws.whole_first[i]; j < i; ++j) {
            *out++ = entry(ws, rows[i], rows[j], i, j);
          }
        }
        ws.whole_ready = true;
      }
    }
    // The biased targets of a manifold of three or more points, fitted by one plane: -beta s_k
    // over the points' offsets in the contact plane, least squares. The rows of coplanar points
    // are dependent (three independent rows for four points), and their separations are only
    // nearly those of one plane (a carried manifold keeps its points' separations while the
    // bodies move a little), so the raw targets ask for a twist of the contact that no motion
    // makes: the system would answer with balanced impulses of any size.
    if (use_bias) {
      for (uint32_t h = 0; h < n; ++h) {
        const DirectRow& r = rows[h];
        if (r.kind != kDirectNormal || r.point != 0 || r.count < 3) continue;
        // Offsets in the plane: A's angular Jacobian is -(c_a x n + o_k); the mean of o_k is 0.
        const double* nb = &ws.jac[12 * std::size_t(h) + 6];
        const Vec3d normal(nb[0], nb[1], nb[2]);
        const Vec3d e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
        Vec3d mean = Vec3d::Zero();
        double alpha = 0;
        for (uint32_t k = h; k < h + r.count; ++k) {
          const double* a = &ws.jac[12 * std::size_t(k) + 3];
          mean += Vec3d(a[0], a[1], a[2]);
          alpha += ws.target[k];
        }
        mean /= double(r.count);
        alpha /= double(r.count);
        double m00 = 0, m01 = 0, m11 = 0, b0 = 0, b1 = 0;
        for (uint32_t k = h; k < h + r.count; ++k) {
          const double* a = &ws.jac[12 * std::size_t(k) + 3];
          const Vec3d o = Vec3d(a[0], a[1], a[2]) - mean;
          const double u0 = o.dot(e1), u1 = o.dot(e2), t = ws.target[k] - alpha;
          m00 += u0 * u0;
          m01 += u0 * u1;
          m11 += u1 * u1;
          b0 += u0 * t;
          b1 += u1 * t;
        }
        // Collinear points: the regularisation keeps the fit along their line.
        const double tiny = 1e-12 * (m00 + m11) + 1e-30;
        m00 += tiny;
        m11 += tiny;
        const double det = m00 * m11 - m01 * m01;
        const double g0 = (m11 * b0 - m01 * b1) / det, g1 = (m00 * b1 - m01 * b0) / det;
        for (uint32_t k = h; k < h + r.count; ++k) {
          const double* a = &ws.jac[12 * std::size_t(k) + 3];
          const Vec3d o = Vec3d(a[0], a[1], a[2]) - mean;
          ws.target[k] = alpha + g0 * o.dot(e1) + g1 * o.dot(e2);
        }
      }
      for (uint32_t i = 0; i < n; ++i) {
        if (rows[i].kind != kDirectNormal) continue;
        ws.in_set[i] =
            uint8_t(ws.lambda[i] > 0 ||
                    ws.target[i] - row_velocity(ws, rows[i], i, ws.velocity.data()) > open_below);
      }
    }
    // Adds each row's impulse change from its current impulse to `v` (6 a slot): the active
    // rows' lambda + delta, the fixed rows' fixed value.
    auto apply_changes = [&](std::vector<double>& v, bool active, bool fixed) {
      for (uint32_t i = 0; i < n; ++i) {
        const double change = ws.in_set[i] ? (active ? ws.delta[i] : 0.0)
                                           : (fixed ? ws.fixed[i] - ws.lambda[i] : 0.0);
        if (change == 0) continue;
        for (int s = 0; s < 2; ++s) {
          if (rows[i].slot[s] < 0) continue;
          double* out = &v[6 * std::size_t(rows[i].slot[s])];
          const double* m = &ws.mjac[12 * std::size_t(i) + 6 * s];
          for (int k = 0; k < 6; ++k) out[k] += m[k] * change;
        }
      }
    };
    auto final_of = [&](uint32_t i) {
      return ws.in_set[i] ? ws.lambda[i] + ws.delta[i] : ws.fixed[i];
    };
    bool solved = false, settled = false;
    for (int round = 0; round < kMaxRounds; ++round) {
      // The velocities with the fixed rows' impulses, and the active rows' residuals there.
      std::copy(ws.velocity.begin(), ws.velocity.end(), ws.trial.begin());
      apply_changes(ws.trial, false, true);
      ws.active.clear();
      for (uint32_t i = 0; i < n; ++i) {
        ws.delta[i] = 0;
        if (!ws.in_set[i]) continue;
        // The compliance acts on the whole impulse, lambda + delta.
        ws.rhs[i] = ws.target[i] - row_velocity(ws, rows[i], i, ws.trial.data()) -
                    kCompliance * ws.diagonal[i] * ws.lambda[i];
        ws.active.push_back(i);
      }
      if (!solve_active(ds, ws, system.row_begin, 0, slots)) break;
      solved = true;
      bool changed = false;
      for (const uint32_t i : ws.active) {
        if (rows[i].kind == kDirectNormal && ws.lambda[i] + ws.delta[i] < 0) {
          ws.in_set[i] = 0;
          ws.fixed[i] = 0;
          changed = true;
        }
      }
      if (changed) continue;
      // Friction on its cone: mu sum(lambda_n) for the tangent pair, mu max(sum lever_k
      // lambda_k, kTorsionPatch sum(lambda_n)) for the twist (as the passes bound them).
      for (uint32_t i = 0; i < n; ++i) {
        const DirectRow& r = rows[i];
        if (r.kind != kDirectTangent0) continue;
        const double mu = double(ctx.bundles[r.source].friction[r.lane]);
        double total = 0, twist = 0;
        for (uint32_t k = r.head; k < r.head + r.count; ++k) {
          total += final_of(k);
          twist += ws.lever[k] * final_of(k);
        }
        const double limit = mu * total;
        if (ws.in_set[i] && ws.in_set[i + 1]) {
          const double f0 = final_of(i), f1 = final_of(i + 1);
          const double length = std::sqrt(f0 * f0 + f1 * f1);
          if (length > limit * (1 + 1e-9) + 1e-12) {
            const double scale = length > 0 ? limit / length : 0.0;
            ws.in_set[i] = ws.in_set[i + 1] = 0;
            ws.fixed[i] = f0 * scale;
            ws.fixed[i + 1] = f1 * scale;
            changed = true;
          }
        }
        const double twist_limit = mu * std::max(twist, double(kTorsionPatch) * total);
        const double tw = final_of(i + 2);
        if (ws.in_set[i + 2] && std::abs(tw) > twist_limit * (1 + 1e-9) + 1e-12) {
          ws.in_set[i + 2] = 0;
          ws.fixed[i + 2] = std::clamp(tw, -twist_limit, twist_limit);
          changed = true;
        }
      }
      if (changed) continue;
      // Normal rows held at zero that the solution would drive into each other join the set.
      apply_changes(ws.trial, true, false);
      for (uint32_t i = 0; i < n; ++i) {
        if (ws.in_set[i] || rows[i].kind != kDirectNormal) continue;
        if (row_velocity(ws, rows[i], i, ws.trial.data()) < ws.target[i] - kVelocityTolerance) {
          ws.in_set[i] = 1;
          changed = true;
        }
      }
      if (!changed) {
        settled = true;
        break;
      }
    }
    // A set that did not settle within the rounds is not a solution: the passes' impulses
    // stand for this pass.
    if (!solved || !settled) continue;
    // Nor is one whose impulses dwarf what the bodies could need: the passes' impulses and the
    // bodies' momentum at their speed plus the push-out cap, many times over (a safeguard against
    // an ill-posed system; a resting or colliding island stays far below it).
    double scale = 0;
    for (uint32_t i = 0; i < n; ++i) scale += std::abs(ws.lambda[i]);
    for (uint32_t s = 0; s < slots; ++s) {
      const Real inv_mass = ctx.masses[ds.packets[system.packet_begin + s]].inv_mass;
      const double* v = &ws.velocity[6 * std::size_t(s)];
      const double speed = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (inv_mass > 0) scale += (speed + max_push) / double(inv_mass);
    }
    bool sane = true;
    for (uint32_t i = 0; i < n && sane; ++i) sane = std::abs(final_of(i)) <= kSaneImpulse * scale;
    // Nor one that would send a body off faster than the fastest body of the system came in plus
    // the push-out cap (and kSaneSpeedMargin for rounding and a substep of gravity): its rows hold
    // loads and push out by at most the cap, so a faster body is energy the system made (seen
    // after bodies spawned into each other: a chain of overlaps flung one box off at 12 m/s).
    // ws.trial holds the final velocities of the last, settled round. The margin is relative too
    // (kSaneSpeedShare), for bodies far past any sane speed, and a system of one body is left as
    // it is (nothing chains there): the passes hold neither (a 1e9 kg box on a 1e-9 kg one under
    // gravity 1e5, tests/physics/api_limits.cpp, went non-finite in them).
    double fastest = 0;
    for (uint32_t s = 0; s < slots; ++s) fastest = std::max(fastest, linear_speed(ws.velocity, s));
    const double fastest_out = fastest * (1 + kSaneSpeedShare) + max_push + kSaneSpeedMargin;
    for (uint32_t s = 0; s < slots && sane && slots > 1; ++s) {
      sane = linear_speed(ws.trial, s) <= fastest_out;
    }
    if (!sane) continue;
    // Apply: the final impulses (a normal one clamped at zero should the last round not have
    // settled), the velocities moved by the change.
    for (uint32_t i = 0; i < n; ++i) {
      const DirectRow& r = rows[i];
      double updated = final_of(i);
      if (r.kind == kDirectNormal) updated = std::max(updated, 0.0);
      const double impulse = updated - ws.lambda[i];
      if (impulse == 0) continue;
      for (int s = 0; s < 2; ++s) {
        if (r.slot[s] < 0) continue;
        double* v = &ws.velocity[6 * std::size_t(r.slot[s])];
        const double* m = &ws.mjac[12 * std::size_t(i) + 6 * s];
        for (int k = 0; k < 6; ++k) v[k] += m[k] * impulse;
      }
      if (r.kind == kDirectJoint) {
        joints[r.source].point_impulse[r.point] = Real(updated);
        continue;
      }
      ContactBundle& c = ctx.bundles[r.source];
      switch (r.kind) {
        case kDirectTangent0:
        case kDirectTangent1:
          c.tangent_impulse[r.kind == kDirectTangent0 ? 0 : 1][r.lane] = Real(updated);
          break;
        case kDirectTwist:
          c.twist_impulse[r.lane] = Real(updated);
          break;
        default: {
          WideContactPoint* points = ctx.rows_of(r.source);
          WideNormalRow& p = r.point == 0 ? c.first : points[r.point - 1].row;
          p.normal_impulse[r.lane] = Real(updated);
          if (!ctx.restitution.empty()) {
            Wide& most = ctx.restitution[r.source].max_normal_impulse[r.point];
            most[r.lane] = std::max(most[r.lane], Real(impulse));
          }
        }
      }
    }
    for (uint32_t s = 0; s < slots; ++s) {
      SolverBody& b = ctx.bodies[ds.packets[system.packet_begin + s]];
      for (int k = 0; k < 3; ++k) {
        b.v[k] = Real(ws.velocity[6 * s + k]);
        b.w[k] = Real(ws.velocity[6 * s + 3 + k]);
      }
    }
  }
}

}  // namespace elan::detail
