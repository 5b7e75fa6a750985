// SPDX-License-Identifier: MIT
// The memory report: every buffer the world keeps, grouped by the stage that owns it.
#include "core/world/memory_use.hpp"

#include <algorithm>
#include <functional>
#include <vector>

#include "core/base/compound.hpp"
#include "core/base/heap_bytes.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/triangle_mesh.hpp"

namespace elan::detail {

namespace {

std::size_t bounds_bytes(const BoundsColumns& b) {
  return heap_bytes(b.min_x) + heap_bytes(b.min_y) + heap_bytes(b.min_z) + heap_bytes(b.max_x) +
         heap_bytes(b.max_y) + heap_bytes(b.max_z);
}

std::size_t hull_bytes(const ConvexHull& h) {
  return sizeof(ConvexHull) + heap_bytes(h.vertices) + heap_bytes(h.faces) +
         heap_bytes(h.face_vertices) + heap_bytes(h.edges) + heap_bytes(h.edge_faces);
}

}  // namespace

MemoryUse memory_use(const WorldState& w) {
  MemoryUse m;
  for_each_column(w.bodies, [&](const auto& c) { m.bodies += heap_bytes(c); });
  m.bodies += heap_bytes(w.bodies.applied_forces) + w.bodies.trait_table.heap_bytes() +
              heap_bytes(w.slot_index) + heap_bytes(w.slot_generation) + heap_bytes(w.free_slots);

  // Shapes may share a hull (copies of one shape): count each once.
  std::vector<const ConvexHull*> hulls;
  // Meshes, heightfields and compounds likewise, and a compound's hull children with the hulls.
  std::vector<const void*> surfaces;
  m.shapes = heap_bytes(w.shapes);
  for (const Shape& s : w.shapes) {
    if (s.hull) hulls.push_back(s.hull.get());
    if (s.mesh) surfaces.push_back(s.mesh.get());
    if (s.heightfield) surfaces.push_back(s.heightfield.get());
    if (s.compound) {
      surfaces.push_back(s.compound.get());
      for (const CompoundPart& p : s.compound->parts) {
        if (p.shape.hull) hulls.push_back(p.shape.hull.get());
      }
    }
  }
  std::sort(hulls.begin(), hulls.end());
  hulls.erase(std::unique(hulls.begin(), hulls.end()), hulls.end());
  for (const ConvexHull* h : hulls) m.shapes += hull_bytes(*h);
  // Each shared surface once: the first shape holding it counts it.
  std::sort(surfaces.begin(), surfaces.end(), std::less<const void*>());
  for (const Shape& s : w.shapes) {
    const void* p = s.mesh          ? static_cast<const void*>(s.mesh.get())
                    : s.heightfield ? static_cast<const void*>(s.heightfield.get())
                                    : static_cast<const void*>(s.compound.get());
    if (!p) continue;
    const auto it = std::lower_bound(surfaces.begin(), surfaces.end(), p, std::less<const void*>());
    if (it == surfaces.end() || *it != p) continue;
    surfaces.erase(it);
    if (s.mesh) m.shapes += mesh_bytes(*s.mesh);
    if (s.heightfield) m.shapes += heightfield_bytes(*s.heightfield);
    if (s.compound) m.shapes += compound_bytes(*s.compound);
  }

  m.broadphase = bounds_bytes(w.bounds) + heap_bytes(w.broad_kind) + heap_bytes(w.is_plane) +
                 heap_bytes(w.idle) + w.all_pairs.heap_bytes() + w.sap.heap_bytes() +
                 heap_bytes(w.deep_balls) + w.deep_sieve.heap_bytes() +
                 heap_bytes(w.deep_candidates);

  m.contacts = w.contacts.heap_bytes();

  const SolverState& v = w.solver;
  m.solver = heap_bytes(v.packet_of) + heap_bytes(v.simulated) + heap_bytes(v.side) +
             heap_bytes(v.split_keys) + heap_bytes(v.packets) + heap_bytes(v.masses) +
             heap_bytes(v.candidates) + heap_bytes(v.color_input) + heap_bytes(v.order) +
             heap_bytes(v.segment_start) + heap_bytes(v.order_scratch) + heap_bytes(v.bundles) +
             heap_bytes(v.row_start) + heap_bytes(v.lane_start) + heap_bytes(v.rows) +
             heap_bytes(v.restitution) + heap_bytes(v.bundle_start) +
             heap_bytes(v.island_scratch.parent) + heap_bytes(v.island_scratch.island_sleep_time) +
             heap_bytes(v.island_scratch.island_awake) + heap_bytes(v.island_scratch.root) +
             heap_bytes(v.island_scratch.size) + v.direct.heap_bytes() + v.executor.heap_bytes() +
             heap_bytes(v.stages) + heap_bytes(v.block_flags) + heap_bytes(v.fast) +
             heap_bytes(v.impacts) + heap_bytes(v.earliest_toi);
  for (const ColorScratch& c : v.color_scratch) {
    m.solver += heap_bytes(c.bits) + heap_bytes(c.color_of) + heap_bytes(c.cursor);
  }

  const ApiState& a = w.api;
  m.api = heap_bytes(a.begin_events) + heap_bytes(a.end_events) + heap_bytes(a.pair_keep) +
          heap_bytes(a.pair_scratch) + heap_bytes(a.shape_destroyed) + heap_bytes(a.body_ids) +
          heap_bytes(a.shape_user_data) + heap_bytes(a.shape_defs) + heap_bytes(a.body_extra) +
          heap_bytes(a.sensor_overlaps) + heap_bytes(a.sensor_begin_events) +
          heap_bytes(a.sensor_end_events) + heap_bytes(a.hit_events) + w.query.tree.heap_bytes() +
          heap_bytes(w.query.planes) + heap_bytes(w.query.pending);
  // A derived definition's own arrays (meshes, heightfields: their size again).
  for (const auto& d : a.shape_defs) {
    if (!d) continue;
    m.api += sizeof(ShapeDef) + heap_bytes(d->points) + heap_bytes(d->vertices) +
             heap_bytes(d->triangles) + heap_bytes(d->heights) + heap_bytes(d->children);
  }
  m.scratch = w.scratch.heap_bytes();
  return m;
}

}  // namespace elan::detail
