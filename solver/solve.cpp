// The solver stages: packets, colouring, preparation, substeps, restitution and write-back.
#include "solver/solve.hpp"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>

#include "core/base/grow.hpp"
#include "core/base/parallel.hpp"
#include "elan/profile.hpp"
#include "solver/integrate.hpp"
#include "solver/partition.hpp"

namespace elan::detail {

namespace {

// Blocks of bodies for writing the results back.
constexpr uint32_t kBodyBlock = 128;

enum StageKind : uint32_t {
  kKinematicVelocities,
  kWarmStart,
  kSolve,
  kKinematicPositions,
  kRelax,
  kRestitution,
};

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

ContactSolverContext make_context(const SolveSettings& settings, SolverState& state) {
  ContactSolverContext ctx;
  ctx.bodies = state.packets;
  ctx.masses = state.masses;
  ctx.bundles = state.bundles;
  ctx.rows = state.rows;
  ctx.restitution = state.restitution;
  ctx.row_start = state.row_start;
  ctx.lane_manifolds = state.order;
  ctx.lane_start = state.lane_start;
  ctx.written_end = state.half_start[kHalves];
  ctx.h = settings.dt / Real(settings.substeps);
  ctx.inv_h = 1 / ctx.h;
  // Box2D v3: contact stiffness at most a quarter of the substep rate, twice as stiff against
  // static bodies (they do not give way).
  const Real hertz = std::min(settings.contact_hertz, Real(0.25) * ctx.inv_h);
  ctx.contact_softness = make_softness(hertz, settings.contact_damping_ratio, ctx.h);
  ctx.static_softness = make_softness(2 * hertz, settings.contact_damping_ratio, ctx.h);
  ctx.max_push_velocity = settings.max_push_velocity;
  ctx.restitution_threshold = settings.restitution_threshold;
  return ctx;
}

}  // namespace

void prepare_solve(BodyStore& bodies, std::span<ManifoldHead> contacts,
                   std::span<const ManifoldTail> tails, const SolveSettings& settings,
                   SolverState& st, SolveStats& stats, StepScratch& scratch) {
  auto t0 = std::chrono::steady_clock::now();
  update_islands(bodies, contacts, {settings.allow_sleep, settings.time_to_sleep},
                 st.island_scratch, scratch);
  stats.islands_ms = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  // Restitution inputs are kept only in a world that has something to bounce: on a pile of
  // inelastic bodies they were 62 B a body (pile10k) read by a pass that found nothing to do.
  const bool bouncy = bodies.trait_table.any_restitution();

  // Packets: the awake dynamic bodies of half 0, then of half 1 (partition.hpp), then every
  // kinematic body, each in index order (packet 0 is the dummy), so that each is one range of
  // packets. Kinematic bodies are apart: contacts of both halves read them, so they move in stages
  // of their own (solve()).
  const std::size_t n = bodies.size();
  st.simulated.clear();
  // Room for every body, reserved once the store has grown: push_back's doubling left up to half
  // of it unused for good (pile10k: 6.6 bytes a body for 4).
  if (st.simulated.capacity() < n) st.simulated.reserve(n);
  uint32_t kinematic = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (bodies.is_dynamic(i) && bodies.is_awake(i) && !(bodies.flags[i] & kFrozen)) {
      st.simulated.push_back(uint32_t(i));
    } else if (bodies.motion[i] == uint8_t(MotionType::Kinematic)) {
      ++kinematic;
    }
  }
  const uint32_t dynamic = uint32_t(st.simulated.size());
  const std::size_t count = 1 + std::size_t(dynamic) + kinematic;
  st.side.resize(dynamic);
  take_from(st.split_keys, scratch, dynamic);
  split_in_halves(bodies, st.simulated, st.split_keys, st.side);
  release(st.split_keys);
  const uint32_t in_half_0 = uint32_t(std::count(st.side.begin(), st.side.end(), uint8_t(0)));
  st.half_start[0] = 1;
  st.half_start[1] = 1 + in_half_0;
  st.half_start[2] = 1 + dynamic;
  st.packet_of.assign(n, 0);
  st.packets.resize(count);
  st.masses.resize(count);
  st.packets[0] = SolverBody{};
  st.masses[0] = SolverBodyMass{};
  stats.awake = dynamic;
  uint32_t next_packet[kHalves] = {st.half_start[0], st.half_start[1]};
  for (uint32_t k = 0; k < dynamic; ++k) {
    const uint32_t i = st.simulated[k];
    const uint32_t p = next_packet[st.side[k]]++;
    st.packet_of[i] = p;
    st.masses[p].body = i;
  }
  for (uint32_t i = 0, p = st.half_start[kHalves]; kinematic > 0 && i < n; ++i) {
    if (bodies.motion[i] != uint8_t(MotionType::Kinematic)) continue;
    st.packet_of[i] = p;
    st.masses[p++].body = i;
  }
  // The packets' step constants: velocities, world inverse inertias.
  auto fill_packets = [&](uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k) {
      SolverBodyMass& mass = st.masses[k];
      const uint32_t i = mass.body;
      SolverBody& b = st.packets[k];
      b.v = bodies.linear_velocity(i);
      b.w = bodies.angular_velocity(i);
      b.dp.setZero();
      b.dtheta.setZero();
      b.dq = Quat::Identity();
      const bool dynamic = bodies.is_dynamic(i);
      mass.inv_mass = dynamic ? bodies.inv_mass[i] : 0;
      const Vec3 inv_i(bodies.inv_ix[i], bodies.inv_iy[i], bodies.inv_iz[i]);
      const Quat q = bodies.orientation(i);
      mass.inv_inertia = dynamic ? rotate_diagonal(q, inv_i) : SymMat3{};
      mass.gyroscopic = dynamic && !(inv_i.x() == inv_i.y() && inv_i.y() == inv_i.z());
    }
  };

  // Candidates: touching contacts with at least one simulated dynamic body, group by group (a
  // half's own, then the cut's), in key order within each. A half's colouring sees its packets
  // from the half's first, so its bitsets cover that half only.
  auto half_of = [&](uint32_t packet) { return packet >= st.half_start[1] ? 1u : 0u; };
  auto group_of = [&](const ManifoldHead& mf, ColorInput& in) {
    const uint32_t pa = st.packet_of[mf.body_a], pb = st.packet_of[mf.body_b];
    in = {pa, pb, pa != 0 && bodies.is_dynamic(mf.body_a), pb != 0 && bodies.is_dynamic(mf.body_b)};
    if (mf.point_count == 0 || !(in.dynamic_a || in.dynamic_b)) return kGroups;
    if (in.dynamic_a && in.dynamic_b && half_of(pa) != half_of(pb)) return kCutGroup;
    return half_of(in.dynamic_a ? pa : pb);
  };
  uint32_t group_size[kGroups + 1] = {};
  std::size_t points = 0;
  uint32_t next_tail = 0;
  for (ManifoldHead& mf : contacts) {
    ColorInput in;
    ++group_size[group_of(mf, in)];
    points += mf.point_count;
    if (mf.point_count > 1) {
      assert(next_tail < tails.size() && tails[next_tail].key == mf.key() && "its tail is next");
      mf.tail = next_tail++;
    }
  }
  assert(next_tail == tails.size() && "every tail has its head");
  stats.points = points;
  st.group_start[0] = 0;
  for (uint32_t g = 0; g < kGroups; ++g) st.group_start[g + 1] = st.group_start[g] + group_size[g];
  const uint32_t candidate_count = st.group_start[kGroups];
  take_from(st.candidates, scratch, candidate_count);
  take_from(st.color_input, scratch, candidate_count);
  uint32_t cursor[kGroups + 1] = {st.group_start[0], st.group_start[1], st.group_start[2], 0};
  for (std::size_t m = 0; m < contacts.size(); ++m) {
    ColorInput in;
    const uint32_t g = group_of(contacts[m], in);
    if (g == kGroups) continue;
    if (g < kHalves) {
      in.packet_a = in.dynamic_a ? in.packet_a - st.half_start[g] : 0;
      in.packet_b = in.dynamic_b ? in.packet_b - st.half_start[g] : 0;
    }
    st.candidates[cursor[g]] = uint32_t(m);
    st.color_input[cursor[g]++] = in;
  }
  grow_to(st.order, candidate_count);
  take_from(st.order_scratch, scratch, candidate_count);
  // The colourings' arrays with their room, taken here in a fixed order so that they go back
  // last taken first (lay_out_bundles), whichever thread colours which group.
  for (uint32_t g = 0; g < kGroups; ++g) {
    const std::size_t packets = g < kHalves ? st.half_start[g + 1] - st.half_start[g] : count;
    ColorScratch& c = st.color_scratch[g];
    take_room(c.bits, scratch, color_words(packets));
    take_room(c.color_of, scratch, st.group_start[g + 1] - st.group_start[g]);
    take_room(c.cursor, scratch, kColorCount + 1);
  }
  st.segment_start.resize(kSegments + 1);
  st.segment_start[kSegments] = candidate_count;
  st.bundle_start.resize(kSegments + 1);
  auto is_overflow = [](std::size_t segment) { return segment % kSegmentsPerGroup == kColorCount; };
  auto point_count = [&](uint32_t k) { return contacts[st.order[k]].point_count; };

  // Colours group g, then orders each of its segments by point count, most first. perf: within
  // a colour the order is free (its constraints share no dynamic body, so any order gives the
  // same bits). Grouped by point count, manifolds of one or two points (spheres, capsules) share
  // bundles, which then skip the empty point rows that a single four-point lane would make the
  // whole bundle read: on pile10k, 1.4 points per manifold on average.
  auto color_group = [&](uint32_t g) {
    const uint32_t first = st.group_start[g], size = st.group_start[g + 1] - first;
    const std::size_t packets = g < kHalves ? st.half_start[g + 1] - st.half_start[g] : count;
    uint32_t start[kColorCount + 2];
    build_colors(std::span(st.color_input).subspan(first, size), packets, st.color_scratch[g],
                 std::span(st.order).subspan(first, size), start);
    for (uint32_t k = first; k < first + size; ++k)
      st.order[k] = st.candidates[first + st.order[k]];
    for (uint32_t c = 0; c <= kColorCount; ++c) {
      st.segment_start[g * kSegmentsPerGroup + c] = first + start[c];
    }
    for (uint32_t c = 0; c <= kColorCount; ++c) {
      const uint32_t begin = first + start[c], end = first + start[c + 1];
      uint32_t at[kMaxManifoldPoints + 1] = {};
      for (uint32_t k = begin; k < end; ++k) ++at[kMaxManifoldPoints - point_count(k)];
      uint32_t running = begin;
      for (uint32_t& a : at) {
        const uint32_t n = a;
        a = running;
        running += n;
      }
      for (uint32_t k = begin; k < end; ++k) {
        st.order_scratch[at[kMaxManifoldPoints - point_count(k)]++] = st.order[k];
      }
      std::copy(st.order_scratch.begin() + begin, st.order_scratch.begin() + end,
                st.order.begin() + begin);
    }
  };

  // Bundles: each colour's constraints kLanes at a time in colour order; an overflow one per
  // bundle (its constraints may share bodies, so they cannot be lanes of one bundle). Each bundle
  // gets a point row for each point but the first of its first lane, which has the most points.
  auto lay_out_bundles = [&]() {
    // The colouring is done: its arrays go back, the last taken first, so the bundles start
    // where they did.
    for (uint32_t g = kGroups; g-- > 0;) {
      release(st.color_scratch[g].cursor);
      release(st.color_scratch[g].color_of);
      release(st.color_scratch[g].bits);
    }
    release(st.order_scratch);
    release(st.color_input);
    release(st.candidates);
    st.bundle_start[0] = 0;
    for (uint32_t s = 0; s < kSegments; ++s) {
      const uint32_t size = st.segment_start[s + 1] - st.segment_start[s];
      const uint32_t bundles = is_overflow(s) ? size : uint32_t(block_count(size, kLanes));
      st.bundle_start[s + 1] = st.bundle_start[s] + bundles;
    }
    const std::size_t bundle_count = st.bundle_start[kSegments];
    st.row_start.resize(bundle_count + 1);
    st.lane_start.resize(bundle_count + 1);
    st.row_start[0] = 0;
    for (uint32_t s = 0; s < kSegments; ++s) {
      const uint32_t per_bundle = is_overflow(s) ? 1 : kLanes;
      for (uint32_t j = st.bundle_start[s]; j < st.bundle_start[s + 1]; ++j) {
        const uint32_t first = st.segment_start[s] + (j - st.bundle_start[s]) * per_bundle;
        st.row_start[j + 1] = st.row_start[j] + uint32_t(point_count(first)) - 1;
        st.lane_start[j] = first;
      }
    }
    st.lane_start[bundle_count] = candidate_count;
    take_from(st.bundles, scratch, bundle_count);
    take_from(st.rows, scratch, st.row_start[bundle_count]);
    take_from(st.restitution, scratch, bouncy ? bundle_count : 0);
  };

  auto prepare_group = [&](uint32_t g) {
    const ContactSolverContext ctx = make_context(settings, st);
    for (uint32_t s = g * kSegmentsPerGroup; s < (g + 1) * kSegmentsPerGroup; ++s) {
      for (uint32_t j = st.bundle_start[s]; j < st.bundle_start[s + 1]; ++j) {
        const uint32_t last = st.lane_start[j + 1];
        // perf: the next bundle's manifolds, while this one is prepared. They are scattered over
        // the contact list, and at 2 threads about half were last written by the other core's
        // collide blocks: at jolt_pyramid's 2 threads the first load of a lane's manifold took
        // a quarter of prepare_bundle.
        const uint32_t next_last = j + 1 < st.bundle_start[s + 1] ? st.lane_start[j + 2] : last;
        for (uint32_t k = last; k < next_last; ++k) prefetch(contacts[st.order[k]]);
        // This bundle's tails: its heads, fetched while the last bundle was prepared, say where.
        for (uint32_t k = st.lane_start[j]; k < last; ++k) {
          const ManifoldHead& head = contacts[st.order[k]];
          if (head.point_count > 1) prefetch(tails[head.tail]);
        }
        prepare_bundle(ctx, bodies, contacts, tails, st.packet_of, j);
      }
    }
  };

  // perf: three stages of the executor, so the workers are woken once and each sync is a spin
  // (a TBB loop per part cost a wake-up each: on pile10k this stage took as long at 2 threads
  // as at 1). A half fills its packets and colours its group; one block fills the kinematic
  // packets, colours the cut and lays out the bundles (it allocates); then each group prepares
  // its bundles.
  enum : uint32_t { kHalfPackets, kCutAndLayout, kGroupBundles };
  std::vector<StageSpec>& stages = st.stages;
  stages.assign({{kHalves, kHalfPackets, 0}, {1, kCutAndLayout, 0}, {kGroups, kGroupBundles, 0}});
  st.executor.run(stages, std::min(settings.participants, int(kHalves)),
                  [&](const StageSpec& stage, uint32_t block) {
                    if (stage.kind == kHalfPackets) {
                      fill_packets(st.half_start[block], st.half_start[block + 1]);
                      color_group(block);
                    } else if (stage.kind == kCutAndLayout) {
                      fill_packets(st.half_start[kHalves], uint32_t(count));
                      color_group(kCutGroup);
                      lay_out_bundles();
                    } else {
                      prepare_group(block);
                    }
                  });

  stats.colors = 0;
  stats.overflow = 0;
  for (uint32_t g = 0; g < kGroups; ++g) {
    std::size_t used = 0;
    for (uint32_t c = 0; c < kColorCount; ++c) {
      const uint32_t s = g * kSegmentsPerGroup + c;
      if (st.segment_start[s + 1] > st.segment_start[s]) ++used;
    }
    const uint32_t s = g * kSegmentsPerGroup + kColorCount;
    stats.colors = std::max(stats.colors, used);
    stats.overflow += st.segment_start[s + 1] - st.segment_start[s];
  }
  stats.color_ms = ms_since(t0);
}

