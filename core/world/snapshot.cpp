// SPDX-License-Identifier: MIT
// Snapshots and compact rollback states of a World (formats in elan/snapshot.hpp). The divergence
// finder is in divergence.cpp.
#include "elan/snapshot.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/base/body_store.hpp"
#include "core/base/compound.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/triangle_mesh.hpp"
#include "core/world/byte_io.hpp"
#include "core/world/recorder_hooks.hpp"
#include "core/world/world_access.hpp"
#include "core/world/world_state.hpp"
#include "elan/limits.hpp"

namespace elan {

using detail::BodyStore;
using detail::ByteReader;
using detail::ByteWriter;
using detail::Column;
using detail::ContactPoint;
using detail::Manifold;
using detail::ManifoldHead;
using detail::ManifoldTail;
using detail::PairCache;
using detail::Shape;
using detail::WorldState;

namespace {

constexpr uint8_t kSnapshotMagic[8] = {0x89, 'E', 'L', 'A', 'N', 'S', 'N', 'P'};
constexpr uint8_t kRollbackMagic[8] = {0x89, 'E', 'L', 'A', 'N', 'R', 'B', 'K'};
constexpr std::size_t kHeaderBytes = 16;  // magic, version, sizeof(Real)
constexpr std::size_t kPointReals = 5;    // A's anchor 3, separation, impulse; plus a u32 id
// Per non-static body in a rollback state: 20 Reals and the flags byte.
constexpr std::size_t kRollbackBodyBytes = 20 * sizeof(Real) + 1;

void begin(ByteWriter& w, const uint8_t (&magic)[8]) {
  w.bytes(magic, 8);
  w.u32(kSnapshotVersion);
  w.u32(uint32_t(sizeof(Real)));
}

void seal(std::vector<uint8_t>& out) {
  const uint64_t sum = detail::checksum_words(out);
  ByteWriter(out).u64(sum);
}

// Checks magic, version, Real size and checksum, in that order (a future version may seal
// differently, so the version is read before the checksum is trusted). Returns the payload.
std::span<const uint8_t> open(std::span<const uint8_t> bytes, const uint8_t (&magic)[8],
                              const char* field, const char* what, uint32_t oldest,
                              uint32_t* version_out = nullptr) {
  const std::size_t seen = std::min<std::size_t>(bytes.size(), 8);
  if (bytes.empty() || !std::equal(bytes.begin(), bytes.begin() + seen, magic)) {
    throw Error(field, std::string("not an elan ") + what + " (the magic bytes do not match)");
  }
  if (bytes.size() < kHeaderBytes + 8) {
    throw Error(field,
                std::string("truncated ") + what + " (" + std::to_string(bytes.size()) + " bytes)");
  }
  ByteReader header(bytes.subspan(8, 8), field);
  const uint32_t version = header.u32();
  const uint32_t real_bytes = header.u32();
  if (version < oldest || version > kSnapshotVersion) {
    throw Error(field,
                std::string("unsupported ") + what + " format version " + std::to_string(version) +
                    " (this build reads " +
                    (oldest == kSnapshotVersion ? "version " + std::to_string(kSnapshotVersion)
                                                : "versions " + std::to_string(oldest) + " to " +
                                                      std::to_string(kSnapshotVersion)) +
                    ")");
  }
  if (version_out != nullptr) *version_out = version;
  if (real_bytes != sizeof(Real)) {
    throw Error(field, std::string(what) + " saved with " + std::to_string(real_bytes * 8) +
                           "-bit Real, this build uses " + std::to_string(sizeof(Real) * 8) +
                           "-bit Real");
  }
  const std::size_t body = bytes.size() - 8;
  ByteReader tail(bytes.subspan(body), field);
  if (tail.u64() != detail::checksum_words(bytes.first(body))) {
    throw Error(field, std::string("truncated or corrupt ") + what + " (checksum mismatch)");
  }
  return bytes.subspan(kHeaderBytes, body - kHeaderBytes);
}

// --- full snapshot -------------------------------------------------------------------------

// A quaternion as w x y z.
void write_quat(ByteWriter& w, const Quat& q) {
  w.real(q.w());
  w.real(q.x());
  w.real(q.y());
  w.real(q.z());
}

Quat read_quat(ByteReader& r) {
  const Real qw = r.real(), qx = r.real(), qy = r.real(), qz = r.real();
  // Every saved rotation is a unit quaternion; anything else would spread NaN into the poses
  // derived through it (found by fuzz_snapshot: a shape frame's).
  const double n2 = double(qw) * qw + double(qx) * qx + double(qy) * qy + double(qz) * qz;
  if (!(std::abs(n2 - 1) <= 1e-3)) r.fail("a rotation is not a unit quaternion");
  return Quat(qw, qx, qy, qz);
}

void write_hull(ByteWriter& w, const detail::ConvexHull& h) {
  w.u32(uint32_t(h.vertices.size()));
  for (const Vec3& v : h.vertices) w.vec3(v);
  w.u32(uint32_t(h.faces.size()));
  for (const detail::HullFace& f : h.faces) {
    w.vec3(f.normal);
    w.real(f.offset);
    w.u32(f.first);
    w.u32(f.count);
  }
  w.u32(uint32_t(h.face_vertices.size()));
  for (uint32_t v : h.face_vertices) w.u32(v);
  w.u32(uint32_t(h.edges.size()));
  for (const auto& e : h.edges) {
    w.u32(e[0]);
    w.u32(e[1]);
  }
}

detail::ConvexHull read_hull(ByteReader& r) {
  detail::ConvexHull h;
  h.vertices.resize(r.count(3 * sizeof(Real), "hull vertex"));
  for (Vec3& v : h.vertices) v = r.vec3();
  h.faces.resize(r.count(4 * sizeof(Real) + 8, "hull face"));
  for (detail::HullFace& f : h.faces) {
    f.normal = r.vec3();
    f.offset = r.real();
    f.first = r.u32();
    f.count = r.u32();
  }
  h.face_vertices.resize(r.count(4, "hull face vertex"));
  for (uint32_t& v : h.face_vertices) {
    v = r.u32();
    if (v >= h.vertices.size()) r.fail("hull face vertex out of range");
  }
  for (const detail::HullFace& f : h.faces) {
    if (f.count < 3 || uint64_t(f.first) + f.count > h.face_vertices.size()) {
      r.fail("hull face loop out of range");
    }
  }
  h.edges.resize(r.count(8, "hull edge"));
  for (auto& e : h.edges) {
    e[0] = r.u32();
    e[1] = r.u32();
    if (e[0] >= h.vertices.size() || e[1] >= h.vertices.size()) r.fail("hull edge out of range");
  }
  if (h.vertices.size() < 4 || h.faces.size() < 4) r.fail("hull has too few vertices or faces");
  detail::compute_edge_faces(h);
  return h;
}

// A float (tree boxes, heightfield samples) by its bits.
void write_f32(ByteWriter& w, float v) {
  w.u32(std::bit_cast<uint32_t>(v));
}
float read_f32(ByteReader& r) {
  return std::bit_cast<float>(r.u32());
}

void write_tree(ByteWriter& w, const detail::Bvh& t) {
  w.u32(uint32_t(t.nodes.size()));
  for (const detail::BvhNode& n : t.nodes) {
    for (float f : n.min) write_f32(w, f);
    w.u32(n.index);
    for (float f : n.max) write_f32(w, f);
    w.u32(n.count);
  }
}

// Checks that nodes [0, node_count) are one tree laid out depth first, as the walks assume: from
// the root, every node visited is the next in the layout (`next`), none deeper than the walks'
// stacks, every node reached. children(i, push) checks node i's own fields and calls push(child)
// for its inner children, the last first, so that the first is visited next.
template <class Children>
void check_depth_first(ByteReader& r, std::size_t node_count, Children&& children) {
  std::vector<std::pair<uint32_t, int>> stack{{0u, 0}};
  std::size_t next = 0;
  while (!stack.empty()) {
    const auto [i, depth] = stack.back();
    stack.pop_back();
    if (i != next || i >= node_count || depth > detail::kBvhMaxDepth) {
      r.fail("tree is not a depth-first tree");
    }
    ++next;
    children(i, [&stack, below = depth + 1](uint32_t child) { stack.emplace_back(child, below); });
  }
  if (next != node_count) r.fail("tree has unreachable nodes");
}

// Reads a tree over `items` items and checks it is one: depth first (an inner node's first child
// next, its second where the first's subtree ends), every node reached once, no deeper than the
// walks' stacks, leaves within the items. A damaged tree is refused, so a walk cannot loop, run
// past its stack or index past the items.
detail::Bvh read_tree(ByteReader& r, std::size_t items) {
  detail::Bvh t;
  t.nodes.resize(r.count(32, "tree node"));
  for (detail::BvhNode& n : t.nodes) {
    for (float& f : n.min) f = read_f32(r);
    n.index = r.u32();
    for (float& f : n.max) f = read_f32(r);
    n.count = r.u32();
  }
  if (t.nodes.empty()) return t;
  check_depth_first(r, t.nodes.size(), [&](uint32_t i, const auto& push) {
    const detail::BvhNode& n = t.nodes[i];
    if (n.leaf()) {
      if (uint64_t(n.index) + n.count > items) r.fail("tree leaf out of range");
      return;
    }
    if (n.index <= i + 1 || n.index >= t.nodes.size()) r.fail("tree child out of range");
    push(n.index);
    push(i + 1);
  });
  return t;
}

// A mesh's 4-wide tree (version 11 on): per node, the four children's boxes axis by axis (min,
// then max), their indices, their counts.
void write_tree4(ByteWriter& w, const detail::Bvh4& t) {
  w.u32(uint32_t(t.nodes.size()));
  for (const detail::Bvh4Node& n : t.nodes) {
    for (const auto& axis : n.min) {
      for (float f : axis) write_f32(w, f);
    }
    for (const auto& axis : n.max) {
      for (float f : axis) write_f32(w, f);
    }
    for (uint32_t v : n.index) w.u32(v);
    for (uint32_t v : n.count) w.u32(v);
  }
}

// Reads a 4-wide tree over `items` items and checks it is one, as read_tree does: depth first
// (a node's inner children follow it in order, each with its subtree), every node reached once,
// no deeper than the walks' stacks, every node with a child, leaves within the items.
detail::Bvh4 read_tree4(ByteReader& r, std::size_t items) {
  detail::Bvh4 t;
  t.nodes.resize(r.count(128, "tree node"));
  for (detail::Bvh4Node& n : t.nodes) {
    for (auto& axis : n.min) {
      for (float& f : axis) f = read_f32(r);
    }
    for (auto& axis : n.max) {
      for (float& f : axis) f = read_f32(r);
    }
    for (uint32_t& v : n.index) v = r.u32();
    for (uint32_t& v : n.count) v = r.u32();
  }
  if (t.nodes.empty()) return t;
  check_depth_first(r, t.nodes.size(), [&](uint32_t i, const auto& push) {
    const detail::Bvh4Node& n = t.nodes[i];
    bool any = false;
    for (int k = 3; k >= 0; --k) {
      const uint32_t count = n.count[k];
      if (count == detail::kBvh4Empty) continue;
      any = true;
      if (count != 0) {
        if (uint64_t(n.index[k]) + count > items) r.fail("tree leaf out of range");
        continue;
      }
      if (n.index[k] <= i || n.index[k] >= t.nodes.size()) r.fail("tree child out of range");
      push(n.index[k]);
    }
    if (!any) r.fail("tree node has no children");
  });
  return t;
}

void write_shape(ByteWriter& w, const Shape& s);
Shape read_shape(ByteReader& r, bool in_compound, uint32_t version);

void write_mesh(ByteWriter& w, const detail::TriangleMesh& m) {
  w.u32(uint32_t(m.vertices.size()));
  for (const Vec3& v : m.vertices) w.vec3(v);
  w.u32(uint32_t(m.triangles.size()));
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (uint32_t v : m.triangles[t]) w.u32(v);
    w.u8(m.active_edges[t]);
  }
  write_tree4(w, m.tree);
  w.vec3(m.min);
  w.vec3(m.max);
}

detail::TriangleMesh read_mesh(ByteReader& r, uint32_t version) {
  detail::TriangleMesh m;
  m.vertices.resize(r.count(3 * sizeof(Real), "mesh vertex"));
  for (Vec3& v : m.vertices) v = r.vec3();
  const uint32_t nt = r.count(13, "mesh triangle");
  m.triangles.resize(nt);
  m.active_edges.resize(nt);
  for (uint32_t t = 0; t < nt; ++t) {
    for (uint32_t& v : m.triangles[t]) {
      v = r.u32();
      if (v >= m.vertices.size()) r.fail("mesh triangle vertex out of range");
    }
    m.active_edges[t] = r.u8();
    if (m.active_edges[t] > 7) r.fail("mesh triangle edge flags out of range");
  }
  if (nt == 0) r.fail("mesh has no triangles");
  // Versions 9 and 10 carry the binary tree, which the 4-wide one is made from at build: the
  // same collapse gives the tree the mesh had, so the world steps as it would have.
  m.tree = version >= 11 ? read_tree4(r, nt) : detail::collapse_to_bvh4(read_tree(r, nt));
  if (m.tree.nodes.empty()) r.fail("mesh has no tree");
  m.min = r.vec3();
  m.max = r.vec3();
  return m;
}

void write_heightfield(ByteWriter& w, const detail::HeightField& f) {
  w.u32(f.columns);
  w.u32(f.rows);
  w.real(f.spacing_x);
  w.real(f.spacing_z);
  w.real(f.min_height);
  w.real(f.max_height);
  w.u32(uint32_t(f.heights.size()));
  for (float h : f.heights) write_f32(w, h);
}

detail::HeightField read_heightfield(ByteReader& r) {
  const uint32_t columns = r.u32(), rows = r.u32();
  const Real spacing_x = r.real(), spacing_z = r.real();
  const Real saved_min = r.real(), saved_max = r.real();
  std::vector<Real> heights(r.count(4, "heightfield sample"));
  for (Real& h : heights) h = Real(read_f32(r));
  if (columns < 2 || rows < 2 || uint64_t(columns) * rows != heights.size()) {
    r.fail("heightfield grid size does not match its samples");
  }
  // Built as the scene built it: the samples checked (finite or a hole, within range, a
  // triangle left), the edges and bounds derived, and the bounds saved must be those.
  detail::HeightField f;
  try {
    f = detail::build_heightfield(heights, columns, spacing_x, spacing_z);
  } catch (const Error& e) {
    r.fail(std::string("heightfield: ") + e.what());
  }
  if (f.min_height != saved_min || f.max_height != saved_max) {
    r.fail("heightfield bounds do not match its samples");
  }
  return f;
}

void write_compound(ByteWriter& w, const detail::Compound& c) {
  w.u32(uint32_t(c.parts.size()));
  for (std::size_t k = 0; k < c.parts.size(); ++k) {
    const detail::CompoundPart& p = c.parts[k];
    write_shape(w, p.shape);
    w.vec3(p.pose.position);
    write_quat(w, p.pose.rotation);
    w.vec3(p.box.min);
    w.vec3(p.box.max);
    w.u32(c.child_of[k]);
  }
  write_tree(w, c.tree);
}

detail::Compound read_compound(ByteReader& r, uint32_t version) {
  detail::Compound c;
  const uint32_t n = r.count(2, "compound part");
  if (n == 0) r.fail("compound has no parts");
  c.parts.resize(n);
  c.child_of.resize(n);
  std::vector<uint8_t> seen(n, 0);
  for (uint32_t k = 0; k < n; ++k) {
    detail::CompoundPart& p = c.parts[k];
    p.shape = read_shape(r, true, version);
    p.pose.position = r.vec3();
    p.pose.rotation = read_quat(r);
    p.box.min = r.vec3();
    p.box.max = r.vec3();
    c.child_of[k] = r.u32();
    if (c.child_of[k] >= n || seen[c.child_of[k]]++)
      r.fail("compound child order is not a permutation");
  }
  c.tree = read_tree(r, n);
  if (c.tree.nodes.empty() != (n < detail::kCompoundTreeMin)) {
    r.fail("compound tree does not match its part count");
  }
  detail::describe_parts(c);
  return c;
}

void write_shape(ByteWriter& w, const Shape& s) {
  w.u8(uint8_t(s.type));
  w.real(s.radius);
  w.real(s.half_height);
  w.vec3(s.half_extents);
  w.vec3(s.plane_normal);
  w.real(s.plane_offset);
  w.vec3(s.frame_position);
  write_quat(w, s.frame_rotation);
  w.real(s.volume);
  w.vec3(s.unit_inertia);
  w.vec3(s.local_min);
  w.vec3(s.local_max);
  w.real(s.bounding_radius);
  w.u8(s.hull ? 1 : 0);
  if (s.hull) write_hull(w, *s.hull);
  // The built surfaces as they are (triangles in tree order, the tree itself), not their
  // definitions: a rebuild would be slower and need not give the same bits.
  if (s.type == ShapeType::Mesh) write_mesh(w, *s.mesh);
  if (s.type == ShapeType::Heightfield) write_heightfield(w, *s.heightfield);
  if (s.type == ShapeType::Compound) write_compound(w, *s.compound);
}

// A compound's part must be convex (one level of nesting, as make_shape builds them).
Shape read_shape(ByteReader& r, bool in_compound, uint32_t version) {
  Shape s;
  const uint8_t type = r.u8();
  if (type > uint8_t(ShapeType::Compound)) r.fail("unknown shape type " + std::to_string(type));
  if (in_compound && type > uint8_t(ShapeType::ConvexHull)) r.fail("compound part is not convex");
  s.type = ShapeType(type);
  s.radius = r.real();
  s.half_height = r.real();
  s.half_extents = r.vec3();
  s.plane_normal = r.vec3();
  s.plane_offset = r.real();
  s.frame_position = r.vec3();
  s.frame_rotation = read_quat(r);
  s.volume = r.real();
  s.unit_inertia = r.vec3();
  s.local_min = r.vec3();
  s.local_max = r.vec3();
  s.bounding_radius = r.real();
  // Every size and frame finite, every size not negative: a body's reported pose is derived
  // through the frame, and the step through the sizes (found by fuzz_snapshot: a body loaded
  // with a non-finite position).
  const bool finite = std::isfinite(s.plane_offset) && s.plane_normal.allFinite() &&
                      s.frame_position.allFinite() && s.local_min.allFinite() &&
                      s.local_max.allFinite();
  const bool sizes =
      s.radius >= 0 && s.half_height >= 0 && s.volume >= 0 && s.bounding_radius >= 0 &&
      (s.half_extents.array() >= 0).all() && (s.unit_inertia.array() >= 0).all() &&
      std::isfinite(s.radius) && std::isfinite(s.half_height) && std::isfinite(s.volume) &&
      std::isfinite(s.bounding_radius) && s.half_extents.allFinite() && s.unit_inertia.allFinite();
  // A shape's frame is within the supported positions (elan/limits.hpp), as make_shape's are.
  const bool frame = s.frame_position.cwiseAbs().maxCoeff() <= Real(limits::kMaxPosition);
  if (!finite || !sizes || !frame) {
    r.fail("shape sizes or frame are not finite and non-negative, or past the supported range");
  }
  const uint8_t has_hull = r.u8();
  if (has_hull > 1 || (has_hull == 1) != (s.type == ShapeType::ConvexHull)) {
    r.fail("hull data does not match the shape type");
  }
  if (has_hull) s.hull = std::make_shared<const detail::ConvexHull>(read_hull(r));
  if (s.type == ShapeType::Mesh) {
    s.mesh = std::make_shared<const detail::TriangleMesh>(read_mesh(r, version));
  }
  if (s.type == ShapeType::Heightfield) {
    s.heightfield = std::make_shared<const detail::HeightField>(read_heightfield(r));
  }
  if (s.type == ShapeType::Compound) {
    s.compound = std::make_shared<const detail::Compound>(read_compound(r, version));
  }
  return s;
}

template <class T>
void write_value(ByteWriter& w, T v) {
  if constexpr (std::is_same_v<T, Real>) {
    w.real(v);
  } else if constexpr (std::is_same_v<T, uint32_t>) {
    w.u32(v);
  } else {
    static_assert(std::is_same_v<T, uint8_t>);
    w.u8(v);
  }
}

template <class T>
T read_value(ByteReader& r) {
  if constexpr (std::is_same_v<T, Real>) {
    return r.real();
  } else if constexpr (std::is_same_v<T, uint32_t>) {
    return r.u32();
  } else {
    static_assert(std::is_same_v<T, uint8_t>);
    return r.u8();
  }
}

void write_point(ByteWriter& w, const ContactPoint& p) {
  w.vec3(p.anchor_a);
  w.real(p.separation);
  w.u32(p.feature_id);
  w.real(p.normal_impulse);
}

ContactPoint read_point(ByteReader& r) {
  ContactPoint p;
  p.anchor_a = r.vec3();
  p.separation = r.real();
  p.feature_id = r.u32();
  p.normal_impulse = r.real();
  return p;
}

// The manifold's friction impulses, carried to the next step like the normal impulses, and the
// poses its points were computed at if it may reuse them (they decide whether the next step
// does): `cache`, null if it keeps none.
void write_friction(ByteWriter& w, const Manifold& m, const PairCache* cache) {
  w.real(m.tangent_impulse[0]);
  w.real(m.tangent_impulse[1]);
  w.real(m.twist_impulse);
  w.u8(cache != nullptr ? 1 : 0);
  if (cache == nullptr) return;
  write_quat(w, cache->orientation_a);
  write_quat(w, cache->orientation_b);
  w.vec3(cache->relative_position);
  w.vec3(cache->exact_position);
  for (uint8_t byte : cache->exact_rotation.bytes) w.u8(byte);
}

// Reads what write_friction wrote. Returns whether the manifold has poses, then in `c`.
bool read_friction(ByteReader& r, Manifold& m, PairCache& c) {
  m.tangent_impulse[0] = r.real();
  m.tangent_impulse[1] = r.real();
  m.twist_impulse = r.real();
  const uint8_t cached = r.u8();
  if (cached > 1) r.fail("bad manifold pair cache flag");
  if (cached == 0) return false;
  c.key = m.key();
  c.orientation_a = read_quat(r);
  c.orientation_b = read_quat(r);
  c.relative_position = r.vec3();
  c.exact_position = r.vec3();
  for (uint8_t& byte : c.exact_rotation.bytes) byte = r.u8();
  if (!c.exact_rotation.valid()) r.fail("manifold exact rotation is not a packed rotation");
  return true;
}

// The sensor overlaps (version 10): u32 count, each u32 sensor, u32 visitor (dense indices).
void write_overlaps(ByteWriter& w, std::span<const detail::SensorOverlap> overlaps) {
  w.u32(uint32_t(overlaps.size()));
  for (const detail::SensorOverlap& o : overlaps) {
    w.u32(o.sensor);
    w.u32(o.visitor);
  }
}

// Checked against the bodies: indices in range, sorted and unique. (A rollback may come back to
// a body whose sensor flag changed since: the next step ends such an overlap.)
std::vector<detail::SensorOverlap> read_overlaps(ByteReader& r, const BodyStore& b) {
  std::vector<detail::SensorOverlap> list(r.count(8, "sensor overlap"));
  for (std::size_t k = 0; k < list.size(); ++k) {
    detail::SensorOverlap& o = list[k];
    o.sensor = r.u32();
    o.visitor = r.u32();
    if (o.sensor >= b.size() || o.visitor >= b.size() || o.sensor == o.visitor) {
      r.fail("sensor overlap body index out of range");
    }
    if (k > 0 && !(list[k - 1] < o)) r.fail("sensor overlaps are not sorted");
  }
  return list;
}

// Everything a snapshot holds, decoded and checked before any of it reaches a world.
// --- joints ------------------------------------------------------------------------------

void write_joints(ByteWriter& w, const detail::JointStore& js) {
  w.u32(uint32_t(js.size()));
  for (const detail::Joint& j : js.joints) {
    const JointDef& d = j.def;
    w.u8(uint8_t(d.type));
    w.u32(j.slot_a);
    w.u32(j.slot_b);
    w.u32(j.slot);
    w.vec3(d.anchor);
    w.vec3(d.anchor_b);
    w.vec3(d.axis);
    w.u8(uint8_t(d.has_anchor) | uint8_t(d.collide_connected) << 1 |
         uint8_t(d.limits.enabled) << 2 | uint8_t(d.motor.enabled) << 3 |
         uint8_t(d.spring.enabled) << 4);
    for (Real v :
         {d.limits.lower, d.limits.upper, d.motor.speed, d.motor.max_force, d.spring.frequency,
          d.spring.damping_ratio, d.spring.target, d.min_length, d.max_length, d.swing_limit,
          d.break_force, d.friction, d.constraint_hertz, d.constraint_damping_ratio}) {
      w.real(v);
    }
    w.vec3(j.anchor_a);
    w.vec3(j.anchor_b);
    write_quat(w, j.frame_a);
    write_quat(w, j.frame_b);
    w.real(j.min_length);
    w.real(j.max_length);
    w.real(j.rest_length);
    const detail::JointImpulses& im = j.impulses;
    w.vec3(im.point);
    w.vec3(im.angular);
    w.vec3(im.linear);
    w.vec3(im.friction);
    for (Real v : {im.axial, im.spring, im.motor, im.lower, im.upper, im.swing}) w.real(v);
    w.vec3(j.force);
    w.vec3(j.torque);
    w.u64(d.user_data);
  }
  w.u32(uint32_t(js.slot_index.size()));
  for (uint32_t v : js.slot_index) w.u32(v);
  for (uint32_t v : js.slot_generation) w.u32(v);
  w.u32(uint32_t(js.free_slots.size()));
  for (uint32_t v : js.free_slots) w.u32(v);
}

// Reads a joint section and checks it against the bodies' id slots: every joint names live
// bodies (or the world), not the same one twice, and the joint slots point back at the joints.
detail::JointStore read_joints(ByteReader& r, std::span<const uint32_t> body_slot_index,
                               uint32_t version) {
  detail::JointStore js;
  constexpr std::size_t kJointBytes = 14 + 64 * sizeof(Real);
  js.joints.resize(r.count(kJointBytes, "joint"));
  auto body_slot = [&](uint32_t slot, std::size_t k) {
    if (slot == detail::kWorldSlot) return;
    if (slot >= body_slot_index.size() || body_slot_index[slot] == UINT32_MAX) {
      r.fail("joint " + std::to_string(k) + ": names a body that does not exist");
    }
  };
  for (std::size_t k = 0; k < js.joints.size(); ++k) {
    detail::Joint& j = js.joints[k];
    JointDef& d = j.def;
    const uint8_t type = r.u8();
    if (type > uint8_t(JointType::Cone)) r.fail("joint " + std::to_string(k) + ": bad type");
    d.type = JointType(type);
    j.slot_a = r.u32();
    j.slot_b = r.u32();
    j.slot = r.u32();
    body_slot(j.slot_a, k);
    body_slot(j.slot_b, k);
    if (j.slot_a == detail::kWorldSlot || j.slot_a == j.slot_b) {
      r.fail("joint " + std::to_string(k) + ": bad bodies");
    }
    d.anchor = r.vec3();
    d.anchor_b = r.vec3();
    d.axis = r.vec3();
    const uint8_t flags = r.u8();
    d.has_anchor = flags & 1;
    d.collide_connected = flags & 2;
    d.limits.enabled = flags & 4;
    d.motor.enabled = flags & 8;
    d.spring.enabled = flags & 16;
    for (Real* v :
         {&d.limits.lower, &d.limits.upper, &d.motor.speed, &d.motor.max_force, &d.spring.frequency,
          &d.spring.damping_ratio, &d.spring.target, &d.min_length, &d.max_length, &d.swing_limit,
          &d.break_force, &d.friction, &d.constraint_hertz, &d.constraint_damping_ratio}) {
      *v = r.real();
    }
    j.anchor_a = r.vec3();
    j.anchor_b = r.vec3();
    j.frame_a = read_quat(r);
    j.frame_b = read_quat(r);
    j.min_length = r.real();
    j.max_length = r.real();
    j.rest_length = r.real();
    detail::JointImpulses& im = j.impulses;
    im.point = r.vec3();
    im.angular = r.vec3();
    im.linear = r.vec3();
    im.friction = r.vec3();
    for (Real* v : {&im.axial, &im.spring, &im.motor, &im.lower, &im.upper, &im.swing}) {
      *v = r.real();
    }
    j.force = r.vec3();
    j.torque = r.vec3();
    if (version >= 10) d.user_data = r.u64();
  }
  const uint32_t slots = r.count(8, "joint slot");
  js.slot_index.resize(slots);
  js.slot_generation.resize(slots);
  for (uint32_t& v : js.slot_index) v = r.u32();
  for (uint32_t& v : js.slot_generation) v = r.u32();
  js.free_slots.resize(r.count(4, "free joint slot"));
  for (uint32_t& v : js.free_slots) v = r.u32();
  std::size_t live = 0;
  for (uint32_t index : js.slot_index) {
    if (index != UINT32_MAX && index >= js.size()) r.fail("joint slot points past the joints");
    live += index != UINT32_MAX;
  }
  if (live != js.size()) r.fail("joint slots and joints disagree");
  for (std::size_t k = 0; k < js.size(); ++k) {
    const uint32_t slot = js.joints[k].slot;
    if (slot >= slots || js.slot_index[slot] != k) {
      r.fail("joint " + std::to_string(k) + ": id slot does not point back at it");
    }
  }
  for (uint32_t slot : js.free_slots) {
    if (slot >= slots || js.slot_index[slot] != UINT32_MAX) {
      r.fail("free joint list holds a live or unknown slot");
    }
  }
  return js;
}

struct Decoded {
  WorldDef def;
  uint64_t step_count = 0;
  uint32_t reported_status = 0;
  std::vector<Shape> shapes;
  std::vector<uint8_t> shape_destroyed;  // per shape: 1 once World::destroy_shape was called
  BodyStore bodies;
  std::vector<uint32_t> slot_index, slot_generation, free_slots;
  std::vector<Manifold> contacts;
  std::vector<PairCache> pair_cache;
  detail::JointStore joints;
  // Version 10: the API's values (user data per shape and per body in index order, the bodies'
  // density and given mass, the hit threshold, the sensor overlaps).
  std::vector<uint64_t> shape_user_data;
  std::vector<detail::BodyExtra> body_extra;
  Real hit_threshold = 1;
  std::vector<detail::SensorOverlap> sensor_overlaps;
};

void check_def(ByteReader& r, const WorldDef& d) {
  if (!d.gravity.allFinite()) r.fail("gravity is not finite");
  if (d.substeps < 1 || d.substeps > 64) r.fail("substeps out of range");
  if (d.iterations < 1 || d.iterations > 64) r.fail("iterations out of range");
  if (d.threads < 0 || d.threads > 1024) r.fail("threads out of range");
}

void check_bodies(ByteReader& r, const Decoded& d) {
  const BodyStore& b = d.bodies;
  const std::size_t n = b.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (b.shape[i] >= d.shapes.size()) r.fail("body " + std::to_string(i) + ": bad shape index");
    if (b.motion[i] > uint8_t(MotionType::Dynamic)) {
      r.fail("body " + std::to_string(i) + ": bad motion type");
    }
    if (b.slot[i] >= d.slot_index.size() || d.slot_index[b.slot[i]] != i) {
      r.fail("body " + std::to_string(i) + ": id slot does not point back at it");
    }
    // A loaded world holds what a running world can: every value finite (found by
    // fuzz_snapshot: nothing was checked, and a loaded world's kinetic energy was infinite), a
    // unit orientation, the mass in the supported range and the inertia at most
    // m r^2 = 1e9 kg (1e4 m)^2 = 1e17 kg m^2 (neither changes in a step). Positions and speeds
    // past the API's ranges (elan/limits.hpp) are not refused: a running world reaches them (the
    // soak test's bodies did), and its snapshot must load.
    const std::string body = "body " + std::to_string(i) + ": ";
    // At most 1e30 (m, m/s, rad/s): what the API reports is derived through a shape frame of at
    // most 1e5 m (position - R frame, v + w x frame), which then stays below the float maximum.
    const auto bounded = [](Real x) { return std::abs(x) <= Real(1e30); };
    if (!(bounded(b.px[i]) && bounded(b.py[i]) && bounded(b.pz[i]))) {
      r.fail(body + "position is not finite or past 1e30 m");
    }
    const double q2 = double(b.qw[i]) * b.qw[i] + double(b.qx[i]) * b.qx[i] +
                      double(b.qy[i]) * b.qy[i] + double(b.qz[i]) * b.qz[i];
    if (!(std::abs(q2 - 1) <= 1e-3)) r.fail(body + "orientation is not a unit quaternion");
    const auto length = [](Real x, Real y, Real z) {
      return std::sqrt(double(x) * x + double(y) * y + double(z) * z);
    };
    if (!(length(b.vx[i], b.vy[i], b.vz[i]) <= 1e30) ||
        !(length(b.wx[i], b.wy[i], b.wz[i]) <= 1e30)) {
      r.fail(body + "velocity is not finite or past 1e30");
    }
    const bool dynamic = b.motion[i] == uint8_t(MotionType::Dynamic);
    // 1/m for m in the mass range, with a float rounding's slack.
    const double inv_mass = b.inv_mass[i];
    if (dynamic ? !(inv_mass >= (1 - 1e-6) / limits::kMaxMass &&
                    inv_mass <= (1 + 1e-6) / limits::kMinMass)
                : inv_mass != 0) {
      r.fail(body + "inverse mass outside the supported range");
    }
    for (const Real inv : {b.inv_ix[i], b.inv_iy[i], b.inv_iz[i]}) {
      if (!(std::isfinite(inv) && inv >= 0 && (!dynamic || inv >= Real(1e-17)))) {
        r.fail(body + "inverse inertia outside the supported range");
      }
    }
    if (!(std::isfinite(b.sleep_time[i]) && b.sleep_time[i] >= 0)) r.fail(body + "bad sleep time");
    const uint32_t k = b.applied[i];
    if (k != detail::kNoForce && (k >= b.applied_forces.size() || b.applied_forces[k].body != i)) {
      r.fail("body " + std::to_string(i) + ": applied force slot does not point back at it");
    }
  }
  for (std::size_t k = 0; k < b.applied_forces.size(); ++k) {
    if (!(b.applied_forces[k].force.allFinite() && b.applied_forces[k].torque.allFinite())) {
      r.fail("applied force is not finite");
    }
    const uint32_t body = b.applied_forces[k].body;
    if (body >= n || b.applied[body] != k) r.fail("applied force of a body that does not hold it");
  }
  std::size_t live = 0;
  for (uint32_t index : d.slot_index) {
    if (index != UINT32_MAX && index >= n) r.fail("id slot points past the bodies");
    live += index != UINT32_MAX;
  }
  if (live != n) r.fail("id slots and bodies disagree");
  for (uint32_t slot : d.free_slots) {
    if (slot >= d.slot_index.size() || d.slot_index[slot] != UINT32_MAX) {
      r.fail("free list holds a live or unknown slot");
    }
  }
}

