// SPDX-License-Identifier: MIT
// Convex hull builder: topology and geometry of known solids, invariants on random clouds against a
// brute-force supporting-plane oracle, degenerate inputs, and the hull clouds of the pile scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/base/convex_hull.hpp"
#include "elan/error.hpp"

namespace elan::detail {
namespace convex_hull_test {

// Float inputs are exact in the double arithmetic of the builder; what remains is the rounding of
// one Real dot product against an offset of the cloud's magnitude (tens of ulps), so geometric
// checks use a band of 1e-4 relative to the cloud's size in float builds.
Real eps_for(std::span<const Vec3> pts) {
  Real m = 0;
  for (const Vec3& p : pts) m = std::max(m, p.cwiseAbs().maxCoeff());
  return Real(1e-4) * std::max(m, Real(1)) *
         (std::numeric_limits<Real>::epsilon() / std::numeric_limits<float>::epsilon());
}

std::vector<Vec3> box_corners(const Vec3& h) {
  std::vector<Vec3> c;
  for (int i = 0; i < 8; ++i) {
    c.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  }
  return c;
}

Vec3 loop_normal(const ConvexHull& hull, const HullFace& f) {
  Vec3 n = Vec3::Zero();
  const Vec3& o = hull.vertices[hull.face_vertices[f.first]];
  for (uint32_t k = 1; k + 1 < f.count; ++k) {
    const Vec3& a = hull.vertices[hull.face_vertices[f.first + k]];
    const Vec3& b = hull.vertices[hull.face_vertices[f.first + k + 1]];
    n += (a - o).cross(b - o);
  }
  return n;
}

// Every structural and geometric invariant a hull must satisfy for its input cloud.
void expect_valid_hull(const ConvexHull& hull, std::span<const Vec3> pts) {
  const Real eps = eps_for(pts);
  const size_t nv = hull.vertices.size();
  ASSERT_GE(nv, 4u);
  ASSERT_GE(hull.faces.size(), 4u);
  // Euler's formula for a convex polyhedron.
  EXPECT_EQ(int(nv) - int(hull.edges.size()) + int(hull.faces.size()), 2);

  // Every hull vertex is one of the input points, bit for bit.
  for (const Vec3& v : hull.vertices) {
    EXPECT_TRUE(std::any_of(pts.begin(), pts.end(), [&](const Vec3& p) { return p == v; }));
  }
  // Every input point is inside or on every face plane.
  for (const HullFace& f : hull.faces) {
    for (const Vec3& p : pts) ASSERT_LE(f.normal.dot(p), f.offset + eps);
  }

  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  std::vector<int> faces_at(nv, 0);
  for (const HullFace& f : hull.faces) {
    ASSERT_GE(f.count, 3u);
    EXPECT_NEAR(f.normal.norm(), 1, 1e-5);
    // The loop lies on its plane and runs counter-clockwise seen from outside (its area vector
    // points along the outward normal), and is convex: each vertex is left of every loop edge.
    const Vec3 area = loop_normal(hull, f);
    EXPECT_GT(area.dot(f.normal), 0.99 * area.norm());
    for (uint32_t k = 0; k < f.count; ++k) {
      const uint32_t a = hull.face_vertices[f.first + k];
      const uint32_t b = hull.face_vertices[f.first + (k + 1) % f.count];
      ASSERT_LT(a, nv);
      EXPECT_NEAR(f.normal.dot(hull.vertices[a]), f.offset, eps);
      ++directed[{a, b}];
      ++faces_at[a];
      const Vec3 inward = f.normal.cross(hull.vertices[b] - hull.vertices[a]);
      for (uint32_t j = 0; j < f.count; ++j) {
        const Vec3& q = hull.vertices[hull.face_vertices[f.first + j]];
        EXPECT_GE(inward.dot(q - hull.vertices[a]), -eps * inward.norm());
      }
    }
  }
  // Closed and consistently oriented: each edge is walked once in each direction.
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(directed.count({e.second, e.first}), 1u);
  }
  EXPECT_EQ(directed.size(), 2 * hull.edges.size());
  // The edge list is exactly the set of undirected loop edges, each once with [0] < [1].
  std::set<std::pair<uint32_t, uint32_t>> listed;
  for (const auto& e : hull.edges) {
    EXPECT_LT(e[0], e[1]);
    EXPECT_TRUE(listed.insert({e[0], e[1]}).second);
    EXPECT_EQ(directed.count({e[0], e[1]}), 1u);
  }
  // Extreme points only: a vertex of a polyhedron meets at least three faces.
  for (size_t v = 0; v < nv; ++v) EXPECT_GE(faces_at[v], 3);
}

TEST(ConvexHull, BoxCornersGiveSixQuads) {
  const Vec3 h(1, 2, 3);
  const std::vector<Vec3> pts = box_corners(h);
  const ConvexHull hull = build_convex_hull(pts);
  expect_valid_hull(hull, pts);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.faces.size(), 6u);
  EXPECT_EQ(hull.edges.size(), 12u);
  // The faces are the six axis planes, at the half extents.
  std::set<std::pair<int, int>> axes;
  for (const HullFace& f : hull.faces) {
    EXPECT_EQ(f.count, 4u);
    int axis = 0;
    f.normal.cwiseAbs().maxCoeff(&axis);
    EXPECT_NEAR(std::abs(f.normal[axis]), 1, 1e-6);
    EXPECT_NEAR(f.offset, h[axis], 1e-6);
    axes.insert({axis, f.normal[axis] > 0 ? 1 : -1});
  }
  EXPECT_EQ(axes.size(), 6u);
}

