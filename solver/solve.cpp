// The solver stages: packets, colouring, preparation, substeps, restitution and write-back.
#include "solver/solve.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/base/parallel.hpp"
#include "elan/profile.hpp"
#include "solver/integrate.hpp"

namespace elan::detail {

namespace {

// perf: blocks of bundles small enough to balance two threads within a colour, large enough
// that claiming a block costs little next to solving it (4 bundles = 64 constraints with
// AVX-512; 2 measured the same).
constexpr uint32_t kBundleBlock = 4;
// Preparing visits every bundle once: larger blocks.
constexpr uint32_t kSweepBlock = 16;
constexpr uint32_t kBodyBlock = 128;

enum StageKind : uint32_t {
  kIntegrateVelocities,
  kWarmStart,
  kSolve,
  kIntegratePositions,
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

void prepare_solve(BodyStore& bodies, std::span<Manifold> contacts, const SolveSettings& settings,
                   SolverState& st, SolveStats& stats) {
  auto t0 = std::chrono::steady_clock::now();
  update_islands(bodies, contacts, {settings.allow_sleep, settings.time_to_sleep},
                 st.island_scratch);
  stats.islands_ms = ms_since(t0);
  t0 = std::chrono::steady_clock::now();

  // Packets: awake dynamic and all kinematic bodies, in index order (packet 0 is the dummy).
  const std::size_t n = bodies.size();
  st.packet_of.assign(n, 0);
  std::size_t count = 1;
  for (std::size_t i = 0; i < n; ++i) {
    const bool simulated =
        (bodies.is_dynamic(i) && bodies.is_awake(i) && !(bodies.flags[i] & kFrozen)) ||
        bodies.motion[i] == uint8_t(MotionType::Kinematic);
    if (simulated) st.packet_of[i] = uint32_t(count++);
  }
  st.packets.resize(count);
  st.params.resize(count);
  st.masses.resize(count);
  st.packets[0] = SolverBody{};
  st.params[0] = SolverBodyParams{};
  st.masses[0] = SolverBodyMass{};
  stats.awake = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t p = st.packet_of[i];
    if (p == 0) continue;
    SolverBodyParams& prm = st.params[p];
    prm.body = uint32_t(i);
    if (bodies.is_dynamic(i)) ++stats.awake;
  }
  for_blocks(count - 1, kBodyBlock, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t k = begin + 1; k < end + 1; ++k) {
      SolverBodyParams& prm = st.params[k];
      const uint32_t i = prm.body;
      SolverBody& b = st.packets[k];
      b.v = bodies.linear_velocity(i);
      b.w = bodies.angular_velocity(i);
      b.dp.setZero();
      b.dtheta.setZero();
      b.dq = Quat::Identity();
      const bool dynamic = bodies.is_dynamic(i);
      SolverBodyMass& mass = st.masses[k];
      mass.inv_mass = dynamic ? bodies.inv_mass[i] : 0;
      const Vec3 inv_i(bodies.inv_ix[i], bodies.inv_iy[i], bodies.inv_iz[i]);
      const Quat q = bodies.orientation(i);
      mass.inv_inertia = dynamic ? rotate_diagonal(q, inv_i) : SymMat3{};
      const Vec3 force(bodies.fx[i], bodies.fy[i], bodies.fz[i]);
      const Vec3 torque(bodies.tx[i], bodies.ty[i], bodies.tz[i]);
      prm.delta_v_per_s = dynamic ? Vec3(settings.gravity + mass.inv_mass * force) : Vec3::Zero();
      prm.delta_w_per_s = dynamic ? Vec3(mass.inv_inertia * torque) : Vec3::Zero();
      prm.linear_damping = bodies.linear_damping[i];
      prm.angular_damping = bodies.angular_damping[i];
      prm.inertia = inv_i.cwiseInverse();
      // Bodies with equal principal moments (spheres, cubes) have no gyroscopic term.
      prm.gyroscopic = dynamic && !(inv_i.x() == inv_i.y() && inv_i.y() == inv_i.z());
    }
  });

  // Candidates: touching contacts with at least one simulated dynamic body.
  st.candidates.clear();
  st.color_input.clear();
  for (std::size_t m = 0; m < contacts.size(); ++m) {
    const Manifold& mf = contacts[m];
    if (mf.point_count == 0) continue;
    const uint32_t pa = st.packet_of[mf.body_a], pb = st.packet_of[mf.body_b];
    const bool da = pa != 0 && bodies.is_dynamic(mf.body_a);
    const bool db = pb != 0 && bodies.is_dynamic(mf.body_b);
    if (!da && !db) continue;
    st.candidates.push_back(uint32_t(m));
    st.color_input.push_back({pa, pb, da, db});
  }
  build_colors(st.color_input, count, st.color_scratch, st.order, st.color_start);
  stats.colors = 0;
  for (uint32_t c = 0; c < kColorCount; ++c) {
    if (st.color_start[c + 1] > st.color_start[c]) ++stats.colors;
  }
  stats.overflow = st.color_start[kColorCount + 1] - st.color_start[kColorCount];