// Before the values go into a Manifold, whose bit-fields would cut them short.
void check_manifold(ByteReader& r, uint32_t body_a, uint32_t body_b, uint32_t point_count,
                    uint64_t key, std::size_t n, uint64_t previous_key, bool first) {
  if (body_a >= n || body_b >= n || body_a == body_b) {
    r.fail("manifold body index out of range");
  }
  if (key != detail::make_pair_key(body_a, body_b)) r.fail("manifold key does not match");
  if (!first && key <= previous_key) r.fail("manifolds are not sorted by key");
  if (point_count > detail::kMaxManifoldPoints) r.fail("manifold point count out of range");
}

Decoded decode_snapshot(std::span<const uint8_t> bytes) {
  uint32_t version = 0;
  ByteReader r(
      open(bytes, kSnapshotMagic, "snapshot", "snapshot", kOldestSnapshotVersion, &version),
      "snapshot");
  Decoded d;
  d.def.gravity = r.vec3();
  d.def.substeps = int32_t(r.u32());
  d.def.iterations = int32_t(r.u32());
  d.def.allow_sleep = r.u8() != 0;
  d.def.threads = int32_t(r.u32());
  const uint8_t broadphase = r.u8();
  if (broadphase > uint8_t(BroadphaseType::Tree)) r.fail("unknown broadphase");
  d.def.broadphase = BroadphaseType(broadphase);
  check_def(r, d.def);
  d.step_count = r.u64();
  d.reported_status = r.u32();

  d.shapes.resize(r.count(2, "shape"));
  d.shape_destroyed.resize(d.shapes.size());
  d.shape_user_data.assign(d.shapes.size(), 0);
  for (std::size_t k = 0; k < d.shapes.size(); ++k) {
    d.shapes[k] = read_shape(r, false, version);
    d.shape_destroyed[k] = r.u8();
    if (d.shape_destroyed[k] > 1) r.fail("bad shape destroyed flag");
    if (version >= 10) d.shape_user_data[k] = r.u64();
  }

  const uint32_t n = r.count(detail::BodyStore{}.bytes_per_body(), "body");
  d.bodies.reserve(n);
  for (uint32_t i = 0; i < n; ++i) d.bodies.push_back();
  detail::for_each_column(d.bodies, [&r](auto& column) {
    using T = typename std::remove_reference_t<decltype(column)>::value_type;
    for (T& v : column) v = read_value<T>(r);
  });
  d.bodies.applied_forces.resize(r.count(4 + 6 * sizeof(Real), "applied force"));
  for (detail::AppliedForce& a : d.bodies.applied_forces) {
    a.body = r.u32();
    a.force = r.vec3();
    a.torque = r.vec3();
  }
  std::vector<detail::BodyTraits> traits(r.count(4 * sizeof(Real) + 8, "body traits"));
  for (detail::BodyTraits& t : traits) {
    t.friction = r.real();
    t.restitution = r.real();
    t.linear_damping = r.real();
    t.angular_damping = r.real();
    t.category = r.u32();
    t.mask = r.u32();
    if (version >= 10) {
      t.gravity_scale = r.real();
      t.flags = r.u32();
      if (!std::isfinite(t.gravity_scale)) r.fail("body traits: gravity scale is not finite");
      if (t.flags & ~detail::kTraitSensor) r.fail("body traits: unknown flags");
    }
  }
  std::vector<uint32_t> free_traits(r.count(4, "free body traits"));
  for (uint32_t& k : free_traits) k = r.u32();
  if (!d.bodies.trait_table.restore(std::move(traits), std::move(free_traits), d.bodies.traits)) {
    r.fail("body traits: a body's entry, or the free list, does not match the table");
  }

  const uint32_t slots = r.count(8, "id slot");
  d.slot_index.resize(slots);
  d.slot_generation.resize(slots);
  for (uint32_t& v : d.slot_index) v = r.u32();
  for (uint32_t& v : d.slot_generation) v = r.u32();
  d.free_slots.resize(r.count(4, "free slot"));
  for (uint32_t& v : d.free_slots) v = r.u32();
  check_bodies(r, d);

  constexpr std::size_t kManifoldBytes =
      16 + 6 * sizeof(Real) + 2 + detail::kMaxManifoldPoints * (kPointReals * sizeof(Real) + 4);
  d.contacts.resize(r.count(kManifoldBytes, "manifold"));
  for (std::size_t k = 0; k < d.contacts.size(); ++k) {
    Manifold& m = d.contacts[k];
    const uint64_t key = r.u64();
    const uint32_t a = r.u32(), b = r.u32();
    m.normal = r.vec3();
    const uint8_t point_count = r.u8();
    check_manifold(r, a, b, point_count, key, n, k > 0 ? d.contacts[k - 1].key() : 0, k == 0);
    m.body_a = a;
    m.body_b = b;
    m.point_count = point_count;
    for (ContactPoint& p : m.points) p = read_point(r);
    PairCache c;
    if (read_friction(r, m, c)) d.pair_cache.push_back(c);
  }
  d.joints = read_joints(r, d.slot_index, version);
  d.body_extra.resize(n);
  if (version >= 10) {
    for (detail::BodyExtra& e : d.body_extra) {
      e.user_data = r.u64();
      e.density = r.real();
      e.given_mass = r.real();
      if (!(e.density > 0) || !std::isfinite(e.density) || !(e.given_mass >= 0) ||
          !std::isfinite(e.given_mass)) {
        r.fail("body density or mass out of range");
      }
    }
    d.hit_threshold = r.real();
    if (!(d.hit_threshold >= 0) || !std::isfinite(d.hit_threshold)) r.fail("bad hit threshold");
    d.sensor_overlaps = read_overlaps(r, d.bodies);
  } else {
    // Before version 10 a body kept no density: a dynamic body keeps the mass it has.
    for (std::size_t i = 0; i < n; ++i) {
      const Real inv = d.bodies.inv_mass[i];
      if (inv > 0) d.body_extra[i].given_mass = 1 / inv;
    }
  }
  if (r.remaining() != 0) r.fail("trailing bytes after the joints");
  return d;
}

