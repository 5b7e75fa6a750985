// SPDX-License-Identifier: MIT
// Scene files with surfaces and compounds: mesh, heightfield and compound shapes read as the
// spec gives them, OBJ files (hull points, fanned faces, the format's index forms), the terrain
// generator's two forms being one surface, and every bad input refused with a message naming the
// body, the field and the triangle, row or child index.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "core/base/heightfield.hpp"
#include "core/base/shape.hpp"
#include "core/scene/terrain.hpp"
#include "elan/elan.hpp"

namespace elan {
namespace scene_geometry_test {

namespace fs = std::filesystem;

// A directory of this test's own (pid and test name), so ctest may run tests in parallel.
fs::path temp_dir() {
  std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path dir =
      fs::path(::testing::TempDir()) / ("elan_geometry_" + std::to_string(getpid()) + "_" + test);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

Scene one_body(const std::string& body, const std::string& file = "t.json") {
  return parse_scene(R"({"bodies": [)" + body + "]}", file);
}

// The SceneError message of parsing (and loading, when `load`) the scene, or "" if accepted.
std::string error_of(const std::string& text, bool load = false,
                     const std::string& file = "t.json") {
  try {
    const Scene s = parse_scene(text, file);
    if (load) {
      World w;
      load_into(s, w, file);
    }
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

std::string mesh_body(const std::string& triangles, const std::string& extra = "") {
  return R"({"name": "m", "motion": "static", "shape": {"type": "mesh",
      "vertices": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1], [2, 0, 0]],
      "triangles": )" +
         triangles + "}" + extra + "}";
}

std::string bodies(const std::string& body) {
  return R"({"bodies": [{"shape": {"type": "sphere", "radius": 1}}, )" + body + "]}";
}

TEST(SceneGeometry, ReadsAnInlineMesh) {
  const Scene s = one_body(mesh_body("[[0, 1, 2], [0, 2, 3]]"));
  const ShapeDef& m = s.bodies[0].shape;
  ASSERT_EQ(m.type, ShapeType::Mesh);
  ASSERT_EQ(m.vertices.size(), 5u);
  EXPECT_EQ(m.vertices[2], Vec3(1, 0, 1));
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(s.bodies[0].body.motion, MotionType::Static);
}

TEST(SceneGeometry, MeshErrorsNameTheBodyFieldAndTriangle) {
  EXPECT_EQ(error_of(bodies(mesh_body("[[0, 1, 2], [0, 2, 5]]"))),
            "t.json: body 1 (\"m\"): shape.triangles: triangle 1: index 5 is out of range (the "
            "mesh has 5 vertices)");
  EXPECT_EQ(error_of(bodies(mesh_body("[[0, 1, 2], [1, 2, 3], [3, 0, 3]]"))),
            "t.json: body 1 (\"m\"): shape.triangles: triangle 2: repeated vertex index (3, 0, 3)");
  EXPECT_NE(
      error_of(bodies(mesh_body("[[0, 1, -1]]"))).find("shape.triangles: triangle 0: expected"),
      std::string::npos);
  EXPECT_NE(error_of(bodies(mesh_body("[[0, 1]]"))).find("shape.triangles: triangle 0: expected 3"),
            std::string::npos);
  EXPECT_NE(error_of(bodies(mesh_body("[]"))).find("body 1 (\"m\"): shape.triangles"),
            std::string::npos);
  // Vertices 0, 1 and 4 lie on one line: a zero-area triangle, refused by the core when the shape
  // is made, and reported in the same form with the triangle's index.
  const std::string zero_area = error_of(bodies(mesh_body("[[0, 1, 2], [0, 4, 1]]")), true);
  EXPECT_EQ(zero_area.rfind("t.json: body 1 (\"m\"): shape.triangles: triangle 1: ", 0), 0u)
      << zero_area;
  // A mesh is a surface: no volume, no mass.
  EXPECT_EQ(
      error_of(bodies(
          R"({"name": "m", "shape": {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]],
                    "triangles": [[0, 1, 2]]}})")),
      "t.json: body 1 (\"m\"): motion: a mesh must be static");
  EXPECT_EQ(error_of(bodies(
                R"({"name": "m", "motion": "kinematic", "shape": {"type": "mesh",
                    "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]], "triangles": [[0, 1, 2]]}})")),
            "t.json: body 1 (\"m\"): motion: a mesh must be static");
}

std::string field_body(const std::string& heights, const std::string& spacing = "[0.5, 2]",
                       const std::string& motion = "static") {
  return R"({"name": "h", "motion": ")" + motion +
         R"(", "shape": {"type": "heightfield", "heights": )" + heights + R"(, "spacing": )" +
         spacing + "}}";
}

