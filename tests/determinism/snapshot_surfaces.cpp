// SPDX-License-Identifier: MIT
// Snapshots of worlds with a mesh, a heightfield and a compound: saved and loaded exactly (the
// built surfaces, trees and parts bit for bit), stepped identically after, and refused when a
// resealed file carries an index, a tree or heightfield samples that do not fit.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/base/compound.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/triangle_mesh.hpp"
#include "core/world/byte_io.hpp"
#include "core/world/world_access.hpp"
#include "elan/snapshot.hpp"

namespace elan {
namespace snapshot_surfaces_test {

constexpr Real kDt = Real(1.0 / 60.0);
// A distinctive mesh vertex coordinate: its bytes locate the mesh's triangles in the file.
constexpr Real kMarker = Real(7.125);

// A static mesh (a bumpy grid), a static heightfield and a dynamic compound of twelve children
// (so it has a tree) spinning in free flight, with a box resting on a plane beside them so the
// file carries contacts too. The bodies are kept apart: the snapshot is what is tested here.
// The bumpy grid of n x n cells, with the marker vertex last.
ShapeDef bumpy_mesh(int n) {
  ShapeDef mesh;
  mesh.type = ShapeType::Mesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      mesh.vertices.emplace_back(Real(i), Real(0.3 * std::sin(i + 2.0 * j)), Real(j));
    }
  }
  mesh.vertices.emplace_back(kMarker, kMarker, kMarker);  // unused: the marker
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i);
      mesh.triangles.push_back({a, a + uint32_t(n) + 2, a + 1});
      mesh.triangles.push_back({a, a + uint32_t(n) + 1, a + uint32_t(n) + 2});
    }
  }
  return mesh;
}

World surfaces_world(int mesh_cells) {
  World w;
  const ShapeDef mesh = bumpy_mesh(mesh_cells);
  BodyDef s;
  s.motion = MotionType::Static;
  s.shape = w.create_shape(mesh);
  s.position = Vec3(-50, 0, 0);
  w.create_body(s);

  ShapeDef field;
  field.type = ShapeType::Heightfield;
  field.columns = 6;
  for (int k = 0; k < 6 * 5; ++k) field.heights.push_back(Real(0.1 * ((k * 7) % 5)));
  field.spacing_x = 1.5f;
  s.shape = w.create_shape(field);
  s.position = Vec3(50, 0, 0);
  w.create_body(s);

  ShapeDef plane;
  plane.type = ShapeType::Plane;
  s.shape = w.create_shape(plane);
  s.position = Vec3(0, -20, 0);
  w.create_body(s);
  ShapeDef box;
  box.type = ShapeType::Box;
  BodyDef b;
  b.shape = w.create_shape(box);
  b.position = Vec3(0, -19.4f, 0);
  w.create_body(b);

  ShapeDef compound;
  compound.type = ShapeType::Compound;
  for (int k = 0; k < 12; ++k) {
    CompoundChild c;
    c.shape.type = k % 3 == 0   ? ShapeType::Box
                   : k % 3 == 1 ? ShapeType::Sphere
                                : ShapeType::Capsule;
    c.shape.radius = Real(0.2 + 0.02 * k);
    c.shape.half_extents = Vec3(0.3f, 0.2f, 0.1f);
    c.position = Vec3(Real(k % 4), Real(k / 4), Real(0.5 * (k % 2)));
    c.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.3 * k), Vec3(1, 1, 0).normalized()));
    compound.children.push_back(c);
  }
  b.shape = w.create_shape(compound);
  b.position = Vec3(0, 100, 0);
  b.angular_velocity = Vec3(1, 2, 3);
  w.create_body(b);
  for (int k = 0; k < 10; ++k) w.step(kDt);
  return w;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expect_same_shape(const detail::Shape& a, const detail::Shape& b) {
  ASSERT_EQ(a.type, b.type);
  EXPECT_EQ(a.local_min, b.local_min);
  EXPECT_EQ(a.local_max, b.local_max);
  EXPECT_EQ(a.frame_position, b.frame_position);
  EXPECT_EQ(a.frame_rotation.coeffs(), b.frame_rotation.coeffs());
  EXPECT_EQ(a.unit_inertia, b.unit_inertia);
  if (a.mesh) {
    ASSERT_TRUE(b.mesh);
    EXPECT_TRUE(same_bytes(a.mesh->vertices, b.mesh->vertices));
    EXPECT_TRUE(same_bytes(a.mesh->triangles, b.mesh->triangles));
    EXPECT_EQ(a.mesh->active_edges, b.mesh->active_edges);
    EXPECT_TRUE(same_bytes(a.mesh->tree.nodes, b.mesh->tree.nodes));
  }
  if (a.heightfield) {
    ASSERT_TRUE(b.heightfield);
    EXPECT_EQ(a.heightfield->heights, b.heightfield->heights);
    EXPECT_EQ(a.heightfield->columns, b.heightfield->columns);
    EXPECT_EQ(a.heightfield->rows, b.heightfield->rows);
    EXPECT_EQ(a.heightfield->spacing_x, b.heightfield->spacing_x);
  }
  if (a.compound) {
    ASSERT_TRUE(b.compound);
    const detail::Compound &ca = *a.compound, &cb = *b.compound;
    ASSERT_EQ(ca.parts.size(), cb.parts.size());
    EXPECT_EQ(ca.child_of, cb.child_of);
    EXPECT_TRUE(same_bytes(ca.tree.nodes, cb.tree.nodes));
    for (std::size_t k = 0; k < ca.parts.size(); ++k) {
      expect_same_shape(ca.parts[k].shape, cb.parts[k].shape);
      EXPECT_EQ(ca.parts[k].pose.position, cb.parts[k].pose.position);
      EXPECT_EQ(ca.parts[k].pose.rotation.coeffs(), cb.parts[k].pose.rotation.coeffs());
      EXPECT_EQ(ca.parts[k].box.min, cb.parts[k].box.min);
      EXPECT_EQ(ca.parts[k].box.max, cb.parts[k].box.max);
    }
  }
}

