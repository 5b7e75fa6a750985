// SPDX-License-Identifier: MIT
#include "elan/run_summary.hpp"

#include <tbb/global_control.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace elan {
namespace {

// Its own name: the scene reader's `Json` (unordered) meets this file in a unity build.
using SummaryJson = nlohmann::ordered_json;

std::string hex(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
  return buf;
}

SummaryJson vec(const Vec3& v) {
  return SummaryJson::array({double(v.x()), double(v.y()), double(v.z())});
}

}  // namespace

const char* broadphase_name(BroadphaseType type) {
  switch (type) {
    case BroadphaseType::AllPairs:
      return "all-pairs";
    case BroadphaseType::Tree:
      return "tree";
    case BroadphaseType::SweepAndPrune:
      break;
  }
  return "sap";
}

int resolve_threads(int threads) {
  // The most threads oneTBB runs at once: the machine's cores, unless a global_control lowers it.
  const int available = std::max(
      1, int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
  return threads > 0 ? std::min(threads, available) : available;
}

void RunTotals::add(const World& world, uint32_t step_status, double step_wall_seconds) {
  ++steps;
  status |= step_status;
  wall_seconds += step_wall_seconds;
  const StepProfile& p = world.last_step().profile;
  profile.bounds += p.bounds;
  profile.pairs += p.pairs;
  profile.collide += p.collide;
  profile.islands += p.islands;
  profile.split += p.split;
  profile.packets += p.packets;
  profile.color += p.color;
  profile.bundles += p.bundles;
  profile.prepare += p.prepare;
  profile.solve += p.solve;
  profile.ccd += p.ccd;
  profile.finalize += p.finalize;
  profile.total += p.total;
}

std::string run_summary_json(const World& world, const std::string& scene, Real timestep,
                             const RunTotals& totals) {
  const StepStats& last = world.last_step();
  const uint64_t steps = totals.steps;
  std::size_t awake = last.awake;
  if (steps == 0) {
    awake = 0;
    for (std::size_t i = 0; i < world.body_count(); ++i) {
      const BodyId id = world.body_at(i);
      awake += world.motion_type(id) == MotionType::Dynamic && world.is_awake(id);
    }
  }
  const StepProfile& total = totals.profile;
  SummaryJson out;
  out["scene"] = scene;
  out["bodies"] = world.body_count();
  out["joints"] = world.joint_count();  // still in the world: broken ones are gone
  out["steps"] = steps;
  out["threads"] = world.settings().threads;
  out["broadphase"] = broadphase_name(world.settings().broadphase);
  out["simd"] =
      simd_path_name(world.simd_path());  // the solver path that ran (docs/determinism.md)
  out["timestep"] = double(timestep);
  out["substeps"] = world.settings().substeps;
  out["iterations"] = world.settings().iterations;
  out["wall_seconds"] = totals.wall_seconds;
  out["ms_per_step"] = steps == 0 ? 0.0 : 1000.0 * totals.wall_seconds / double(steps);
  out["state_hash"] = hex(world.state_hash());
  out["kinetic_energy"] = double(world.kinetic_energy());
  out["linear_momentum"] = vec(world.linear_momentum());
  out["angular_momentum"] = vec(world.angular_momentum());
  out["pairs"] = steps == 0 ? 0 : last.pairs;
  out["manifolds"] = steps == 0 ? 0 : last.manifolds;
  out["contacts"] = steps == 0 ? 0 : last.contacts;
  out["awake"] = awake;
  out["colors"] = steps == 0 ? 0 : last.colors;
  out["overflow"] = steps == 0 ? 0 : last.overflow;
  out["status"] = totals.status;
  out["profile_ms"] = {
      {"bounds", total.bounds},   {"pairs", total.pairs},     {"collide", total.collide},
      {"islands", total.islands}, {"split", total.split},     {"packets", total.packets},
      {"color", total.color},     {"bundles", total.bundles}, {"prepare", total.prepare},
      {"solve", total.solve},     {"ccd", total.ccd},         {"finalize", total.finalize},
      {"total", total.total}};
  // A path or body name need not be valid UTF-8 (a file name may be any bytes): such bytes are
  // printed as U+FFFD, where nlohmann's default would throw after the whole run.
  return out.dump(-1, ' ', false, SummaryJson::error_handler_t::replace);
}

}  // namespace elan