TEST(SceneGeometry, ReadsAHeightfieldRowByRow) {
  const Scene s = one_body(field_body("[[0, 1, 2], [3, 4, 5]]"));
  const ShapeDef& h = s.bodies[0].shape;
  ASSERT_EQ(h.type, ShapeType::Heightfield);
  EXPECT_EQ(h.columns, 3u);
  // heights[z][x] flattened row after row: heights[j * columns + i].
  ASSERT_EQ(h.heights.size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(h.heights[std::size_t(k)], Real(k));
  EXPECT_EQ(h.spacing_x, Real(0.5));
  EXPECT_EQ(h.spacing_z, Real(2));
  // null is a hole: NaN in the definition, and the field loads with the triangles left.
  const std::string holed = field_body("[[0, 1, null], [3, 4, 5]]");
  const Scene t = one_body(holed);
  ASSERT_EQ(t.bodies[0].shape.heights.size(), 6u);
  EXPECT_TRUE(std::isnan(t.bodies[0].shape.heights[2]));
  EXPECT_EQ(t.bodies[0].shape.heights[1], Real(1));
  EXPECT_EQ(error_of(bodies(holed), true), "");
}

TEST(SceneGeometry, HeightfieldErrorsNameTheBodyFieldAndRow) {
  EXPECT_EQ(error_of(bodies(field_body("[[0, 1, 2], [3, 4, 5], [6, 7]]"))),
            "t.json: body 1 (\"h\"): shape.heights: row 2 has 2 heights, row 0 has 3 (all rows "
            "must be the same length)");
  EXPECT_EQ(error_of(bodies(field_body("[[0, 1, 2]]"))),
            "t.json: body 1 (\"h\"): shape.heights: at least 2 rows of 2 heights are needed, got 1 "
            "rows of 3");
  EXPECT_NE(error_of(bodies(field_body("[[0], [1]]"))).find("shape.heights: at least 2 rows"),
            std::string::npos);
  EXPECT_EQ(error_of(bodies(field_body("[[0, 1], [2, 3]]", "[0, 1]"))),
            "t.json: body 1 (\"h\"): shape.spacing[0]: must be positive, got 0");
  EXPECT_NE(error_of(bodies(field_body("[[0, 1], [2, 3]]", "[1, -1]"))).find("shape.spacing[1]"),
            std::string::npos);
  EXPECT_NE(error_of(bodies(field_body("[[0, 1], [2, \"x\"]]"))).find("shape.heights[1][1]"),
            std::string::npos);
  EXPECT_EQ(error_of(bodies(field_body("[[0, 1], [2, 3]]", "[1, 1]", "dynamic"))),
            "t.json: body 1 (\"h\"): motion: a heightfield must be static");
  // Holes that leave no triangle: refused when the field is built.
  EXPECT_EQ(error_of(bodies(field_body("[[0, 1], [2, null]]")), true),
            "t.json: body 1 (\"h\"): shape.heights: the holes (NaN heights) leave no triangle: "
            "every cell has a hole at a corner of both its triangles");
}

std::string compound_body(const std::string& children) {
  return R"({"name": "c", "shape": {"type": "compound", "children": )" + children + "}}";
}

TEST(SceneGeometry, ReadsACompoundsChildren) {
  const Scene s = one_body(compound_body(R"([
      {"shape": {"type": "box", "half_extents": [1, 0.1, 1]}, "position": [0, 1, 0]},
      {"shape": {"type": "capsule", "radius": 0.1, "half_height": 0.5},
       "orientation": [0, 0, 0, 2]}])"));
  const ShapeDef& c = s.bodies[0].shape;
  ASSERT_EQ(c.type, ShapeType::Compound);
  ASSERT_EQ(c.children.size(), 2u);
  EXPECT_EQ(c.children[0].shape.type, ShapeType::Box);
  EXPECT_EQ(c.children[0].position, Vec3(0, 1, 0));
  EXPECT_EQ(c.children[0].orientation.coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(c.children[1].shape.type, ShapeType::Capsule);
  EXPECT_EQ(c.children[1].position, Vec3::Zero());
  EXPECT_EQ(c.children[1].orientation.coeffs(), Quat(0, 0, 0, 1).coeffs());  // normalised
}

TEST(SceneGeometry, CompoundErrorsNameTheBodyFieldAndChild) {
  const std::string ok = R"({"shape": {"type": "sphere", "radius": 1}}, )";
  for (
      const std::string child :
      {R"({"type": "plane", "normal": [0, 1, 0]})",
       R"({"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]], "triangles": [[0, 1, 2]]})",
       R"({"type": "heightfield", "heights": [[0, 0], [0, 0]], "spacing": [1, 1]})",
       R"({"type": "compound", "children": [{"shape": {"type": "sphere", "radius": 1}}]})"}) {
    const std::string e =
        error_of(bodies(compound_body("[" + ok + ok + R"({"shape": )" + child + "}]")));
    const std::string type = child.substr(10, child.find('"', 10) - 10);
    EXPECT_EQ(e,
              "t.json: body 1 (\"c\"): shape.children[2].shape.type: a compound child cannot be "
              "a " +
                  type + " (allowed: sphere, box, capsule, cylinder, convex_hull)")
        << child;
  }
  EXPECT_EQ(error_of(bodies(compound_body("[]"))),
            "t.json: body 1 (\"c\"): shape.children: a compound needs at least one child");
  EXPECT_EQ(
      error_of(bodies(compound_body("[" + ok + R"({"shape": {"type": "sphere", "radius": 0}}])"))),
      "t.json: body 1 (\"c\"): shape.children[1].shape.radius: must be positive, got 0");
  EXPECT_NE(error_of(bodies(compound_body(
                         "[" + ok + R"({"shape": {"type": "sphere", "radius": 1}, "colour": 1}])")))
                .find("shape.children[1].colour: unknown key for a compound child"),
            std::string::npos);
  EXPECT_NE(error_of(bodies(compound_body(R"([{"position": [0, 0, 0]}])")))
                .find("shape.children[0].shape: missing"),
            std::string::npos);
  // Inside a grid's template body the prefix says so.
  EXPECT_NE(error_of(R"({"generators": [{"type": "grid", "count": [1, 1, 1], "spacing": [1, 1, 1],
      "body": {"shape": {"type": "compound", "children": []}}}]})")
                .find("generator 0 (grid): body.shape.children: a compound needs"),
            std::string::npos);
}