  // perf: within a colour the order is free (its constraints share no dynamic body, so any order
  // gives the same bits). Grouped by point count, manifolds of one or two points (spheres,
  // capsules) share bundles, which then skip the empty point rows that a single four-point lane
  // would make the whole bundle read: on pile10k, 1.4 points per manifold on average. The
  // grouping is done within each of kOrderChunks consecutive parts of the colour, which keep the
  // key order between them: the solver's participants start at fixed fractions of every colour,
  // so each then solves about the same range of bodies in every colour and their packets stay
  // in its cache instead of moving between cores.
  constexpr uint32_t kOrderChunks = 8;
  st.order_scratch.resize(st.order.size());
  for_blocks(kColorCount * kOrderChunks, 1, [&](std::size_t task, std::size_t, std::size_t) {
    const uint32_t c = uint32_t(task / kOrderChunks), q = uint32_t(task % kOrderChunks);
    const uint32_t size = st.color_start[c + 1] - st.color_start[c];
    const uint32_t first = st.color_start[c] + uint32_t(uint64_t(size) * q / kOrderChunks);
    const uint32_t last = st.color_start[c] + uint32_t(uint64_t(size) * (q + 1) / kOrderChunks);
    uint32_t start[kMaxManifoldPoints + 1] = {};
    for (uint32_t k = first; k < last; ++k) {
      ++start[kMaxManifoldPoints - contacts[st.candidates[st.order[k]]].point_count];
    }
    uint32_t running = first;
    for (uint32_t& s : start) {
      const uint32_t n = s;
      s = running;
      running += n;
    }
    for (uint32_t k = first; k < last; ++k) {
      const uint32_t i = st.order[k];
      st.order_scratch[start[kMaxManifoldPoints - contacts[st.candidates[i]].point_count]++] = i;
    }
    std::copy(st.order_scratch.begin() + first, st.order_scratch.begin() + last,
              st.order.begin() + first);
  });

  // Bundles: each colour's constraints kLanes at a time in colour order; the overflow one per
  // bundle (its constraints may share bodies, so they cannot be lanes of one bundle).
  st.bundle_start.assign(kColorCount + 2, 0);
  for (uint32_t c = 0; c <= kColorCount; ++c) {
    const uint32_t n = st.color_start[c + 1] - st.color_start[c];
    const uint32_t bundles = c == kColorCount ? n : uint32_t(block_count(n, kLanes));
    st.bundle_start[c + 1] = st.bundle_start[c] + bundles;
  }
  // Calls f(j, first, last) for every bundle j in parallel blocks, where [first, last) of
  // `order` are its lanes' constraints.
  const std::size_t bundle_count = st.bundle_start[kColorCount + 1];
  auto for_each_bundle = [&](const auto& f) {
    for_blocks(bundle_count, kSweepBlock, [&](std::size_t begin, std::size_t end, std::size_t) {
      uint32_t color = 0;
      for (std::size_t j = begin; j < end; ++j) {
        while (st.bundle_start[color + 1] <= j) ++color;
        const uint32_t per_bundle = color == kColorCount ? 1 : kLanes;
        const uint32_t first =
            st.color_start[color] + (uint32_t(j) - st.bundle_start[color]) * per_bundle;
        f(j, first, std::min(st.color_start[color + 1], first + per_bundle));
      }
    });
  };
  // Each bundle gets as many point rows as its lanes' largest point count.
  st.row_start.resize(bundle_count + 1);
  st.row_start[0] = 0;
  for_each_bundle([&](std::size_t j, uint32_t first, uint32_t last) {
    int rows = 0;
    for (uint32_t k = first; k < last; ++k) {
      rows = std::max(rows, contacts[st.candidates[st.order[k]]].point_count);
    }
    st.row_start[j + 1] = uint32_t(rows);
  });
  for (std::size_t j = 0; j < bundle_count; ++j) st.row_start[j + 1] += st.row_start[j];
  // Rebuilt every step, these keep their capacity for good: growing by a quarter, not doubling,
  // leaves less of it unused (pile10k: the solver's part 1300 -> 976 B/body).
  auto grow = [](auto& v, std::size_t n) {
    if (n > v.capacity()) v.reserve(n + n / 4);
    v.resize(n);
  };
  grow(st.bundles, bundle_count);
  grow(st.rows, st.row_start[bundle_count]);
  grow(st.restitution, bundle_count);
  const ContactSolverContext ctx = make_context(settings, st);
  for_each_bundle([&](std::size_t j, uint32_t first, uint32_t last) {
    ContactBundle& bundle = st.bundles[j];
    bundle.first_row = st.row_start[j];
    bundle.max_count = int(st.row_start[j + 1] - st.row_start[j]);
    uint32_t lanes[kLanes];
    for (uint32_t k = first; k < last; ++k) lanes[k - first] = st.candidates[st.order[k]];
    prepare_bundle(ctx, bodies, contacts, st.packet_of, uint32_t(j),
                   std::span<const uint32_t>(lanes, last - first));
  });
  stats.color_ms = ms_since(t0);
}

