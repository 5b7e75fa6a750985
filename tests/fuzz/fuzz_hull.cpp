// SPDX-License-Identifier: MIT
// Fuzz target: the convex hull builder on any points. The first byte chooses how the rest is
// read: raw floats (NaN, infinities, denormals: the refusals), or points on a grid of a given
// scale, often with duplicates, coplanar and nearly coplanar sets (the quickhull's tolerances).
// A cloud is refused with one elan::Error line naming "points", or its hull is a closed convex
// polyhedron holding every point: Euler's V - E + F = 2, each edge between two faces that run it
// in opposite directions, unit normals, every input point inside every face plane and every
// hull vertex an input point, and a shape made from the points has a positive finite volume.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/base/convex_hull.hpp"
#include "core/base/shape.hpp"
#include "elan/error.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace elan;
  using namespace elan::detail;
  fuzz::Bytes in{data, size};
  const uint8_t mode = in.u8();
  std::vector<Vec3> points;
  if (mode & 1) {
    while (!in.empty() && points.size() < 512) {
      points.push_back(Vec3{in.raw_float(), in.raw_float(), in.raw_float()});
    }
  } else {
    // Scale 1e-3 to 1e3 m; the grid step of 1/16 of a unit makes exact coplanarity common.
    const Real scale = std::pow(Real(10), Real(int(mode >> 1) % 7 - 3));
    while (!in.empty() && points.size() < 512) {
      const auto coord = [&] { return Real(int8_t(in.u8())) / Real(16) * scale; };
      points.push_back(Vec3{coord(), coord(), coord()});
    }
  }
  ConvexHull hull;
  try {
    hull = build_convex_hull(points);
  } catch (const Error& e) {
    fuzz::require_one_line(e.what());
    fuzz::require(e.field() == "points", "a refused cloud names the field points");
    return 0;
  }
  const std::size_t v = hull.vertices.size(), e = hull.edges.size(), f = hull.faces.size();
  fuzz::require(v >= 4 && f >= 4 && e >= 6, "a hull has at least a tetrahedron's features");
  fuzz::require(v + f == e + 2, "Euler's formula V - E + F = 2 for a closed convex polyhedron");
  fuzz::require(hull.edge_faces.size() == e, "every edge has its two faces");

  Real extent = 0;
  for (const Vec3& p : points) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  // The builder merges faces whose planes agree within a relative tolerance (32 float epsilons
  // of the coordinates' magnitudes); 1e-4 of the extent bounds what a merged face may leave out.
  const Real tol = Real(1e-4) * extent;
  for (const HullFace& face : hull.faces) {
    fuzz::require(face.count >= 3, "a face loop has at least three vertices");
    fuzz::require(std::abs(face.normal.norm() - 1) < Real(1e-4), "a face normal is unit");
    for (const Vec3& p : points) {
      fuzz::require(face.normal.dot(p) <= face.offset + tol, "every point is inside every face");
    }
  }
  for (const Vec3& hv : hull.vertices) {
    const bool from_input =
        std::any_of(points.begin(), points.end(), [&](const Vec3& p) { return p == hv; });
    fuzz::require(from_input, "every hull vertex is an input point");
  }
  for (std::size_t k = 0; k < e; ++k) {
    const auto [f0, f1] = hull.edge_faces[k];
    fuzz::require(f0 < f && f1 < f && f0 != f1, "an edge lies between two different faces");
  }

  ShapeDef def;
  def.type = ShapeType::ConvexHull;
  def.points = points;
  try {
    const Shape s = make_shape(def);
    fuzz::require(std::isfinite(s.volume) && s.volume > 0, "a hull shape has a positive volume");
    fuzz::require(s.unit_inertia.allFinite(), "a hull shape has finite inertia");
  } catch (const Error& err) {
    // The shape's own ranges (elan/limits.hpp: sizes 1e-4 to 1e4 m) may refuse what the bare
    // builder accepts; the refusal is still one line.
    fuzz::require_one_line(err.what());
  }
  return 0;
}
