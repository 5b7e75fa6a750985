// SPDX-License-Identifier: MIT
// The solver's stages before the solve, each alone on a hand-made world: split_halves puts every
// simulated body in exactly one half and lays out the packets; load_packets copies the bodies'
// state; color_contacts groups and colours exactly the contacts that take part; build_bundles
// covers every segment. Each takes and gives back its own scratch (the bundles excepted, which
// release_bundles gives back).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

#include "solver/bundles.hpp"
#include "solver/color_contacts.hpp"
#include "solver/packets.hpp"

namespace elan::detail {
namespace solver_stages_test {

// Body 0 static; 1 .. 12 and 16 dynamic and awake, along x; 13 asleep; 14 frozen; 15 kinematic.
constexpr uint32_t kBodies = 17;
constexpr uint32_t kAsleep = 13, kFrozenBody = 14, kKinematic = 15;

BodyStore make_bodies() {
  BodyStore b;
  for (uint32_t i = 0; i < kBodies; ++i) {
    b.push_back();
    b.set_position(i, Vec3(Real(i), Real(i % 3), 0));
    b.set_orientation(i, Quat(Real(0.8), Real(0.6), 0, 0));
    b.set_linear_velocity(i, Vec3(Real(i), 1, 2));
    b.set_angular_velocity(i, Vec3(0, Real(i), 0));
    const bool dynamic = i != 0 && i != kKinematic;
    b.motion[i] = uint8_t(i == 0            ? MotionType::Static
                          : i == kKinematic ? MotionType::Kinematic
                                            : MotionType::Dynamic);
    b.flags[i] = dynamic && i != kAsleep ? kAwake : 0;
    if (i == kFrozenBody) b.flags[i] |= kFrozen;
    b.inv_mass[i] = dynamic ? Real(0.5) : 0;
    b.inv_ix[i] = dynamic ? 1 : 0;
    b.inv_iy[i] = dynamic ? 2 : 0;
    b.inv_iz[i] = dynamic ? 3 : 0;
  }
  return b;
}

std::vector<uint32_t> simulated_bodies() {
  std::vector<uint32_t> s;
  for (uint32_t i = 1; i <= 12; ++i) s.push_back(i);
  s.push_back(16);
  return s;
}

ManifoldHead head(uint32_t a, uint32_t b, uint32_t points) {
  ManifoldHead h;
  h.body_a = a;
  h.body_b = b;
  h.point_count = points;
  return h;
}

// Contacts in key order: a chain through the awake bodies, each on the static ground, the
// sleeping and the frozen body on the ground, the kinematic body against body 16, and one pair
// that is not touching (no points).
struct Contacts {
  std::vector<ManifoldHead> heads;
  std::vector<ManifoldTail> tails;
};

Contacts make_contacts() {
  std::vector<ManifoldHead> h;
  for (uint32_t i = 1; i < kBodies; ++i) h.push_back(head(i, 0, 1 + i % 4));  // ground is B
  for (uint32_t i = 1; i < 12; ++i) h.push_back(head(i, i + 1, 1 + (i * 7) % 4));
  h.push_back(head(3, 9, 0));
  h.push_back(head(kKinematic, 16, 2));
  std::sort(h.begin(), h.end(),
            [](const ManifoldHead& x, const ManifoldHead& y) { return x.key() < y.key(); });
  Contacts c;
  c.heads = h;
  for (ManifoldHead& m : c.heads) {
    if (m.point_count > 1) c.tails.push_back(ManifoldTail{m.key(), {}});
  }
  return c;
}

// A contact takes part when it touches and one of its bodies is simulated (awake, dynamic and
// not frozen).
bool takes_part(const ManifoldHead& m) {
  const std::vector<uint32_t> s = simulated_bodies();
  auto simulated = [&](uint32_t i) { return std::find(s.begin(), s.end(), i) != s.end(); };
  return m.point_count > 0 && (simulated(m.body_a) || simulated(m.body_b));
}

TEST(SolverSplitHalves, EverySimulatedBodyInExactlyOneHalf) {
  const BodyStore bodies = make_bodies();
  SolverState st;
  StepScratch scratch;
  scratch.begin_phase();
  split_halves(bodies, st, scratch);
  EXPECT_EQ(scratch.held_bytes(), 0u) << "split_halves gives its scratch back";
  EXPECT_EQ(st.simulated, simulated_bodies());
  const uint32_t n = uint32_t(st.simulated.size());
  EXPECT_EQ(st.half_start[0], 1u);
  EXPECT_EQ(st.half_start[1], 1 + n / 2);
  EXPECT_EQ(st.half_start[2], 1 + n);
  ASSERT_EQ(st.packets.size(), 1 + n + 1);  // the dummy, the simulated, one kinematic
  ASSERT_EQ(st.masses.size(), st.packets.size());
  std::vector<int> owners(st.packets.size(), 0);
  for (uint32_t k = 0; k < n; ++k) {
    const uint32_t i = st.simulated[k];
    const uint32_t p = st.packet_of[i];
    const uint32_t side = st.side[k];
    ASSERT_LT(side, kHalves);
    EXPECT_GE(p, st.half_start[side]) << i;
    EXPECT_LT(p, st.half_start[side + 1]) << i;
    EXPECT_EQ(st.masses[p].body, i);
    ++owners[p];
  }
  for (uint32_t p = 1; p < st.half_start[kHalves]; ++p) EXPECT_EQ(owners[p], 1) << p;
  // Within a half, packets follow the body index.
  for (uint32_t h = 0; h < kHalves; ++h) {
    for (uint32_t p = st.half_start[h] + 1; p < st.half_start[h + 1]; ++p) {
      EXPECT_LT(st.masses[p - 1].body, st.masses[p].body);
    }
  }
  EXPECT_EQ(st.packet_of[kKinematic], st.half_start[kHalves]);
  EXPECT_EQ(st.masses[st.half_start[kHalves]].body, kKinematic);
  for (uint32_t i : {0u, kAsleep, kFrozenBody}) EXPECT_EQ(st.packet_of[i], 0u) << i;
}

TEST(SolverLoadPackets, CopiesEachPacketsBody) {
  const BodyStore bodies = make_bodies();
  SolverState st;
  StepScratch scratch;
  scratch.begin_phase();
  split_halves(bodies, st, scratch);
  load_packets(bodies, st, 1);
  for (uint32_t p = 1; p < st.packets.size(); ++p) {
    const uint32_t i = st.masses[p].body;
    EXPECT_EQ(st.packets[p].v, bodies.linear_velocity(i)) << p;
    EXPECT_EQ(st.packets[p].w, bodies.angular_velocity(i)) << p;
    EXPECT_EQ(st.packets[p].dp, Vec3::Zero());
    EXPECT_EQ(st.packets[p].dq.coeffs(), Quat::Identity().coeffs());
    const bool dynamic = bodies.is_dynamic(i);
    EXPECT_EQ(st.masses[p].inv_mass, dynamic ? Real(0.5) : Real(0)) << p;
    EXPECT_EQ(st.masses[p].gyroscopic, dynamic) << p;  // unequal principal inertias
  }
}

struct Prepared {
  BodyStore bodies = make_bodies();
  Contacts contacts = make_contacts();
  SolverState st;
  StepScratch scratch;
  ColorStats stats;
  Prepared() {
    scratch.begin_phase();
    split_halves(bodies, st, scratch);
    load_packets(bodies, st, 1);
    stats = color_contacts(bodies, contacts.heads, contacts.tails, st, scratch, 1);
  }
};

TEST(SolverColorContacts, GroupsAndColoursExactlyTheContactsThatTakePart) {
  Prepared s;
  EXPECT_EQ(s.scratch.held_bytes(), 0u) << "color_contacts gives its scratch back";
  const std::vector<ManifoldHead>& heads = s.contacts.heads;
  const SolverState& st = s.st;
  std::size_t points = 0;
  std::vector<int> seen(heads.size(), 0);
  for (const ManifoldHead& m : heads) points += m.point_count;
  EXPECT_EQ(s.stats.points, points);
  ASSERT_EQ(st.segment_start.size(), kSegments + 1);
  EXPECT_EQ(st.segment_start[kSegments], st.group_start[kGroups]);
  auto half_of = [&](uint32_t body) {
    const uint32_t p = st.packet_of[body];
    return p >= st.half_start[1] ? 1u : 0u;
  };
  auto simulated = [&](uint32_t body) {
    return st.packet_of[body] != 0 && s.bodies.is_dynamic(body);
  };
  for (uint32_t g = 0; g < kGroups; ++g) {
    EXPECT_EQ(st.segment_start[g * kSegmentsPerGroup], st.group_start[g]);
    for (uint32_t c = 0; c < kSegmentsPerGroup; ++c) {
      const uint32_t seg = g * kSegmentsPerGroup + c;
      std::set<uint32_t> used;
      for (uint32_t k = st.segment_start[seg]; k < st.segment_start[seg + 1]; ++k) {
        const uint32_t m = st.order[k];
        ++seen[m];
        const ManifoldHead& h = heads[m];
        // The group: both dynamic sides in half g, or across the cut.
        for (uint32_t body : {uint32_t(h.body_a), uint32_t(h.body_b)}) {
          if (!simulated(body)) continue;
          if (g < kHalves) {
            EXPECT_EQ(half_of(body), g) << m;
          }
          if (c < kColorCount) {
            EXPECT_TRUE(used.insert(body).second) << "colour " << c;
          }
        }
        if (g == kCutGroup) {
          EXPECT_TRUE(simulated(h.body_a) && simulated(h.body_b));
          EXPECT_NE(half_of(h.body_a), half_of(h.body_b));
        }
        // Most points first within a segment.
        if (k > st.segment_start[seg]) {
          EXPECT_GE(heads[st.order[k - 1]].point_count, h.point_count);
        }
      }
    }
  }
  for (std::size_t m = 0; m < heads.size(); ++m) {
    EXPECT_EQ(seen[m], takes_part(heads[m]) ? 1 : 0) << m;
  }
  // Each head with more than one point knows its tail.
  for (const ManifoldHead& m : heads) {
    if (m.point_count > 1) {
      EXPECT_EQ(s.contacts.tails[m.tail].key, m.key());
    }
  }
}

TEST(SolverBuildBundles, CoverEverySegmentAndGoBackWhole) {
  Prepared s;
  SolverState& st = s.st;
  const std::vector<ManifoldHead>& heads = s.contacts.heads;
  build_bundles(heads, false, st, s.scratch);
  const uint32_t bundle_count = st.bundle_start[kSegments];
  ASSERT_EQ(st.bundles.size(), bundle_count);
  EXPECT_TRUE(st.restitution.empty());
  EXPECT_GT(s.scratch.held_bytes(), 0u);
  for (uint32_t seg = 0; seg < kSegments; ++seg) {
    const uint32_t size = st.segment_start[seg + 1] - st.segment_start[seg];
    const bool overflow = seg % kSegmentsPerGroup == kColorCount;
    const uint32_t per = overflow ? 1 : uint32_t(kLanes);
    EXPECT_EQ(st.bundle_start[seg + 1] - st.bundle_start[seg], (size + per - 1) / per) << seg;
    for (uint32_t j = st.bundle_start[seg]; j < st.bundle_start[seg + 1]; ++j) {
      EXPECT_EQ(st.lane_start[j], st.segment_start[seg] + (j - st.bundle_start[seg]) * per);
      const uint32_t first_points = heads[st.order[st.lane_start[j]]].point_count;
      EXPECT_EQ(st.row_start[j + 1] - st.row_start[j], first_points - 1) << j;
    }
  }
  EXPECT_EQ(st.lane_start[bundle_count], st.segment_start[kSegments]);
  EXPECT_EQ(st.rows.size(), st.row_start[bundle_count]);
  release_bundles(st);
  EXPECT_EQ(s.scratch.held_bytes(), 0u);
}

}  // namespace solver_stages_test
}  // namespace elan::detail