void solve(const BodyStore& bodies, std::span<ManifoldHead> contacts, std::span<ManifoldTail> tails,
           const SolveSettings& settings, SolverState& st) {
  ContactSolverContext ctx = make_context(settings, st);

  // The schedule: every pass is a stage of the two halves (block h solves half h) and then, if
  // any contact crosses the cut, a stage of one block for those (partition.hpp): two syncs a
  // pass. The halves integrate their own packets in the stage before the pass that needs it.
  std::vector<StageSpec>& stages = st.stages;
  stages.clear();
  const bool cut = st.bundle_start[kSegments] > st.bundle_start[kCutGroup * kSegmentsPerGroup];
  const uint32_t packet_count = uint32_t(st.packets.size());
  const bool kinematic = packet_count > st.half_start[kHalves];
  auto add_pass = [&](StageKind kind) {
    stages.push_back({kHalves, kind, 0});
    if (cut) stages.push_back({1, kind, kCutGroup});
  };
  // Kinematic packets are read by the contacts of both halves, so they move in a stage of one
  // block between passes, never while a pass runs.
  auto add_kinematic = [&](StageKind kind) {
    if (kinematic) stages.push_back({1, kind, 0});
  };
  for (int s = 0; s < settings.substeps; ++s) {
    add_kinematic(kKinematicVelocities);
    add_pass(kWarmStart);  // halves: integrate velocities first
    for (int it = 0; it < settings.iterations; ++it) add_pass(kSolve);
    // The bodies move; the relax pass first refreshes each bundle's arms and separations.
    add_kinematic(kKinematicPositions);
    add_pass(kRelax);  // halves: integrate positions first
  }
  // Restitution, then each bundle's impulses are final and stored.
  add_pass(kRestitution);

  const Real h = ctx.h;
  auto work = [&](const StageSpec& stage, uint32_t block) {
    if (stage.kind == kKinematicVelocities) {
      integrate_velocities(st.packets, st.masses, bodies, settings.gravity, h,
                           st.half_start[kHalves], packet_count);
      return;
    }
    if (stage.kind == kKinematicPositions) {
      integrate_positions(st.packets, st.masses, bodies, h, st.half_start[kHalves], packet_count);
      return;
    }
    const uint32_t group = stage.arg == kCutGroup ? kCutGroup : block;
    const uint32_t begin = st.bundle_start[group * kSegmentsPerGroup];
    const uint32_t end = st.bundle_start[(group + 1) * kSegmentsPerGroup];
    const bool half = group < kHalves;
    switch (stage.kind) {
      case kWarmStart:
        if (half) {
          integrate_velocities(st.packets, st.masses, bodies, settings.gravity, h,
                               st.half_start[group], st.half_start[group + 1]);
        }
        warm_start_contacts(ctx, begin, end);
        break;
      case kSolve:
        solve_contacts(ctx, begin, end, true);
        break;
      case kRelax:
        if (half) {
          integrate_positions(st.packets, st.masses, bodies, h, st.half_start[group],
                              st.half_start[group + 1]);
        }
        // perf: refreshing a bundle reads only the poses, which no constraint pass changes, and
        // writes only the bundle, so it is done in the relax pass rather than as a pass of its
        // own: one sweep of the bundles' memory and one sync fewer a substep.
        refresh_contacts(ctx, bodies, contacts, tails, begin, end);
        solve_contacts(ctx, begin, end, false);
        break;
      case kRestitution:
        apply_restitution(ctx, begin, end);
        store_impulses(ctx, begin, end, contacts, tails);
        break;
      default:
        break;
    }
  };
  st.executor.run(stages, std::min(settings.participants, int(kHalves)), work);
  release(st.bundles);
  release(st.rows);
  release(st.restitution);
}