// The last step's events belong to the timeline left behind; the query tree is rebuilt for the
// restored bodies. The pair filter is the caller's code, not state: the world keeps its own.
void forget_api_caches(WorldState& s) {
  s.api.begin_events.clear();
  s.api.end_events.clear();
  s.api.joint_events.clear();
  s.api.body_ids.clear();
  s.api.sensor_begin_events.clear();
  s.api.sensor_end_events.clear();
  s.api.hit_events.clear();
  s.bodies_placed = false;
  for (uint8_t f : s.bodies.flags) s.bodies_placed |= (f & detail::kPlaced) != 0;
  s.bodies_separating = false;
  for (uint8_t f : s.bodies.flags) s.bodies_separating |= (f & detail::kSeparating) != 0;
  detail::query_tree_refit_all(s);
}

// Replaces the world's state with `d`. Scratch of the step (bounds, pairs, the sweep's kept
// order, solver buffers) is rebuilt by the next step; the kept sweep order only speeds up the
// re-sort and every broadphase returns the same sorted pair list, so it need not be saved.
void commit(WorldState& s, Decoded&& d) {
  s.def.gravity = d.def.gravity;
  s.def.substeps = d.def.substeps;
  s.def.iterations = d.def.iterations;
  s.def.allow_sleep = d.def.allow_sleep;
  s.step_count = d.step_count;
  s.reported_status = d.reported_status;
  s.shapes = std::move(d.shapes);
  s.bodies = std::move(d.bodies);
  s.slot_index = std::move(d.slot_index);
  s.slot_generation = std::move(d.slot_generation);
  s.free_slots = std::move(d.free_slots);
  s.contacts.restore(d.contacts, d.pair_cache);
  s.joints = std::move(d.joints);
  ++s.joints.version;
  s.pairs.clear();
  s.sap = detail::SweepAndPrune{};
  s.all_pairs = detail::AllPairs{};
  s.stats = StepStats{};
  s.api.shape_destroyed = std::move(d.shape_destroyed);
  s.api.shape_defs.clear();
  s.api.shape_user_data = std::move(d.shape_user_data);
  s.api.body_extra.assign(s.slot_index.size(), detail::BodyExtra{});
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    s.api.body_extra[s.bodies.slot[i]] = d.body_extra[i];
  s.api.hit_threshold = d.hit_threshold;
  s.api.sensor_overlaps = std::move(d.sensor_overlaps);
  forget_api_caches(s);
}

