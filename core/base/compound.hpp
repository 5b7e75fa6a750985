// SPDX-License-Identifier: MIT
// A compound shape: convex children, each a Shape placed in the compound's principal frame, with
// a small tree over their boxes when there are many (bepu's BigCompound).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/base/bvh.hpp"
#include "core/base/shape.hpp"

namespace elan::detail {

struct CompoundPart {
  Shape shape;     // the child's own shape (its principal frame at its centre of mass)
  Transform pose;  // the child's principal frame in the compound's principal frame
  Aabb box;        // the child's bounds in the compound's principal frame
};

// Children past this count get a tree; fewer are tested box by box.
inline constexpr std::size_t kCompoundTreeMin = 8;

struct Compound {
  std::vector<CompoundPart> parts;  // in tree order when there is a tree, else as given
  std::vector<uint32_t> child_of;   // parts[k] is the definition's child child_of[k]
  Bvh tree;                         // empty below kCompoundTreeMin children
  // Read by every pair and every step, derived once from the parts by describe_parts (perf: the
  // parts are large and far apart in memory; the collide and continuous stages asked them each
  // time).
  bool round = false;  // a part is a sphere, capsule or cylinder
  Real thinnest = 0;   // half the thinnest side of a part's box in its principal frame, m
};

// Sets the compound's derived fields from its parts; whatever builds a Compound calls it last.
void describe_parts(Compound& c);

// Calls f(k, part) for each part whose box overlaps [lo, hi] (compound principal frame), in one
// fixed order.
template <class F>
void for_each_part(const Compound& c, const Vec3& lo, const Vec3& hi, F&& f) {
  const auto visit = [&](uint32_t k) {
    const CompoundPart& p = c.parts[k];
    if ((p.box.min.array() > hi.array()).any() || (p.box.max.array() < lo.array()).any()) return;
    f(k, p);
  };
  if (c.tree.nodes.empty()) {
    for (uint32_t k = 0; k < c.parts.size(); ++k) visit(k);
    return;
  }
  bvh_query(c.tree, lo, hi, [&](uint32_t first, uint32_t count) {
    for (uint32_t k = first; k < first + count; ++k) visit(k);
  });
}

std::size_t compound_bytes(const Compound& c);

}  // namespace elan::detail
