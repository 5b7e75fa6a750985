// Contact begin/end events by one merge of key-sorted lists (last step's touching pairs, this
// step's manifolds), and the pair filter.
#include "core/world/events.hpp"

#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"

namespace elan::detail {

namespace {
constexpr std::size_t kFilterGrain = 1024;

ContactBeginEvent begin_event(const WorldState& w, const Manifold& m) {
  ContactBeginEvent e;
  e.body_a = body_id_at(w, m.body_a);
  e.body_b = body_id_at(w, m.body_b);
  e.normal = m.normal;
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < m.point_count; ++k) {
    sum += m.points[k].anchor_a;
    e.normal_impulse += m.points[k].normal_impulse;
  }
  e.point = w.bodies.position(m.body_a) + sum / Real(m.point_count);
  return e;
}
}  // namespace

void filter_pairs(WorldState& w) {
  const PairFilter& filter = w.api.pair_filter;
  if (!filter) return;
  const std::size_t n = w.pairs.size();
  w.api.pair_keep.resize(n);
  // determinism: one flag per pair, then a serial compaction in pair order (rule 1).
  // threading: the caller's filter runs on worker threads (documented on PairFilter).
  for_blocks(n, kFilterGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t k = begin; k < end; ++k) {
      const uint64_t key = w.pairs[k];
      w.api.pair_keep[k] =
          filter(body_id_at(w, pair_first(key)), body_id_at(w, pair_second(key))) ? 1 : 0;
    }
  });
  std::size_t kept = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (w.api.pair_keep[k]) w.pairs[kept++] = w.pairs[k];
  }
  w.pairs.resize(kept);
}

void remember_touching(WorldState& w) {
  w.previous_touching.clear();
  for (const Manifold& m : w.contacts) {
    if (m.point_count > 0) w.previous_touching.push_back({m.body_a, m.body_b});
  }
}

void compute_contact_events(WorldState& w) {
  std::vector<ContactBeginEvent>& begins = w.api.begin_events;
  std::vector<ContactEndEvent>& ends = w.api.end_events;
  begins.clear();
  ends.clear();
  const std::vector<ContactRecord>& old_list = w.previous_touching;
  const std::vector<Manifold>& new_list = w.contacts;
  // determinism: a serial merge by key; events come out in pair-key order (rule 4).
  std::size_t i = 0, j = 0;
  while (i < old_list.size() || j < new_list.size()) {
    const bool take_old =
        j == new_list.size() || (i < old_list.size() && old_list[i].key() <= new_list[j].key());
    const bool take_new =
        i == old_list.size() || (j < new_list.size() && new_list[j].key() <= old_list[i].key());
    const bool is = take_new && new_list[j].point_count > 0;
    if (is && !take_old) begins.push_back(begin_event(w, new_list[j]));
    if (take_old && !is) {
      ends.push_back({body_id_at(w, old_list[i].body_a), body_id_at(w, old_list[i].body_b)});
    }
    if (take_old) ++i;
    if (take_new) ++j;
  }
}

}  // namespace elan::detail