// An OBJ box of half extents (0.5, 0.3, 0.2) centred on (1, 2, 3), written with quads.
const char* kBoxObj = R"(# a box
v 0.5 1.7 2.8
v 1.5 1.7 2.8
v 1.5 2.3 2.8
v 0.5 2.3 2.8
v 0.5 1.7 3.2
v 1.5 1.7 3.2
v 1.5 2.3 3.2
v 0.5 2.3 3.2
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 4 8 7 3
f 1 5 8 4
f 2 3 7 6
)";

// I = R diag(unit_inertia) R^T, the unit inertia tensor in the shape frame's axes.
Mat3 unit_tensor(const detail::Shape& s) {
  const Mat3 r = s.frame_rotation.toRotationMatrix();
  return r * s.unit_inertia.asDiagonal() * r.transpose();
}

TEST(SceneGeometry, AnObjBoxLoadsToTheSameMassPropertiesAsTheBox) {
  const fs::path dir = temp_dir();
  write(dir / "box.obj", kBoxObj);
  // Relative to the scene file's directory.
  const Scene s = one_body(R"({"shape": {"type": "convex_hull", "file": "box.obj"}})",
                           (dir / "scene.json").string());
  ASSERT_EQ(s.bodies[0].shape.type, ShapeType::ConvexHull);
  ASSERT_EQ(s.bodies[0].shape.points.size(), 8u);
  ShapeDef box;
  box.type = ShapeType::Box;
  box.half_extents = Vec3(Real(0.5), Real(0.3), Real(0.2));
  const detail::Shape hull = detail::make_shape(s.bodies[0].shape);
  const detail::Shape cuboid = detail::make_shape(box);
  // Float rounding of the hull's integral over 12 triangles is ~1e-6 relative; 1e-5 still tells
  // a missing or misplaced face (a change of 10% or more).
  const double v = 8 * 0.5 * 0.3 * 0.2;
  EXPECT_NEAR(hull.volume, v, 1e-5 * v);
  EXPECT_NEAR(cuboid.volume, v, 1e-5 * v);
  EXPECT_NEAR((hull.frame_position - Vec3(1, 2, 3)).norm(), 0, 1e-5);
  EXPECT_NEAR(cuboid.frame_position.norm(), 0, 1e-6);
  // A box's unit moments: (b^2 + c^2) / 3 of the other two half extents.
  const Mat3 expected =
      Vec3((0.09 + 0.04) / 3, (0.25 + 0.04) / 3, (0.25 + 0.09) / 3).cast<Real>().asDiagonal();
  EXPECT_NEAR((unit_tensor(hull) - expected).norm(), 0, 1e-5 * expected.norm());
  EXPECT_NEAR((unit_tensor(cuboid) - expected).norm(), 0, 1e-5 * expected.norm());
  // And in a world: the same mass and centre of mass.
  World w;
  load_into(s, w, "scene.json");
  EXPECT_NEAR(w.mass(w.body_at(0)), 1000 * v, 1e-5 * 1000 * v);
  EXPECT_NEAR((w.center_of_mass(w.body_at(0)) - Vec3(1, 2, 3)).norm(), 0, 1e-5);
}