// --- compact rollback ----------------------------------------------------------------------

uint64_t mix(uint64_t h, uint64_t w) {
  h = (h ^ w) * 0xBF58476D1CE4E5B9ull;
  return h ^ (h >> 31);
}

uint64_t layout_fingerprint(const BodyStore& b) {
  uint64_t h = 0x726F6C6C6261636Bull ^ b.size();
  for (std::size_t i = 0; i < b.size(); ++i) {
    h = mix(h, (uint64_t(b.shape[i]) << 32) | b.slot[i]);
    h = mix(h, b.motion[i]);
  }
  return h;
}

// Walks a rollback payload. With Apply false it only checks it (every count, index and key),
// so a bad buffer is refused before the world is touched; with Apply true it writes.
template <bool Apply>
void read_rollback(ByteReader& r, WorldState& s) {
  BodyStore& b = s.bodies;
  const std::size_t n = b.size();
  if (r.u32() != n) r.fail("saved from a world with a different number of bodies");
  if (r.u64() != layout_fingerprint(b)) r.fail("saved from a world with other bodies or shapes");
  const uint64_t step_count = r.u64();
  if constexpr (Apply) {
    s.step_count = step_count;
    b.drop_forces_if([](uint32_t) { return true; });
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (b.is_static(i)) continue;
    if constexpr (Apply) {
      for (Column<Real>* c : {&b.px, &b.py, &b.pz, &b.qw, &b.qx, &b.qy, &b.qz, &b.vx, &b.vy, &b.vz,
                              &b.wx, &b.wy, &b.wz}) {
        (*c)[i] = r.real();
      }
      // A body with no force and torque has no entry; a zero entry would step the same bits.
      const Vec3 force = r.vec3(), torque = r.vec3();
      if (force != Vec3::Zero() || torque != Vec3::Zero()) {
        detail::AppliedForce& a = b.applied_force(i);
        a.force = force;
        a.torque = torque;
      }
      b.sleep_time[i] = r.real();
      b.flags[i] = r.u8();
    } else {
      r.need(kRollbackBodyBytes);
      for (std::size_t k = 0; k < 20; ++k) r.real();
      r.u8();
    }
  }
  const uint32_t count = r.count(8 + 1 + 6 * sizeof(Real) + 2, "manifold");
  if constexpr (Apply) s.contacts.begin_restore(count);
  uint64_t previous_key = 0;
  for (uint32_t k = 0; k < count; ++k) {
    Manifold m;
    const uint64_t key = r.u64();
    const uint8_t swapped = r.u8();
    uint32_t a = detail::pair_first(key), b = detail::pair_second(key);
    if (swapped > 1) r.fail("bad manifold order flag");
    if (swapped) std::swap(a, b);
    m.normal = r.vec3();
    const uint8_t point_count = r.u8();
    check_manifold(r, a, b, point_count, key, n, previous_key, k == 0);
    m.body_a = a;
    m.body_b = b;
    m.point_count = point_count;
    previous_key = key;
    for (int p = 0; p < m.point_count; ++p) m.points[p] = read_point(r);
    PairCache c;
    const bool cached = read_friction(r, m, c);
    if constexpr (Apply) s.contacts.restore_manifold(k, m, cached ? &c : nullptr);
  }
  detail::JointStore joints = read_joints(r, s.slot_index, kSnapshotVersion);
  std::vector<detail::SensorOverlap> overlaps = read_overlaps(r, b);
  if (r.remaining() != 0) r.fail("trailing bytes after the sensor overlaps");
  if constexpr (Apply) {
    s.joints = std::move(joints);
    ++s.joints.version;
    s.api.sensor_overlaps = std::move(overlaps);
  }
}

}  // namespace