TEST(ConvexHull, RegularTetrahedronHasFourTriangles) {
  const std::vector<Vec3> pts = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  const ConvexHull hull = build_convex_hull(pts);
  expect_valid_hull(hull, pts);
  EXPECT_EQ(hull.vertices.size(), 4u);
  EXPECT_EQ(hull.faces.size(), 4u);
  EXPECT_EQ(hull.edges.size(), 6u);
  // Insphere radius of a regular tetrahedron with circumradius sqrt(3) is sqrt(3)/3.
  for (const HullFace& f : hull.faces) EXPECT_NEAR(f.offset, std::sqrt(3.0) / 3, 1e-6);
}

TEST(ConvexHull, DropsInteriorDuplicateAndEdgePoints) {
  const Vec3 h(0.5, 1, 2);
  std::vector<Vec3> pts = box_corners(h);
  const std::vector<Vec3> corners = pts;
  // Duplicates, interior points, edge midpoints and face centres add no vertex.
  for (const Vec3& c : corners) pts.push_back(c);
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (int i = 0; i < 50; ++i) pts.push_back(h.cwiseProduct(Vec3{u(rng), u(rng), u(rng)}) * 0.9f);
  for (int a = 0; a < 3; ++a) {
    Vec3 c = Vec3::Zero();
    c[a] = h[a];
    pts.push_back(c);
    pts.push_back(-c);
  }
  pts.push_back(Vec3(h.x(), h.y(), 0));
  pts.push_back(Vec3(0, -h.y(), h.z()));
  pts.push_back(Vec3(-h.x(), 0, -h.z()));
  const ConvexHull hull = build_convex_hull(pts);
  expect_valid_hull(hull, pts);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.faces.size(), 6u);
  EXPECT_EQ(hull.edges.size(), 12u);
}

TEST(ConvexHull, RotatedOffsetBoxStillMergesFaces) {
  // Rotation and translation round the corners to float, so each face's four corners are
  // coplanar only within a few ulps: the tolerance must still merge each pair of triangles.
  const Quat q = Quat(Eigen::AngleAxis<Real>(Real(0.7), Vec3(1, 2, 3).normalized()));
  std::vector<Vec3> pts = box_corners(Vec3(0.3f, 0.45f, 0.2f));
  for (Vec3& p : pts) p = q * p + Vec3(30, -20, 50);
  const ConvexHull hull = build_convex_hull(pts);
  expect_valid_hull(hull, pts);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.faces.size(), 6u);
  EXPECT_EQ(hull.edges.size(), 12u);
}

// Brute-force oracle: a plane through three input points is a face plane of the hull iff every
// input point is on or below it. For points in general position, the hull's face normals are
// exactly the normals of such supporting planes.
void expect_matches_supporting_planes(const ConvexHull& hull, std::span<const Vec3> pts) {
  const Real eps = eps_for(pts);
  std::vector<Vec3> oracle;
  const size_t n = pts.size();
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      for (size_t k = j + 1; k < n; ++k) {
        Vec3 nrm = (pts[j] - pts[i]).cross(pts[k] - pts[i]);
        if (nrm.norm() < Real(1e-3)) continue;
        nrm.normalize();
        for (int side = 0; side < 2; ++side, nrm = -nrm) {
          const Real off = nrm.dot(pts[i]);
          bool support = true;
          for (const Vec3& p : pts) support = support && nrm.dot(p) <= off + eps;
          if (support) oracle.push_back(nrm);
        }
      }
    }
  }
  auto has = [](const std::vector<Vec3>& set, const Vec3& nrm) {
    return std::any_of(set.begin(), set.end(),
                       [&](const Vec3& m) { return m.dot(nrm) > Real(1 - 1e-4); });
  };
  std::vector<Vec3> faces;
  for (const HullFace& f : hull.faces) faces.push_back(f.normal);
  for (const Vec3& m : oracle) EXPECT_TRUE(has(faces, m)) << "missing face " << m.transpose();
  for (const Vec3& m : faces) EXPECT_TRUE(has(oracle, m)) << "spurious face " << m.transpose();
}