TEST(SceneGeometry, ObjFacesAreFannedAndEveryIndexFormReadsAlike) {
  const fs::path dir = temp_dir();
  // A unit quad, as positive indices, negative (relative) ones, and with texture and normal
  // indices; the second file also spans a line with CRLF ends.
  write(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n");
  write(dir / "negative.obj", "v 0 0 0\r\nv 1 0 0\r\nv 1 0 1\r\nv 0 0 1\r\nf -4 -3 -2 -1\r\n");
  write(dir / "forms.obj",
        "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvt 0 0\nvn 0 1 0\nf 1/1/1 2//1 3/1 4/1/1\n");
  for (const char* name : {"quad.obj", "negative.obj", "forms.obj"}) {
    const Scene s = one_body(
        std::string(R"({"motion": "static", "shape": {"type": "mesh", "file": ")") + name + "\"}}",
        (dir / "scene.json").string());
    const ShapeDef& m = s.bodies[0].shape;
    ASSERT_EQ(m.vertices.size(), 4u) << name;
    EXPECT_EQ(m.vertices[2], Vec3(1, 0, 1)) << name;
    ASSERT_EQ(m.triangles.size(), 2u) << name;
    EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 2})) << name;
    EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 2, 3})) << name;
  }
  // A pentagon fans into three triangles around its first vertex.
  write(dir / "pentagon.obj", "v 0 0 0\nv 2 0 0\nv 3 0 1\nv 1 0 2\nv -1 0 1\nf 1 2 3 4 5\n");
  const Scene p = one_body(R"({"motion": "static", "shape": {"type": "mesh", "file": ")" +
                           (dir / "pentagon.obj").string() + "\"}}");
  ASSERT_EQ(p.bodies[0].shape.triangles.size(), 3u);
  EXPECT_EQ(p.bodies[0].shape.triangles[2], (std::array<uint32_t, 3>{0, 3, 4}));
}

