// SPDX-License-Identifier: MIT
// ContactStore: the step's merge of the five contact lists, the separation cache's entry codes,
// restore and memory accounting.
#include "narrowphase/contact_store.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include "core/base/heap_bytes.hpp"

namespace elan::detail {

bool SeparatedPair::make(uint64_t key, const Separation& separation, const Vec3& position,
                         const Quat& rotation, Real step, SeparatedPair& out) {
  if (separation.kind == Separation::Kind::Unknown) return false;
  if (separation.kind == Separation::Kind::EdgePair) {
    if (!(separation.edge_a >= 0 && separation.edge_a <= 32767 && separation.edge_b >= 0 &&
          separation.edge_b <= 32767)) {
      return false;
    }
    out = SeparatedPair{};
    out.key = key;
    out.gap_bits = 0x80000000u;
    out.position[0] = int16_t(separation.edge_a);
    out.position[1] = int16_t(separation.edge_b);
    return true;
  }
  if (!(separation.gap > 0 && separation.gap <= std::numeric_limits<float>::max())) return false;
  if (!(step > 0 && step <= std::numeric_limits<Real>::max())) return false;
  const Vec3 steps = position / step;
  if (!(steps.cwiseAbs().maxCoeff() <= 32767)) return false;  // false for NaN too
  // The gap as a float rounded towards zero, its lowest four bits (2^-19 of it) then dropped.
  float gap = float(separation.gap);
  if (Real(gap) > separation.gap) gap = std::nextafter(gap, 0.0f);
  uint32_t bits = 0;
  std::memcpy(&bits, &gap, sizeof(bits));
  const PackedRotation packed = PackedRotation::pack(rotation);
  out.key = key;
  out.gap_bits = (bits & ~0xFu) | uint32_t(packed.bytes[6]) << 2 | uint32_t(separation.kind);
  for (int k = 0; k < 3; ++k) out.position[k] = int16_t(std::lrint(steps[k]));
  std::memcpy(out.rotation, packed.bytes, sizeof(out.rotation));
  return true;
}

Real SeparatedPair::gap() const {
  const uint32_t bits = gap_bits & ~0xFu;
  float gap = 0;
  std::memcpy(&gap, &bits, sizeof(gap));
  return Real(gap);
}

void ContactStore::begin_step(std::span<const uint64_t> pairs, std::size_t grain, std::size_t parts,
                              StepScratch* step_scratch) {
  Merge& u = merge_;
  if (step_scratch == nullptr) {
    if (!u.own) u.own = std::make_unique<StepScratch>();
    step_scratch = u.own.get();
    step_scratch->begin_phase();
  }
  u.parts = parts;
  u.step_scratch = step_scratch;
  begin_update(u.heads, heads_, pairs, grain, parts, *step_scratch);
  begin_update(u.tails, tails_, pairs, grain, parts, *step_scratch);
  begin_update(u.separated, separated_, pairs, grain, parts, *step_scratch);
  begin_update(u.apart_keys, apart_keys_, pairs, grain, parts, *step_scratch);
  begin_update(u.cache, cache_, pairs, grain, parts, *step_scratch);
}

void ContactStore::finish_step() {
  Merge& u = merge_;
  const std::size_t parts = u.parts;
  StepScratch& step_scratch = *u.step_scratch;
  ListUpdate<ManifoldHead>& mu = u.heads;
  // The manifolds' changes, before the join drops the ended ones: in part order, so in key
  // order. perf: only the parts that lost a manifold are read again.
  u.ended.clear();
  u.began.clear();
  for (std::size_t p = 0; p < parts; ++p) {
    if (mu.live[p] < mu.start[p + 1] - mu.start[p]) {
      for (std::size_t i = mu.start[p]; i < mu.start[p + 1]; ++i) {
        if (ListEntry<ManifoldHead>::ended(heads_[i])) {
          u.ended.push_back({heads_[i].body_a, heads_[i].body_b});
        }
      }
    }
    const auto& run = mu.added_run[p];
    const ScratchVector<ManifoldHead>& added = mu.added[run.thread];
    for (std::size_t i = run.first; i < run.first + run.count; ++i) {
      u.began.push_back(added[i].key());
    }
  }
  // determinism: the lists are joined apart (disjoint data), each in part order.
  // threading: five blocks of one for_blocks call (annotated for ThreadSanitizer in
  // parallel.hpp) rather than parallel_invoke, which runs its callables in place on the
  // caller's stack, where TSan sees the worker read them before any hand-off it can be told of.
  for_blocks(5, 1, [&](std::size_t, std::size_t, std::size_t list) {
    switch (list) {
      case 0:
        join(mu, heads_, parts, step_scratch);
        break;
      case 1:
        join(u.tails, tails_, parts, step_scratch);
        break;
      case 2:
        join(u.separated, separated_, parts, step_scratch);
        break;
      case 3:
        join(u.apart_keys, apart_keys_, parts, step_scratch);
        break;
      default:
        join(u.cache, cache_, parts, step_scratch);
    }
  });
  end_update(mu);
  end_update(u.tails);
  end_update(u.separated);
  end_update(u.apart_keys);
  end_update(u.cache);
  trim_spike(u.ended, u.ended_trim);
  trim_spike(u.began, u.began_trim);
  u.step_scratch = nullptr;
}

unsigned ContactStore::Block::file_apart_entries(uint64_t key, const SeparatedPair* entry,
                                                 const Apart& apart,
                                                 ScratchVector<SeparatedPair>& added_separated,
                                                 ScratchVector<uint64_t>& added_keys) {
  if (entry != nullptr) {
    if (apart.separated != nullptr) {
      *apart.separated = *entry;
    } else {
      added_separated.push_back(*entry);
    }
    if (apart.key == nullptr) return 0;
    *apart.key = kEndedKey;
    return 2;
  }
  if (apart.key == nullptr) added_keys.push_back(key);
  if (apart.separated == nullptr) return 0;
  apart.separated->end();
  return 1;
}

void ContactStore::restore(std::span<const Manifold> manifolds, std::span<const PairCache> cache,
                           std::span<const SeparatedPair> separated,
                           std::span<const uint64_t> apart_keys) {
  split_list(manifolds, heads_, tails_);
  cache_.assign(cache.begin(), cache.end());
  separated_.assign(separated.begin(), separated.end());
  apart_keys_.assign(apart_keys.begin(), apart_keys.end());
  merge_ = {};
}

void ContactStore::begin_restore(std::size_t count) {
  heads_.resize(count);
  tails_.clear();
  cache_.clear();
  clear_apart();
}

std::size_t ContactStore::step_buffer_bytes() const {
  const Merge& u = merge_;
  std::size_t bytes = 0;
  auto add = [&](const auto& buffers) {
    for (const auto& b : buffers) bytes += detail::heap_bytes(b);
  };
  add(u.heads.added);
  add(u.tails.added);
  add(u.cache.added);
  add(u.separated.added);
  add(u.apart_keys.added);
  return bytes;
}

std::size_t ContactStore::heap_bytes() const {
  const Merge& u = merge_;
  return detail::heap_bytes(heads_) + detail::heap_bytes(tails_) + detail::heap_bytes(cache_) +
         detail::heap_bytes(separated_) + detail::heap_bytes(apart_keys_) + u.heads.heap_bytes() +
         u.tails.heap_bytes() + u.separated.heap_bytes() + u.apart_keys.heap_bytes() +
         u.cache.heap_bytes() + detail::heap_bytes(u.ended) + detail::heap_bytes(u.began);
}

}  // namespace elan::detail