TEST(ConvexHull, RandomCloudsMatchBruteForceSupportingPlanes) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3> pts;
    const int n = 5 + trial * 2;
    for (int i = 0; i < n; ++i) pts.push_back(Vec3{u(rng), u(rng), u(rng)});
    const ConvexHull hull = build_convex_hull(pts);
    expect_valid_hull(hull, pts);
    expect_matches_supporting_planes(hull, pts);
  }
}

TEST(ConvexHull, RandomCloudInvariants) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<Real> u(-1, 1);
  std::normal_distribution<Real> g(0, 1);
  std::uniform_int_distribution<int> grid(-3, 3);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Vec3> pts;
    const int n = 20 + 25 * (trial % 8);
    const Vec3 offset{u(rng) * 100, u(rng) * 100, u(rng) * 100};
    const Real scale = std::pow(Real(10), Real(trial % 5 - 2));
    for (int i = 0; i < n; ++i) {
      Vec3 p;
      switch (trial % 4) {
        case 0:
          p = Vec3{u(rng), u(rng), u(rng)};
          break;
        case 1:
          p = Vec3{g(rng), g(rng), g(rng)};
          break;
        // Integer grid: many exactly coplanar and collinear points, the hard case for merging.
        case 2:
          p = Vec3{Real(grid(rng)), Real(grid(rng)), Real(grid(rng))};
          break;
        default:
          p = Vec3{g(rng), g(rng), g(rng)}.normalized();
          break;
      }
      pts.push_back(p * scale + (trial % 3 == 0 ? Vec3(offset * scale) : Vec3::Zero()));
      if (i % 7 == 0) pts.push_back(pts.back());
    }
    SCOPED_TRACE("trial " + std::to_string(trial));
    const ConvexHull hull = build_convex_hull(pts);
    expect_valid_hull(hull, pts);
  }
}

// Found by fuzz_narrowphase (tests/fuzz/corpus/narrowphase/regression_folded_hull_no_contact):
// three collinear points 6e-5 m and 0.08 m apart on an edge of a 4 m cloud (the last three below
// but one) came out folded, the triangles (x, 7, 9) and (x, 8, 7) back to back in one plane, with
// hull points 2.9 m above the first's plane; the SAT then read that face as separating two
// hulls overlapping by 1.7 m. Every input point must lie below every face plane.
TEST(ConvexHull, NearlyCoincidentCollinearPointsDoNotFoldTheHull) {
  const std::vector<Vec3> pts = {
      {0x1.8fb59p-1f, -0x1.d521ep-4f, -0x1.b88bb8p+0f},
      {0x1.6fa57p-1f, -0x1.ed25ecp-1f, -0x1.d13fd2p+0f},
      {0x1.51575p+0f, -0x1.aaa9a8p-2f, 0x1.b96db8p-1f},
      {-0x1.885d88p-1f, -0x1.667f66p+0f, 0x1.d56dd8p-1f},
      {0x1.62b96p-2f, -0x1.354b34p+0f, 0x1.669f68p+0f},
      {-0x1.461346p+0f, 0x1.a093ap+0f, 0x1.71618p-4f},
      {-0x1.ab71bp-3f, -0x1.ff94p+0f, -2},
      {-2, -2, -2},
      {-2, -2, -0x1.fffcp+0f},
      {-2, -2, -0x1.ebffecp+0f},
      {0x1.480548p-1f, 0x1.e43de8p-1f, -0x1.dcafdcp+0f},
  };
  const ConvexHull hull = build_convex_hull(pts);
  expect_valid_hull(hull, pts);
}