TEST(SceneGeometry, ObjErrorsNameTheBodyFieldAndPath) {
  const fs::path dir = temp_dir();
  const std::string scene = (dir / "scene.json").string();
  const auto mesh_error =
      [&](const std::string& file) {
        return error_of(bodies(R"({"name": "m", "motion": "static", "shape": {"type": "mesh",
        "file": ")" + file + "\"}}"),
                        false, scene);
      };
  const std::string missing = mesh_error("missing.obj");
  EXPECT_EQ(missing.rfind(scene + ": body 1 (\"m\"): shape.file: " +
                              (dir / "missing.obj").string() + ": cannot open Wavefront OBJ: ",
                          0),
            0u)
      << missing;
  write(dir / "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 0\n");  // indices start at 1
  const std::string zero = mesh_error("zero.obj");
  EXPECT_NE(
      zero.find("body 1 (\"m\"): shape.file: " + (dir / "zero.obj").string() + ": malformed OBJ"),
      std::string::npos)
      << zero;
  write(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\nf 1 2 9\n");
  EXPECT_NE(mesh_error("range.obj")
                .find("shape.file: " + (dir / "range.obj").string() +
                      ": malformed OBJ: face 2 names a vertex that does not exist"),
            std::string::npos);
  write(dir / "empty.obj", "# nothing\n");
  EXPECT_NE(mesh_error("empty.obj").find("malformed OBJ: no vertices"), std::string::npos);
  write(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\n");
  EXPECT_NE(mesh_error("points.obj").find("malformed OBJ: no faces"), std::string::npos);
  write(dir / "repeat.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\nf 1 1 2\n");
  EXPECT_NE(mesh_error("repeat.obj").find("shape.file: triangle 1: repeated vertex index"),
            std::string::npos);
  // A hull from a file: its vertices are the points, so 4 coplanar ones are a degenerate hull.
  write(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n");
  const std::string flat =
      error_of(bodies(R"({"shape": {"type": "convex_hull", "file": "flat.obj"}})"), false, scene);
  EXPECT_NE(flat.find("body 1: shape.file: degenerate hull"), std::string::npos) << flat;
  EXPECT_NE(error_of(bodies(R"({"shape": {"type": "convex_hull", "file": "x.obj",
                                 "points": [[0, 0, 0]]}})"))
                .find("shape.points: give either points or file"),
            std::string::npos);
  // A directory is not an OBJ file.
  EXPECT_NE(mesh_error(".").find("is a directory"), std::string::npos);
}

TEST(SceneGeometry, TerrainMeshAndHeightfieldAreTheSameSurface) {
  const std::string terrain = R"("cells": [7, 5], "spacing": [0.75, 1.25], "origin": [-3, 1, 2],
                                 "amplitude": 2, "wavelength": 6)";
  const Scene s = parse_scene(R"({"generators": [
      {"type": "terrain", "shape": "heightfield", )" +
                                  terrain + R"(},
      {"type": "terrain", "shape": "mesh", )" +
                                  terrain + "}]}",
                              "t.json");
  ASSERT_EQ(s.bodies.size(), 2u);
  const ShapeDef& hf = s.bodies[0].shape;
  const ShapeDef& mesh = s.bodies[1].shape;
  ASSERT_EQ(hf.type, ShapeType::Heightfield);
  ASSERT_EQ(mesh.type, ShapeType::Mesh);
  for (const SceneBody& b : s.bodies) {
    EXPECT_EQ(b.body.motion, MotionType::Static);
    EXPECT_EQ(b.body.position, Vec3(-3, 1, 2));
  }
  const uint32_t nx = 8, nz = 6;
  ASSERT_EQ(hf.columns, nx);
  ASSERT_EQ(hf.heights.size(), std::size_t(nx * nz));
  ASSERT_EQ(mesh.vertices.size(), std::size_t(nx * nz));
  ASSERT_EQ(mesh.triangles.size(), std::size_t(2 * 7 * 5));
  // The sample (i, j) of the heightfield is the mesh's vertex j nx + i, to the bit.
  Real lo = hf.heights[0], hi = hf.heights[0];
  for (uint32_t j = 0; j < nz; ++j) {
    for (uint32_t i = 0; i < nx; ++i) {
      const Real h = hf.heights[j * nx + i];
      EXPECT_EQ(mesh.vertices[j * nx + i], Vec3(Real(i) * hf.spacing_x, h, Real(j) * hf.spacing_z));
      lo = std::min(lo, h);
      hi = std::max(hi, h);
      EXPECT_LE(std::abs(h), Real(2));  // |h| <= amplitude
    }
  }
  EXPECT_GT(hi - lo, Real(1)) << "a terrain of amplitude 2 is not flat";
  // The formula at the origin sample: 2 (0.3 sin 0.4 sin 1.1 + 0.2).
  EXPECT_NEAR(hf.heights[0], 2 * (0.3 * std::sin(0.4) * std::sin(1.1) + 0.2), 1e-6);
  // And at sample (1, 2): x = 0.75, z = 2.5, k = 2 pi / 6.
  const double k = 2 * std::numbers::pi / 6, x = 0.75, z = 2.5;
  const double h12 = 2 * (0.5 * std::sin(k * x) * std::cos(k * z) +
                          0.3 * std::sin(1.7 * k * x + 0.4) * std::sin(1.3 * k * z + 1.1) +
                          0.2 * std::cos(0.6 * k * (x + z)));
  EXPECT_NEAR(hf.heights[2 * nx + 1], h12, 1e-6);
  // Each cell as the heightfield splits it: its first triangle holds the corner (i+1, j), its
  // second the corner (i, j+1), both on the diagonal (i, j) - (i+1, j+1), both facing +y.
  for (uint32_t j = 0; j + 1 < nz; ++j) {
    for (uint32_t i = 0; i + 1 < nx; ++i) {
      const uint32_t c = j * (nx - 1) + i, v00 = j * nx + i;
      auto sorted = [](std::array<uint32_t, 3> t) {
        std::sort(t.begin(), t.end());
        return t;
      };
      EXPECT_EQ(sorted(mesh.triangles[2 * c]),
                (std::array<uint32_t, 3>{v00, v00 + 1, v00 + nx + 1}));
      EXPECT_EQ(sorted(mesh.triangles[2 * c + 1]),
                (std::array<uint32_t, 3>{v00, v00 + nx, v00 + nx + 1}));
      for (int t = 0; t < 2; ++t) {
        const auto& tri = mesh.triangles[2 * c + std::size_t(t)];
        const Vec3 n = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]])
                           .cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
        EXPECT_GT(n.y(), 0) << "cell " << c << " triangle " << t;
      }
    }
  }
  // The core's heightfield gives the same triangles, corner for corner.
  const detail::HeightField field =
      detail::build_heightfield(hf.heights, hf.columns, hf.spacing_x, hf.spacing_z);
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const detail::MeshTriangle tri = field.triangle(t);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(tri.v[k], mesh.vertices[mesh.triangles[t][std::size_t(k)]]) << t << " " << k;
    }
  }
}