TEST(SnapshotSurfaces, RoundTripIsExactAndStepsIdentically) {
  World world = surfaces_world(12);
  World copy = load_snapshot(save_snapshot(world));
  const auto& sa = detail::state_of(world).shapes;
  const auto& sb = detail::state_of(copy).shapes;
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t k = 0; k < sa.size(); ++k) expect_same_shape(sa[k], sb[k]);
  ASSERT_FALSE(detail::state_of(world).shapes[4].compound->tree.nodes.empty());
  for (int s = 0; s < 60; ++s) {
    world.step(kDt);
    copy.step(kDt);
    ASSERT_EQ(copy.state_hash(), world.state_hash()) << "step " << s;
  }
  // Saving the loaded world again gives the same bytes.
  EXPECT_EQ(save_snapshot(copy), save_snapshot(world));
}

// A rollback state holds the moving bodies only: a surface a thousand times bigger leaves it the
// same size (shapes are never copied into frames).
TEST(SnapshotSurfaces, RollbackStatesDoNotCarryShapes) {
  World small = surfaces_world(2);
  World big = surfaces_world(60);
  EXPECT_EQ(save_rollback(small).size(), save_rollback(big).size());
  EXPECT_GT(save_snapshot(big).size(), save_snapshot(small).size() + 100000);
  const std::vector<uint8_t> frame = save_rollback(big);
  for (int s = 0; s < 5; ++s) big.step(kDt);
  restore_rollback(big, frame);
  World again = surfaces_world(60);
  EXPECT_EQ(big.state_hash(), again.state_hash());
}

void reseal(std::vector<uint8_t>& bytes) {
  bytes.erase(bytes.end() - 8, bytes.end());
  const uint64_t sum = detail::checksum_words(bytes);
  detail::ByteWriter(bytes).u64(sum);
}

std::string restore_error(const std::vector<uint8_t>& bytes) {
  World target;
  try {
    restore_snapshot(target, bytes);
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "snapshot");
    return e.what();
  }
  return "";
}