uint32_t finalize_bodies(BodyStore& bodies, std::span<const Shape> shapes,
                         const SolveSettings& settings, SolverState& st) {
  const std::size_t n = bodies.size();
  // determinism: indexed writes per body; the non-finite flag is a per-block OR, combined in
  // block order below. perf: blocks of bodies, not of packets: the packets of a half are bodies
  // from all over the index range, so blocks of packets had both threads writing the same cache
  // lines of the body columns (pile4k at 2 threads: this stage 0.09 -> 1.56 ms).
  std::vector<uint8_t>& frozen_any = st.block_flags;
  frozen_any.assign(block_count(n, kBodyBlock) + 1, 0);
  for_blocks(n, kBodyBlock, [&](std::size_t begin, std::size_t end, std::size_t block) {
    for (std::size_t i = begin; i < end; ++i) {
      const uint32_t k = st.packet_of[i];
      if (k == 0) continue;
      const SolverBody& b = st.packets[k];
      const Vec3 p = bodies.position(i) + b.dp;
      const Quat q = (b.dq * bodies.orientation(i)).normalized();
      const bool finite =
          p.allFinite() && q.coeffs().allFinite() && b.v.allFinite() && b.w.allFinite();
      if (!finite) {
        // Quarantine: keep the last good pose, stop it, take it out of the simulation.
        bodies.set_linear_velocity(i, Vec3::Zero());
        bodies.set_angular_velocity(i, Vec3::Zero());
        bodies.flags[i] = uint8_t((bodies.flags[i] | kFrozen) & ~kAwake);
        frozen_any[block] = 1;
        continue;
      }
      bodies.set_position(i, p);
      bodies.set_orientation(i, q);
      bodies.set_linear_velocity(i, b.v);
      bodies.set_angular_velocity(i, b.w);
    }
  });
  // The forces applied for this step are spent on the bodies it moved (a quarantined one's too).
  bodies.drop_forces_if([&](uint32_t i) { return st.packet_of[i] != 0; });
  uint32_t status = 0;
  for (uint8_t f : frozen_any) status |= f ? uint32_t(kStepFrozeNonFinite) : 0u;
  if (settings.allow_sleep) {
    update_sleep_timers(bodies, shapes, settings.dt, settings.sleep_threshold);
  }
  if (st.segment_start.size() == kSegments + 1) {
    for (uint32_t g = 0; g < kGroups; ++g) {
      const uint32_t s = g * kSegmentsPerGroup + kColorCount;
      if (st.segment_start[s + 1] > st.segment_start[s]) status |= kStepColorOverflow;
    }
  }
  return status;
}

}  // namespace elan::detail