TEST(SceneGeometry, TerrainErrorsNameTheGeneratorAndField) {
  const auto terrain = [](const std::string& keys) {
    return error_of(R"({"generators": [{"type": "terrain", )" + keys + "}]}");
  };
  EXPECT_NE(terrain(R"("shape": "plane", "cells": [2, 2], "spacing": [1, 1])")
                .find("generator 0 (terrain): shape: unknown terrain shape"),
            std::string::npos);
  EXPECT_NE(terrain(R"("shape": "mesh", "cells": [0, 2], "spacing": [1, 1])").find("cells[0]"),
            std::string::npos);
  EXPECT_NE(terrain(R"("shape": "mesh", "cells": [4096, 4096], "spacing": [1, 1])")
                .find("cells: too many cells"),
            std::string::npos);
  EXPECT_NE(terrain(R"("shape": "mesh", "cells": [2, 2], "spacing": [1, 0])").find("spacing[1]"),
            std::string::npos);
  EXPECT_NE(terrain(R"("shape": "mesh", "cells": [2, 2], "spacing": [1, 1], "wavelength": 0)")
                .find("wavelength: must be positive"),
            std::string::npos);
}

TEST(SceneGeometry, AGridCopiesACompoundBody) {
  const Scene s = parse_scene(R"({"generators": [{"type": "grid", "count": [3, 1, 2],
      "spacing": [2, 0, 2], "body": {"shape": {"type": "compound", "children": [
        {"shape": {"type": "sphere", "radius": 0.2}, "position": [-0.5, 0, 0]},
        {"shape": {"type": "sphere", "radius": 0.2}, "position": [0.5, 0, 0]},
        {"shape": {"type": "cylinder", "radius": 0.05, "half_height": 0.5},
         "orientation": [0.70710678, 0, 0, 0.70710678]}]}}}]})",
                              "t.json");
  ASSERT_EQ(s.bodies.size(), 6u);
  for (const SceneBody& b : s.bodies) ASSERT_EQ(b.shape.children.size(), 3u);
  EXPECT_EQ(s.bodies[5].body.position, Vec3(4, 0, 2));
}

}  // namespace scene_geometry_test
}  // namespace elan