// The offset of the mesh's triangle count: right after the marker vertex, the last vertex.
std::size_t mesh_triangles_at(const std::vector<uint8_t>& bytes) {
  std::vector<uint8_t> marker;
  detail::ByteWriter wr(marker);
  wr.vec3(Vec3::Constant(kMarker));
  const auto it = std::search(bytes.begin(), bytes.end(), marker.begin(), marker.end());
  EXPECT_NE(it, bytes.end());
  return std::size_t(it - bytes.begin()) + marker.size();
}

TEST(SnapshotSurfaces, ResealedBadIndicesAndTreesAreRefused) {
  const std::vector<uint8_t> saved = save_snapshot(surfaces_world(3));
  const std::size_t count_at = mesh_triangles_at(saved);
  // The first triangle's first vertex index, past the vertices.
  std::vector<uint8_t> bytes = saved;
  bytes[count_at + 4] = 0xff;
  reseal(bytes);
  std::string error = restore_error(bytes);
  EXPECT_NE(error.find("mesh triangle vertex out of range"), std::string::npos) << error;
  // Edge flags past the three bits.
  bytes = saved;
  bytes[count_at + 4 + 12] = 9;
  reseal(bytes);
  error = restore_error(bytes);
  EXPECT_NE(error.find("edge flags"), std::string::npos) << error;
  // The tree follows the 18 triangles (13 bytes each) and its node count. A 4-wide node is 24
  // floats of boxes, then four child indices (offset 96) and four counts (offset 112). The root
  // (18 triangles, leaves of at most 8) has leaf children: its first child's count set to 0 makes
  // it an inner child whose index (its first triangle, 0) points back at the root.
  const std::size_t tree_at = count_at + 4 + 18 * 13;
  const std::size_t root_at = tree_at + 4;
  const auto u32_at = [&](const std::vector<uint8_t>& b, std::size_t at) {
    uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = v << 8 | b[at + std::size_t(k)];
    return v;
  };
  bytes = saved;
  ASSERT_GE(u32_at(bytes, tree_at), 1u);
  ASSERT_EQ(u32_at(bytes, root_at + 96), 0u);   // the first child's first triangle
  ASSERT_GT(u32_at(bytes, root_at + 112), 0u);  // the first child's count: a leaf
  for (int k = 0; k < 4; ++k) bytes[root_at + 112 + std::size_t(k)] = 0;
  reseal(bytes);
  error = restore_error(bytes);
  EXPECT_NE(error.find("tree child out of range"), std::string::npos) << error;
  // A leaf past the triangles.
  bytes = saved;
  bytes[root_at + 96 + 3] = 0x01;  // the first child's first triangle: 2^24
  reseal(bytes);
  error = restore_error(bytes);
  EXPECT_NE(error.find("tree leaf out of range"), std::string::npos) << error;

  // A node with no child.
  bytes = saved;
  for (std::size_t k = 0; k < 16; ++k) bytes[root_at + 112 + k] = 0xff;
  reseal(bytes);
  error = restore_error(bytes);
  EXPECT_NE(error.find("tree node has no children"), std::string::npos) << error;

  // The heightfield: its samples (f32, after its bounds and their count) found by the first
  // five heights, 0.1 ((k 7) % 5): 0, 0.2, 0.4, 0.1, 0.3.
  std::vector<uint8_t> first;
  for (const float h : {0.0f, 0.2f, 0.4f, 0.1f, 0.3f}) {
    detail::ByteWriter(first).u32(std::bit_cast<uint32_t>(float(Real(h))));
  }
  const auto samples = std::search(saved.begin(), saved.end(), first.begin(), first.end());
  ASSERT_NE(samples, saved.end());
  const std::size_t samples_at = std::size_t(samples - saved.begin());
  const auto set_f32 = [](std::vector<uint8_t>& b, std::size_t at, float v) {
    const uint32_t u = std::bit_cast<uint32_t>(v);
    for (int k = 0; k < 4; ++k) b[at + std::size_t(k)] = uint8_t(u >> (8 * k));
  };
  bytes = saved;
  set_f32(bytes, samples_at + 8, std::numeric_limits<float>::infinity());
  reseal(bytes);
  error = restore_error(bytes);
  EXPECT_NE(error.find("heightfield: shape.heights: height 2 (row 0, column 2) must be finite"),
            std::string::npos)
      << error;
  // Bounds that are not the samples' (the greatest, 0.4 m, saved as 0.5).
  bytes = saved;
  set_f32(bytes, samples_at - 8, 0.5f);
  reseal(bytes);
  error = restore_error(bytes);
  EXPECT_NE(error.find("bounds do not match"), std::string::npos) << error;
  // Every sample a hole.
  bytes = saved;
  for (std::size_t k = 0; k < 30; ++k) {
    set_f32(bytes, samples_at + 4 * k, std::numeric_limits<float>::quiet_NaN());
  }
  reseal(bytes);
  error = restore_error(bytes);
  EXPECT_NE(error.find("heightfield: shape.heights: the holes (NaN heights) leave no triangle"),
            std::string::npos)
      << error;

  // Any byte of the file changed and resealed is refused or loads a world that steps: never a
  // crash, a hang or an out-of-range read.
  int refused = 0;
  for (std::size_t k = 16; k + 8 < saved.size(); ++k) {
    bytes = saved;
    bytes[k] ^= 0x5a;
    reseal(bytes);
    World target;
    try {
      restore_snapshot(target, bytes);
    } catch (const Error&) {
      ++refused;
      continue;
    }
    target.step(kDt);
    SCOPED_TRACE(k);
    std::optional<RayHit> hit = target.cast_ray(Vec3(-49.5f, 5, 0.5f), -Vec3::UnitY(), 100);
    (void)hit;
  }
  EXPECT_GT(refused, 100);
}