std::vector<uint8_t> save_snapshot(const World& world) {
  const WorldState& s = detail::state_of(world);
  std::vector<uint8_t> out;
  out.reserve(4096 + s.bodies.size() * detail::BodyStore{}.bytes_per_body() +
              s.contacts.size() * (32 + detail::kMaxManifoldPoints * 52));
  ByteWriter w(out);
  begin(w, kSnapshotMagic);
  w.vec3(s.def.gravity);
  w.u32(uint32_t(s.def.substeps));
  w.u32(uint32_t(s.def.iterations));
  w.u8(s.def.allow_sleep ? 1 : 0);
  w.u32(uint32_t(s.def.threads));
  w.u8(uint8_t(s.def.broadphase));
  w.u64(s.step_count);
  w.u32(s.reported_status);

  w.u32(uint32_t(s.shapes.size()));
  for (std::size_t k = 0; k < s.shapes.size(); ++k) {
    write_shape(w, s.shapes[k]);
    w.u8(k < s.api.shape_destroyed.size() ? s.api.shape_destroyed[k] : 0);
    w.u64(detail::shape_user_data(s, uint32_t(k)));
  }

  w.u32(uint32_t(s.bodies.size()));
  detail::for_each_column(s.bodies, [&w](const auto& column) {
    for (auto v : column) write_value(w, v);
  });
  w.u32(uint32_t(s.bodies.applied_forces.size()));
  for (const detail::AppliedForce& a : s.bodies.applied_forces) {
    w.u32(a.body);
    w.vec3(a.force);
    w.vec3(a.torque);
  }
  w.u32(uint32_t(s.bodies.trait_table.entries().size()));
  for (const detail::BodyTraits& t : s.bodies.trait_table.entries()) {
    w.real(t.friction);
    w.real(t.restitution);
    w.real(t.linear_damping);
    w.real(t.angular_damping);
    w.u32(t.category);
    w.u32(t.mask);
    w.real(t.gravity_scale);
    w.u32(t.flags);
  }
  w.u32(uint32_t(s.bodies.trait_table.free_entries().size()));
  for (uint32_t k : s.bodies.trait_table.free_entries()) w.u32(k);

  w.u32(uint32_t(s.slot_index.size()));
  for (uint32_t v : s.slot_index) w.u32(v);
  for (uint32_t v : s.slot_generation) w.u32(v);
  w.u32(uint32_t(s.free_slots.size()));
  for (uint32_t v : s.free_slots) w.u32(v);

  w.u32(uint32_t(s.contacts.size()));
  s.contacts.for_each_manifold([&](const Manifold& m, const PairCache* cache) {
    w.u64(m.key());
    w.u32(m.body_a);
    w.u32(m.body_b);
    w.vec3(m.normal);
    w.u8(uint8_t(m.point_count));
    for (const ContactPoint& p : m.points) write_point(w, p);
    write_friction(w, m, cache);
  });
  write_joints(w, s.joints);
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const detail::BodyExtra e = detail::body_extra(s, s.bodies.slot[i]);
    w.u64(e.user_data);
    w.real(e.density);
    w.real(e.given_mass);
  }
  w.real(s.api.hit_threshold);
  write_overlaps(w, s.api.sensor_overlaps);
  seal(out);
  return out;
}

