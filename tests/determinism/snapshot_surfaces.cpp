// SPDX-License-Identifier: MIT
// Snapshots of worlds with a mesh, a heightfield and a compound: saved and loaded exactly (the
// built surfaces, trees and parts bit for bit), stepped identically after, and refused when a
// resealed file carries an index or a tree that does not fit.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
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
World surfaces_world(int mesh_cells) {
  World w;
  ShapeDef mesh;
  mesh.type = ShapeType::Mesh;
  const int n = mesh_cells;
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
  // The tree follows the 18 triangles (13 bytes each) and its node count; the root is an inner
  // node (18 triangles, leaves of at most 8): its second child's index (offset 12 in the node)
  // made to point back at the root.
  const std::size_t tree_at = count_at + 4 + 18 * 13;
  bytes = saved;
  ASSERT_GE(bytes[tree_at], 3);
  ASSERT_EQ(bytes[tree_at + 4 + 28], 0);  // the root's count: inner
  for (int k = 0; k < 4; ++k) bytes[tree_at + 4 + 12 + k] = 0;
  reseal(bytes);
  error = restore_error(bytes);
  EXPECT_NE(error.find("tree child out of range"), std::string::npos) << error;

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

}  // namespace snapshot_surfaces_test
}  // namespace elan