void solve(const BodyStore& bodies, std::span<Manifold> contacts, const SolveSettings& settings,
           SolverState& st) {
  ContactSolverContext ctx = make_context(settings, st);
  const uint32_t packet_count = uint32_t(st.packets.size() - 1);
  const uint32_t body_blocks = uint32_t(block_count(packet_count, kBodyBlock));

  // The schedule: one stage per colour for each constraint pass, the overflow as one block.
  std::vector<StageSpec>& stages = st.stages;
  stages.clear();
  auto add_constraint_pass = [&](StageKind kind) {
    for (uint32_t c = 0; c < kColorCount; ++c) {
      const uint32_t n = st.bundle_start[c + 1] - st.bundle_start[c];
      if (n) stages.push_back({uint32_t(block_count(n, kBundleBlock)), kind, c});
    }
    if (st.bundle_start[kColorCount + 1] > st.bundle_start[kColorCount]) {
      stages.push_back({1, kind, kColorCount});
    }
  };
  for (int s = 0; s < settings.substeps; ++s) {
    stages.push_back({body_blocks, kIntegrateVelocities, 0});
    add_constraint_pass(kWarmStart);
    for (int it = 0; it < settings.iterations; ++it) add_constraint_pass(kSolve);
    stages.push_back({body_blocks, kIntegratePositions, 0});
    // The bodies just moved: the relax pass first refreshes each bundle's arms and separations.
    add_constraint_pass(kRelax);
  }
  // Restitution, then each bundle's impulses are final and stored.
  add_constraint_pass(kRestitution);

  const Real h = ctx.h;
  auto work = [&](const StageSpec& stage, uint32_t block) {
    if (stage.kind == kIntegrateVelocities || stage.kind == kIntegratePositions) {
      // Packets are 1..packet_count; block b covers [1 + b*kBodyBlock, ...).
      const uint32_t begin = 1 + block * kBodyBlock;
      const uint32_t end = std::min(packet_count + 1, begin + kBodyBlock);
      if (stage.kind == kIntegrateVelocities) {
        integrate_velocities(st.packets, st.params, st.masses, h, begin, end);
      } else {
        integrate_positions(st.packets, st.params, st.masses, bodies, h, begin, end);
      }
      return;
    }
    const uint32_t color_begin = st.bundle_start[stage.arg];
    const uint32_t color_end = st.bundle_start[stage.arg + 1];
    const bool overflow = stage.arg == kColorCount;
    const uint32_t begin = overflow ? color_begin : color_begin + block * kBundleBlock;
    const uint32_t end = overflow ? color_end : std::min(color_end, begin + kBundleBlock);
    switch (stage.kind) {
      case kWarmStart:
        warm_start_contacts(ctx, begin, end);
        break;
      case kSolve:
        solve_contacts(ctx, begin, end, true);
        break;
      case kRelax:
        // perf: refreshing a bundle reads only the poses, which no constraint pass changes, and
        // writes only the bundle, so it is done here, per colour, rather than as a pass of its
        // own over all bundles: one sweep of the bundles' memory and one sync fewer a substep,
        // and each participant refreshes the bundles whose bodies it is about to solve.
        refresh_contacts(ctx, bodies, contacts, begin, end);
        solve_contacts(ctx, begin, end, false);
        break;
      case kRestitution:
        apply_restitution(ctx, begin, end);
        store_impulses(ctx, begin, end, contacts);
        break;
      default:
        break;
    }
  };
  st.executor.run(stages, settings.participants, work);
}

uint32_t finalize_bodies(BodyStore& bodies, std::span<const Shape> shapes,
                         const SolveSettings& settings, SolverState& st) {
  const std::size_t count = st.packets.size() - 1;
  // determinism: indexed writes per packet; the non-finite flag is a per-block OR, combined in
  // block order below.
  std::vector<uint8_t>& frozen_any = st.block_flags;
  frozen_any.assign(block_count(count, kBodyBlock) + 1, 0);
  for_blocks(count, kBodyBlock, [&](std::size_t begin, std::size_t end, std::size_t block) {
    for (std::size_t k = begin + 1; k < end + 1; ++k) {
      const SolverBody& b = st.packets[k];
      const uint32_t i = st.params[k].body;
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
      bodies.fx[i] = bodies.fy[i] = bodies.fz[i] = 0;
      bodies.tx[i] = bodies.ty[i] = bodies.tz[i] = 0;
    }
  });
  uint32_t status = 0;
  for (uint8_t f : frozen_any) status |= f ? uint32_t(kStepFrozeNonFinite) : 0u;
  if (settings.allow_sleep) {
    update_sleep_timers(bodies, shapes, settings.dt, settings.sleep_threshold);
  }
  if (st.color_start.size() == kColorCount + 2 &&
      st.color_start[kColorCount + 1] > st.color_start[kColorCount]) {
    status |= kStepColorOverflow;
  }
  return status;
}

}  // namespace elan::detail