TEST(ConvexHull, PointsOnASphereAreAllVertices) {
  // Well-separated points on a sphere are all extreme; none may be lost to the tolerance.
  std::vector<Vec3> pts;
  const int rings = 8, per_ring = 12;
  pts.emplace_back(0, 1, 0);
  pts.emplace_back(0, -1, 0);
  for (int r = 1; r < rings; ++r) {
    const double phi = std::numbers::pi * r / rings;
    for (int k = 0; k < per_ring; ++k) {
      const double th = 2 * std::numbers::pi * (k + 0.5 * r) / per_ring;
      pts.emplace_back(Real(std::sin(phi) * std::cos(th)), Real(std::cos(phi)),
                       Real(std::sin(phi) * std::sin(th)));
    }
  }
  const ConvexHull hull = build_convex_hull(pts);
  expect_valid_hull(hull, pts);
  EXPECT_EQ(hull.vertices.size(), pts.size());
}

void expect_points_error(const std::vector<Vec3>& pts) {
  try {
    build_convex_hull(pts);
    ADD_FAILURE() << "no error for a degenerate cloud";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "points") << e.what();
  }
}

TEST(ConvexHull, DegenerateCloudsThrowWithFieldPoints) {
  expect_points_error({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
  expect_points_error(std::vector<Vec3>(10, Vec3(1, 2, 3)));
  std::vector<Vec3> line, plane, tilted;
  const Quat q = Quat(Eigen::AngleAxis<Real>(Real(0.4), Vec3(1, -1, 2).normalized()));
  for (int i = 0; i < 5; ++i) {
    line.emplace_back(Real(i), Real(2 * i), Real(-i));
    for (int j = 0; j < 5; ++j) {
      plane.emplace_back(Real(i), Real(j), 0);
      // A tilted plane with float rounding off the plane, still flat within tolerance.
      tilted.push_back(q * Vec3(Real(i), Real(j), 0) + Vec3(3, 4, 5));
    }
  }
  expect_points_error(line);
  expect_points_error(plane);
  expect_points_error(tilted);
  std::vector<Vec3> with_nan = box_corners(Vec3(1, 1, 1));
  with_nan[3].y() = std::numeric_limits<Real>::quiet_NaN();
  expect_points_error(with_nan);
  std::vector<Vec3> with_inf = box_corners(Vec3(1, 1, 1));
  with_inf[5].z() = std::numeric_limits<Real>::infinity();
  expect_points_error(with_inf);
}

TEST(ConvexHull, TransformMovesVerticesAndPlanes) {
  const std::vector<Vec3> pts = box_corners(Vec3(1, 2, 3));
  const ConvexHull hull = build_convex_hull(pts);
  const Mat3 r = Eigen::AngleAxis<Real>(Real(1.1), Vec3(0, 0.6f, 0.8f)).toRotationMatrix();
  const Vec3 origin(1, -2, 0.5f);
  const ConvexHull moved = transform_hull(hull, origin, r);
  ASSERT_EQ(moved.vertices.size(), hull.vertices.size());
  for (size_t i = 0; i < hull.vertices.size(); ++i) {
    EXPECT_LT((moved.vertices[i] - r * (hull.vertices[i] - origin)).norm(), 1e-5);
  }
  EXPECT_EQ(moved.face_vertices, hull.face_vertices);
  EXPECT_EQ(moved.edges, hull.edges);
  std::vector<Vec3> moved_pts;
  for (const Vec3& p : pts) moved_pts.push_back(r * (p - origin));
  for (size_t f = 0; f < hull.faces.size(); ++f) {
    EXPECT_LT((moved.faces[f].normal - r * hull.faces[f].normal).norm(), 1e-5);
    for (uint32_t k = 0; k < moved.faces[f].count; ++k) {
      const Vec3& v = moved.vertices[moved.face_vertices[moved.faces[f].first + k]];
      EXPECT_NEAR(moved.faces[f].normal.dot(v), moved.faces[f].offset, 1e-5);
    }
  }
}

TEST(ConvexHull, PileSceneCloudsBuild) {
  for (const char* name : {"pile4k.json"}) {
    std::ifstream in(std::string(ELAN_SCENE_DIR) + "/" + name);
    ASSERT_TRUE(in) << name;
    const nlohmann::json scene = nlohmann::json::parse(in);
    int hulls = 0;
    for (const auto& body : scene.at("bodies")) {
      const auto& shape = body.at("shape");
      if (shape.at("type") != "convex_hull") continue;
      std::vector<Vec3> pts;
      for (const auto& p : shape.at("points")) {
        pts.emplace_back(p[0].get<Real>(), p[1].get<Real>(), p[2].get<Real>());
      }
      const ConvexHull hull = build_convex_hull(pts);
      expect_valid_hull(hull, pts);
      if (::testing::Test::HasFailure()) FAIL() << name << " hull " << hulls;
      ++hulls;
    }
    EXPECT_GT(hulls, 0) << name;
  }
}

}  // namespace convex_hull_test
}  // namespace elan::detail