void restore_snapshot(World& world, std::span<const uint8_t> bytes) {
  if (detail::state_of(world).recorder) [[unlikely]] {
    return detail::recorded(
        detail::state_of(world), detail::Call::RestoreSnapshot,
        [&] { restore_snapshot(world, bytes); }, bytes);
  }
  commit(detail::state_of(world), decode_snapshot(bytes));
}

World load_snapshot(std::span<const uint8_t> bytes) {
  Decoded d = decode_snapshot(bytes);
  World world(d.def);
  commit(detail::state_of(world), std::move(d));
  return world;
}

void save_rollback(const World& world, std::vector<uint8_t>& out) {
  const WorldState& s = detail::state_of(world);
  const BodyStore& b = s.bodies;
  out.clear();
  ByteWriter w(out);
  begin(w, kRollbackMagic);
  w.u32(uint32_t(b.size()));
  w.u64(layout_fingerprint(b));
  w.u64(s.step_count);
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.is_static(i)) continue;
    for (const Column<Real>* c : {&b.px, &b.py, &b.pz, &b.qw, &b.qx, &b.qy, &b.qz, &b.vx, &b.vy,
                                  &b.vz, &b.wx, &b.wy, &b.wz}) {
      w.real((*c)[i]);
    }
    w.vec3(b.force(i));
    w.vec3(b.torque(i));
    w.real(b.sleep_time[i]);
    w.u8(b.flags[i]);
  }
  w.u32(uint32_t(s.contacts.size()));
  s.contacts.for_each_manifold([&](const Manifold& m, const PairCache* cache) {
    w.u64(m.key());
    w.u8(m.body_a > m.body_b ? 1 : 0);
    w.vec3(m.normal);
    w.u8(uint8_t(m.point_count));
    for (int p = 0; p < m.point_count; ++p) write_point(w, m.points[p]);
    write_friction(w, m, cache);
  });
  write_joints(w, s.joints);
  write_overlaps(w, s.api.sensor_overlaps);
  seal(out);
}

std::vector<uint8_t> save_rollback(const World& world) {
  std::vector<uint8_t> out;
  save_rollback(world, out);
  return out;
}

void restore_rollback(World& world, std::span<const uint8_t> bytes) {
  if (detail::state_of(world).recorder) [[unlikely]] {
    return detail::recorded(
        detail::state_of(world), detail::Call::RestoreRollback,
        [&] { restore_rollback(world, bytes); }, bytes);
  }
  const std::span<const uint8_t> payload =
      open(bytes, kRollbackMagic, "rollback", "rollback state", kSnapshotVersion);
  WorldState& s = detail::state_of(world);
  ByteReader check(payload, "rollback");
  read_rollback<false>(check, s);
  ByteReader apply(payload, "rollback");
  read_rollback<true>(apply, s);
  forget_api_caches(s);
}

}  // namespace elan
