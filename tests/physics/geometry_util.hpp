// SPDX-License-Identifier: MIT
// Shapes for the geometry tests, made in code: a bumpy terrain as a mesh and as a heightfield
// (the same surface: each cell split along the same diagonal), compounds, and the convex shapes
// not in physics_util.hpp.
#pragma once

#include <cmath>
#include <cstdint>

#include "physics/physics_util.hpp"

namespace elan::test {

// The terrain's height at (x, z), m: gentle hills of 0.3 m, slopes under 25 degrees.
inline Real bumps(Real x, Real z) {
  return Real(0.3) * std::sin(Real(0.9) * x) * std::cos(Real(0.7) * z) +
         Real(0.1) * std::sin(Real(1.7) * z + Real(0.4) * x);
}

// A grid of (cells + 1)^2 samples `spacing` apart, its corner at (x0, 0, z0) in the body's frame
// when the body is placed at (x0, 0, z0) (a heightfield's sample (i, j) is (i dx, h, j dz)).
struct Terrain {
  int cells = 32;
  Real spacing = Real(0.5);
  Real x0 = -8, z0 = -8;

  Real height(int i, int j) const { return bumps(x0 + Real(i) * spacing, z0 + Real(j) * spacing); }
  // The surface's height at world (x, z), interpolated on the cell's triangle as the heightfield
  // and the mesh below split it (diagonal from (i, j) to (i + 1, j + 1)).
  Real surface(Real x, Real z) const {
    const Real u = (x - x0) / spacing, v = (z - z0) / spacing;
    const int i = int(std::floor(u)), j = int(std::floor(v));
    const Real fu = u - Real(i), fv = v - Real(j);
    const Real h00 = height(i, j), h11 = height(i + 1, j + 1);
    if (fu >= fv) {  // the triangle with the corner (i + 1, j)
      const Real h10 = height(i + 1, j);
      return h00 + fu * (h10 - h00) + fv * (h11 - h10);
    }
    const Real h01 = height(i, j + 1);
    return h00 + fv * (h01 - h00) + fu * (h11 - h01);
  }
};

inline ShapeDef heightfield_shape(const Terrain& t) {
  ShapeDef s;
  s.type = ShapeType::Heightfield;
  s.columns = uint32_t(t.cells + 1);
  s.spacing_x = s.spacing_z = t.spacing;
  for (int j = 0; j <= t.cells; ++j) {
    for (int i = 0; i <= t.cells; ++i) s.heights.push_back(t.height(i, j));
  }
  return s;
}

// The same surface as a mesh: vertex (i, j) at (i dx, h, j dz); each cell's two triangles,
// counter-clockwise seen from above.
inline ShapeDef mesh_shape(const Terrain& t) {
  ShapeDef s;
  s.type = ShapeType::Mesh;
  const uint32_t n = uint32_t(t.cells + 1);
  for (int j = 0; j <= t.cells; ++j) {
    for (int i = 0; i <= t.cells; ++i) {
      s.vertices.emplace_back(Real(i) * t.spacing, t.height(i, j), Real(j) * t.spacing);
    }
  }
  for (uint32_t j = 0; j < n - 1; ++j) {
    for (uint32_t i = 0; i < n - 1; ++i) {
      const uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      s.triangles.push_back({a, d, b});  // corner (i + 1, j)
      s.triangles.push_back({a, c, d});  // corner (i, j + 1)
    }
  }
  return s;
}

inline ShapeDef cylinder_shape(Real radius, Real half_height) {
  ShapeDef s;
  s.type = ShapeType::Cylinder;
  s.radius = radius;
  s.half_height = half_height;
  return s;
}

// A squashed octahedron with one vertex pulled sideways: a hull with no symmetry to lean on.
inline ShapeDef hull_shape(Real size) {
  ShapeDef s;
  s.type = ShapeType::ConvexHull;
  s.points = {Vec3(size, 0, 0),
              Vec3(-size, 0, 0),
              Vec3(0, size * Real(0.7), 0),
              Vec3(Real(0.2) * size, -size * Real(0.6), 0),
              Vec3(0, 0, size),
              Vec3(0, 0, -size * Real(0.8))};
  return s;
}

inline CompoundChild child(const ShapeDef& shape, const Vec3& position,
                           const Quat& orientation = Quat::Identity()) {
  CompoundChild c;
  c.shape = shape;
  c.position = position;
  c.orientation = orientation;
  return c;
}

// An L of two boxes: a 1 x 0.2 x 0.2 bar along x and a 0.2 x 0.6 x 0.2 bar up from its end.
inline ShapeDef l_shape() {
  ShapeDef s;
  s.type = ShapeType::Compound;
  s.children.push_back(child(box_shape(Vec3(Real(0.5), Real(0.1), Real(0.1))), Vec3::Zero()));
  s.children.push_back(
      child(box_shape(Vec3(Real(0.1), Real(0.3), Real(0.1))), Vec3(Real(0.4), Real(0.4), 0)));
  return s;
}

// A table: a top of 1 x 0.1 x 0.6 on four legs of 0.1 x 0.5 x 0.1 at its corners, the legs'
// feet at y = -0.3 in the compound's frame.
inline ShapeDef table_shape() {
  ShapeDef s;
  s.type = ShapeType::Compound;
  s.children.push_back(
      child(box_shape(Vec3(Real(0.5), Real(0.05), Real(0.3))), Vec3(0, Real(0.25), 0)));
  for (int k = 0; k < 4; ++k) {
    const Real x = (k & 1) ? Real(0.4) : Real(-0.4), z = (k & 2) ? Real(0.2) : Real(-0.2);
    s.children.push_back(
        child(box_shape(Vec3(Real(0.05), Real(0.25), Real(0.05))), Vec3(x, Real(-0.05), z)));
  }
  return s;
}

// A dumbbell: two spheres on a capsule bar, turned so the bar lies along x.
inline ShapeDef dumbbell_shape() {
  ShapeDef s;
  s.type = ShapeType::Compound;
  const Quat along_x(Eigen::AngleAxis<Real>(Real(M_PI / 2), Vec3::UnitZ()));
  s.children.push_back(child(capsule_shape(Real(0.05), Real(0.3)), Vec3::Zero(), along_x));
  s.children.push_back(child(sphere_shape(Real(0.15)), Vec3(Real(-0.35), 0, 0)));
  s.children.push_back(child(sphere_shape(Real(0.15)), Vec3(Real(0.35), 0, 0)));
  return s;
}

}  // namespace elan::test