// Versions 9 and 10 carry a mesh's binary tree (32-byte nodes: 3 f32 min, u32 index, 3 f32 max,
// u32 count). Loaded, it is collapsed into the 4-wide tree the mesh is built with: the world steps
// as it would have, and saves as the current version the bytes it would have saved.
TEST(SnapshotSurfaces, Version10MeshTreeLoadsAsTheTreeTheMeshIsBuiltWith) {
  World world = surfaces_world(3);
  const std::vector<uint8_t> saved = save_snapshot(world);
  // The binary tree the builder made: build_bvh over the triangles' boxes in the definition's
  // order, leaves of at most 8 (build_triangle_mesh).
  const ShapeDef def = bumpy_mesh(3);
  std::vector<detail::Aabb> boxes;
  for (const auto& t : def.triangles) {
    const Vec3 &a = def.vertices[t[0]], &b = def.vertices[t[1]], &c = def.vertices[t[2]];
    boxes.push_back({a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)});
  }
  std::vector<uint32_t> order;
  const detail::Bvh binary = detail::build_bvh(boxes, 8, order);
  const detail::Bvh4& built = detail::state_of(world).shapes[0].mesh->tree;
  ASSERT_TRUE(same_bytes(detail::collapse_to_bvh4(binary).nodes, built.nodes));

  // The same world as version 10 wrote it: the version, and the binary tree in the 4-wide one's
  // place.
  const std::size_t tree_at = mesh_triangles_at(saved) + 4 + 18 * 13;
  std::vector<uint8_t> old(saved.begin(), saved.begin() + std::ptrdiff_t(tree_at));
  detail::ByteWriter w(old);
  w.u32(uint32_t(binary.nodes.size()));
  for (const detail::BvhNode& n : binary.nodes) {
    for (float f : n.min) w.u32(std::bit_cast<uint32_t>(f));
    w.u32(n.index);
    for (float f : n.max) w.u32(std::bit_cast<uint32_t>(f));
    w.u32(n.count);
  }
  old.insert(old.end(), saved.begin() + std::ptrdiff_t(tree_at + 4 + built.nodes.size() * 128),
             saved.end());
  old[8] = 10;
  reseal(old);

  World loaded = load_snapshot(old);
  EXPECT_TRUE(same_bytes(detail::state_of(loaded).shapes[0].mesh->tree.nodes, built.nodes));
  EXPECT_EQ(save_snapshot(loaded), saved);
  for (int s = 0; s < 30; ++s) {
    world.step(kDt);
    loaded.step(kDt);
    ASSERT_EQ(loaded.state_hash(), world.state_hash()) << "step " << s;
  }
}

}  // namespace snapshot_surfaces_test
}  // namespace elan
