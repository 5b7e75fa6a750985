// SPDX-License-Identifier: MIT
// Tests of `elan view`: pictures rendered off screen (--screenshot) under a display (Xvfb with
// Mesa's software renderer in the test script), checked pixel by pixel, the viewer's state hash
// against `elan run`'s, and the errors that come before any window. Skipped when no display is
// set (the script runs them under `xvfb-run -a`).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "determinism/recorded_program.hpp"
#include "elan/debug_draw.hpp"
#include "stb/stb_image.h"

namespace elan::test {
namespace {

using Json = nlohmann::json;

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  const uint8_t* at(int x, int y) const { return &rgb[3 * (std::size_t(y) * width + x)]; }
};

Image load_png(const std::string& path) {
  Image img;
  int channels = 0;
  uint8_t* data = stbi_load(path.c_str(), &img.width, &img.height, &channels, 3);
  if (data != nullptr) {
    img.rgb.assign(data, data + std::size_t(img.width) * img.height * 3);
    stbi_image_free(data);
  }
  return img;
}

// A pixel is background when it is within a few levels of the clear colour (the top left
// corner of a picture whose corner shows no body); anything drawn is lit to other values.
bool is_background(const Image& img, int x, int y) {
  const uint8_t* c = img.at(x, y);
  const uint8_t* bg = img.at(0, 0);
  int d = 0;
  for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(c[k]) - int(bg[k])));
  return d <= 6;
}

std::size_t drawn_pixels(const Image& img) {
  std::size_t n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) n += !is_background(img, x, y);
  return n;
}

// Runs the elan binary with `env_prefix` (e.g. "env -u DISPLAY") before it.
Result run_with_env(const std::string& env_prefix, const std::vector<std::string>& args) {
  return run_elan(args, 120, env_prefix);
}

class ViewerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* display = std::getenv("DISPLAY");
    if (display == nullptr || *display == '\0') {
      GTEST_SKIP() << "no X display (DISPLAY is not set): tools/test.sh runs these tests under "
                      "'xvfb-run -a'";
    }
  }
  std::string scene(const std::string& name, const std::string& text) {
    const std::string path = temp_path(name + ".json");
    write(path, text);
    files_.push_back(path);
    return path;
  }
  std::string png(const std::string& name) {
    const std::string path = temp_path(name + ".png");
    files_.push_back(path);
    return path;
  }
  void TearDown() override {
    for (const std::string& f : files_) std::remove(f.c_str());
  }
  // Renders and returns the picture; the command must succeed.
  Image shot(const std::string& scene_path, const std::string& out, std::vector<std::string> extra,
             Json* summary = nullptr) {
    std::vector<std::string> args = {"view", scene_path, "--screenshot", out};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = run_elan(args, 120);
    EXPECT_EQ(r.status, 0) << r.err;
    if (summary != nullptr && r.status == 0) *summary = Json::parse(r.out);
    return load_png(out);
  }
  std::vector<std::string> files_;
};

// One box of half extents 1 at the origin, no gravity.
const char* const kOneBox = R"({"gravity": [0, 0, 0], "bodies": [
  {"shape": {"type": "box", "half_extents": [1, 1, 1]}, "position": [0, 0, 0]}]})";

TEST_F(ViewerTest, ScreenshotHasTheSizeAndTheBoxWhereTheCameraPutsIt) {
  const std::string s = scene("box", kOneBox);
  const std::string out = png("box");
  const Image img = shot(s, out, {"--size", "320x240", "--camera", "0,0,10,0,0,0"});
  ASSERT_EQ(img.width, 320);
  ASSERT_EQ(img.height, 240);
  // The face towards the eye (z = 1) is 9 m away; its half size 1 m spans 1 / (9 tan(22.5 deg))
  // of the half height in normalised coordinates (a vertical field of view of 45 degrees), so
  // h = 0.26825 * 120 = 32.2 pixels each way from the centre, the same across (the projection
  // keeps pixels square). The faces behind it project inside it.
  const double h = 120.0 / (9.0 * std::tan(3.14159265358979 / 8));
  std::size_t inside = 0, inside_drawn = 0, outside = 0, outside_drawn = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const double dx = std::abs(x + 0.5 - 160), dy = std::abs(y + 0.5 - 120);
      const bool drawn = !is_background(img, x, y);
      // Two pixels of margin on either side of the edge for its antialiasing.
      if (dx < h - 2 && dy < h - 2) {
        ++inside;
        inside_drawn += drawn;
      } else if (dx > h + 2 || dy > h + 2) {
        ++outside;
        outside_drawn += drawn;
      }
    }
  }
  EXPECT_GT(inside, 3000u);
  EXPECT_EQ(inside_drawn, inside);
  EXPECT_EQ(outside_drawn, 0u);
}

TEST_F(ViewerTest, SameStateTwiceGivesTheSameImageAndSteppingChangesIt) {
  // The small scene: bodies fall and tumble on a ground box.
  const std::string s = scene("small", kSmallScene);
  const std::vector<std::string> view = {"--size", "200x150", "--camera", "4,3,6,0,0.5,0"};
  std::vector<std::string> at120 = view;
  at120.insert(at120.end(), {"--steps", "120"});
  const Image a = shot(s, png("a"), view), b = shot(s, png("b"), view),
              c = shot(s, png("c"), at120);
  ASSERT_EQ(a.rgb.size(), 200u * 150u * 3u);
  EXPECT_GT(drawn_pixels(a), 1000u);
  EXPECT_EQ(a.rgb, b.rgb);
  ASSERT_EQ(c.rgb.size(), a.rgb.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.rgb.size(); i += 3) differ += a.rgb[i] != c.rgb[i];
  EXPECT_GT(differ, 100u) << "the bodies moved in 120 steps";
}

TEST_F(ViewerTest, EveryShapeKindIsDrawn) {
  // Each kind alone at the origin, seen from the same camera: each picture shows something.
  // (A joint is drawn as lines: two spheres with and without one differ.)
  const std::vector<std::pair<std::string, std::string>> shapes = {
      {"sphere", R"({"type": "sphere", "radius": 0.8})"},
      {"box", R"({"type": "box", "half_extents": [0.6, 0.5, 0.4]})"},
      {"capsule", R"({"type": "capsule", "radius": 0.4, "half_height": 0.6})"},
      {"cylinder", R"({"type": "cylinder", "radius": 0.5, "half_height": 0.6})"},
      {"hull",
       R"({"type": "convex_hull", "points": [[1,0,0],[-1,0,0],[0,1,0],[0,-1,0],[0,0,1],[0,0,-1]]})"},
      {"plane", R"({"type": "plane", "normal": [0, 1, 0], "offset": -0.5})"},
      {"mesh",
       R"({"type": "mesh", "vertices": [[-1,0,-1],[1,0,-1],[1,0,1],[-1,0,1]], "triangles": [[0,2,1],[0,3,2]]})"},
      {"heightfield",
       R"({"type": "heightfield", "heights": [[0,0.5,0],[0.3,0,0.2],[0,0.4,0]], "spacing": [0.8, 0.8]})"},
      {"compound",
       R"({"type": "compound", "children": [{"shape": {"type": "box", "half_extents": [0.5,0.2,0.2]}, "position": [0,0,0]}, {"shape": {"type": "sphere", "radius": 0.3}, "position": [0,0.5,0]}]})"},
  };
  for (const auto& [kind, shape] : shapes) {
    const bool fixed = kind == "plane" || kind == "mesh" || kind == "heightfield";
    const std::string s =
        scene(kind, std::string(R"({"gravity": [0,0,0], "bodies": [{"shape": )") + shape +
                        (fixed ? R"(, "motion": "static")" : "") + R"(}]})");
    const Image img = shot(s, png(kind), {"--size", "160x120", "--camera", "0,3,6,0,0,0"});
    ASSERT_EQ(img.width, 160) << kind;
    // Something of its own colour: more than 1% of the picture (each shape spans several %).
    EXPECT_GT(drawn_pixels(img), 160u * 120u / 100u) << kind;
  }
  const std::string two = R"({"gravity": [0,0,0], "bodies": [
    {"name": "a", "shape": {"type": "sphere", "radius": 0.2}, "position": [-1.5, 0, 0]},
    {"name": "b", "shape": {"type": "sphere", "radius": 0.2}, "position": [1.5, 0, 0]}])";
  const Image without = shot(scene("apart", two + "}"), png("apart"),
                             {"--size", "160x120", "--camera", "0,0,5,0,0,0"});
  const Image with = shot(
      scene("joined",
            two + R"(, "joints": [{"type": "ball", "bodies": ["a", "b"], "anchor": [0, 0, 0]}]})"),
      png("joined"), {"--size", "160x120", "--camera", "0,0,5,0,0,0"});
  EXPECT_GT(drawn_pixels(with), drawn_pixels(without) + 40) << "the joint's line";
}

TEST_F(ViewerTest, StateHashIsTheRunsForTheSameSceneAndSteps) {
  const std::string s = scene("small", kSmallScene);
  for (const char* steps : {"0", "90"}) {
    Json view;
    shot(s, png("hash"), {"--steps", steps, "--size", "64x64"}, &view);
    const Result run = run_elan({"run", s, "--steps", steps});
    ASSERT_EQ(run.status, 0) << run.err;
    const Json r = Json::parse(run.out);
    EXPECT_EQ(view["state_hash"], r["state_hash"]) << steps << " steps";
    EXPECT_EQ(view["steps"], r["steps"]);
  }
  // A recording is replayed to the step asked for: the recorded hash.
  const std::string rec = temp_path("rec.elanrec");
  files_.push_back(rec);
  const Result run =
      run_elan({"run", s, "--steps", "100", "--record", rec, "--keyframe-every", "30"});
  ASSERT_EQ(run.status, 0) << run.err;
  Json view;
  shot(rec, png("rec"), {"--step", "100", "--body", "1", "--size", "64x64"}, &view);
  EXPECT_EQ(view["state_hash"], Json::parse(run.out)["state_hash"]);
  EXPECT_EQ(view["steps"], 100);
}

// Where a camera looking along -z from (0, cy, d) at (0, cy, 0) puts the world point (x, y, z)
// in a picture of height h (45 degrees of vertical field, square pixels): f = (h / 2) /
// tan(22.5 deg) pixels per unit of x / depth.
struct Projection {
  double width, height, cy, d;
  double f() const { return height / 2 / std::tan(3.14159265358979 / 8); }
  double px(double x, double z) const { return width / 2 + f() * x / (d - z); }
  double py(double y, double z) const { return height / 2 - f() * (y - cy) / (d - z); }
};

// The pixels that differ between two pictures of the same size.
std::vector<std::pair<int, int>> changed(const Image& a, const Image& b) {
  std::vector<std::pair<int, int>> out;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      if (std::memcmp(a.at(x, y), b.at(x, y), 3) != 0) out.emplace_back(x, y);
    }
  }
  return out;
}

// Chromaticity: the colour with its brightness divided out. Lighting scales a body's colour by
// one factor per pixel (renderer.cpp), so the faces of one colour share it.
std::array<double, 3> chroma(const Image& img, double cx, double cy) {
  // The mean of a 5x5 patch.
  double sum[3] = {0, 0, 0};
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx)
      for (int k = 0; k < 3; ++k) sum[k] += img.at(int(cx) + dx, int(cy) + dy)[k];
  const double t = sum[0] + sum[1] + sum[2];
  return {sum[0] / t, sum[1] / t, sum[2] / t};
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

// --draw bounds: a sphere of radius 1 at the origin has the box [-1, 1]^3, whose twelve edges are
// drawn over everything. Seen from z = 10 its front square (z = 1) projects to f / 9 pixels each
// way from the centre and its back one (z = -1) to f / 11, both outside or across the sphere's
// outline (radius f / sqrt(99)). Every pixel the overlay changes lies within the front square;
// outside the sphere it is the bounds' yellow over the background; without --draw none is.
TEST_F(ViewerTest, BoundsOverlayOutlinesTheBodyWhereTheProjectionPutsIt) {
  const std::string s = scene("ball", R"({"gravity": [0, 0, 0], "bodies": [
    {"shape": {"type": "sphere", "radius": 1}, "position": [0, 0, 0]}]})");
  const std::vector<std::string> view = {"--size", "320x240", "--camera", "0,0,10,0,0,0"};
  std::vector<std::string> with = view;
  with.insert(with.end(), {"--draw", "bounds"});
  const Image plain = shot(s, png("plain"), view), bounds = shot(s, png("bounds"), with);
  ASSERT_EQ(plain.rgb.size(), bounds.rgb.size());
  const Projection cam{320, 240, 0, 10};
  const double front = cam.f() / 9, back = cam.f() / 11, ball = cam.f() / std::sqrt(99.0);
  // A yellow pixel: red and green well above blue (the background is bluish grey).
  const auto yellow = [](const Image& img, int x, int y) {
    const uint8_t* c = img.at(x, y);
    return int(c[0]) - int(c[2]) > 50 && int(c[1]) - int(c[2]) > 50;
  };
  std::size_t outside_square = 0, yellow_outside_ball = 0;
  for (const auto& [x, y] : changed(plain, bounds)) {
    const double dx = std::abs(x + 0.5 - 160), dy = std::abs(y + 0.5 - 120);
    outside_square += dx > front + 2 || dy > front + 2;
    if (std::hypot(dx, dy) > ball + 2) yellow_outside_ball += yellow(bounds, x, y);
    // Every changed pixel is on one of the projected edges: the front or back square's sides,
    // or a corner-to-corner edge along z (on the diagonals |dx| = |dy|).
    const bool on_front = (std::abs(dx - front) < 2 && dy < front + 2) ||
                          (std::abs(dy - front) < 2 && dx < front + 2);
    const bool on_back =
        (std::abs(dx - back) < 2 && dy < back + 2) || (std::abs(dy - back) < 2 && dx < back + 2);
    const bool on_diagonal = std::abs(dx - dy) < 2.5 && dx > back - 2 && dx < front + 2;
    EXPECT_TRUE(on_front || on_back || on_diagonal) << x << "," << y;
  }
  EXPECT_EQ(outside_square, 0u);
  // The front square's perimeter is 8 f / 9 = 257 pixels, most of it outside the ball.
  EXPECT_GT(yellow_outside_ball, 150u);
  std::size_t yellow_plain = 0;
  for (int y = 0; y < plain.height; ++y) {
    for (int x = 0; x < plain.width; ++x) {
      const bool outside_ball = std::hypot(x + 0.5 - 160, y + 0.5 - 120) > ball + 2;
      yellow_plain += outside_ball && yellow(plain, x, y);
    }
  }
  EXPECT_EQ(yellow_plain, 0u) << "no overlay without --draw";
}

// --draw contacts: a box of half extents 0.5 resting on the ground touches it at its four bottom
// corners (y = 0, x and z = +-0.5); each point is drawn as a small cross and its normal (from
// body A to body B, up or down by the pair's order) as a white line 0.2 m long. Every changed
// pixel lies around those points; white appears only with the overlay.
TEST_F(ViewerTest, ContactOverlayDrawsPointsAndNormalsAtTheContact) {
  const std::string s = scene("resting", R"({"bodies": [
    {"motion": "static", "shape": {"type": "box", "half_extents": [10, 1, 10]}, "position": [0, -1, 0]},
    {"shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [0, 0.5, 0]}]})");
  const std::vector<std::string> view = {"--size",          "320x240", "--camera",
                                         "0,0.5,6,0,0.5,0", "--steps", "20"};
  std::vector<std::string> with = view;
  with.insert(with.end(), {"--draw", "contacts"});
  const Image plain = shot(s, png("plain"), view), contacts = shot(s, png("contacts"), with);
  ASSERT_EQ(plain.rgb.size(), contacts.rgb.size());
  const Projection cam{320, 240, 0.5, 6};
  // The points and normals span x in [-0.55, 0.55], y in [-0.21, 0.21], z in [-0.55, 0.55]
  // (crosses of 0.05 m half length, normals 0.2 m; a margin of 3 pixels for the lines' width).
  const double x_max = cam.f() * 0.55 / 5.45 + 3;
  // The highest point on the picture is the farthest top one, the lowest the nearest bottom one.
  const double y_lo = cam.py(0.21, -0.55) - 3, y_hi = cam.py(-0.21, 0.55) + 3;
  const auto white = [](const Image& img, int x, int y) {
    const uint8_t* c = img.at(x, y);
    return std::min({c[0], c[1], c[2]}) > 200;
  };
  const std::vector<std::pair<int, int>> diff = changed(plain, contacts);
  std::size_t outside = 0, white_pixels = 0;
  for (const auto& [x, y] : diff) {
    outside += std::abs(x + 0.5 - 160) > x_max || y + 0.5 < y_lo || y + 0.5 > y_hi;
    white_pixels += white(contacts, x, y);
  }
  EXPECT_GT(diff.size(), 40u);
  EXPECT_EQ(outside, 0u);
  EXPECT_GT(white_pixels, 4u) << "the normals";
  std::size_t white_plain = 0;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) white_plain += white(plain, x, y);
  EXPECT_EQ(white_plain, 0u);
}

// --draw islands: two piles of two boxes, apart on the ground, are two islands (contacts with
// the static ground link nothing): the boxes of one pile share a colour, the piles' differ.
TEST_F(ViewerTest, IslandsAreColouredOneColourEach) {
  const std::string s = scene("piles", R"({"bodies": [
    {"motion": "static", "shape": {"type": "box", "half_extents": [10, 1, 10]}, "position": [0, -1, 0]},
    {"shape": {"type": "box", "half_extents": [0.4, 0.4, 0.4]}, "position": [-1.5, 0.4, 0]},
    {"shape": {"type": "box", "half_extents": [0.4, 0.4, 0.4]}, "position": [-1.5, 1.2, 0]},
    {"shape": {"type": "box", "half_extents": [0.4, 0.4, 0.4]}, "position": [1.5, 0.4, 0]},
    {"shape": {"type": "box", "half_extents": [0.4, 0.4, 0.4]}, "position": [1.5, 1.2, 0]}]})");
  const Image img = shot(
      s, png("islands"),
      {"--size", "320x240", "--camera", "0,0.8,8,0,0.8,0", "--steps", "10", "--draw", "islands"});
  ASSERT_EQ(img.width, 320);
  const Projection cam{320, 240, 0.8, 8};
  // The centres of the boxes' front faces (z = 0.4).
  const auto at = [&](double x, double y) { return chroma(img, cam.px(x, 0.4), cam.py(y, 0.4)); };
  const auto a_low = at(-1.5, 0.4), a_high = at(-1.5, 1.2);
  const auto b_low = at(1.5, 0.4), b_high = at(1.5, 1.2);
  // One colour per island, up to 8-bit rounding (about 1/300 of a channel at these levels).
  EXPECT_LT(distance(a_low, a_high), 0.02);
  EXPECT_LT(distance(b_low, b_high), 0.02);
  // The library's island colours of roots 1 and 3 are blue and magenta: far apart.
  EXPECT_GT(distance(a_low, b_low), 0.1);
}

// --draw halves: four boxes in a row along x, 1 m apart but for a 3.5 m gap on the right. The
// solver cuts them at the median of their centres along x (the axis of largest spread): the
// first two by x (-3, -2) in half 0, the other two (-1, 2.5) in half 1, so the cut lies between
// -2 and -1, not in the gap nor at the origin.
TEST_F(ViewerTest, SolverHalvesAreColouredOneColourEachSplitAtTheMedian) {
  std::string bodies =
      R"({"bodies": [{"motion": "static", "shape": {"type": "box", "half_extents": [10, 1, 10]},)"
      R"( "position": [0, -1, 0]})";
  for (const char* x : {"-3", "-2", "-1", "2.5"}) {
    bodies += R"(, {"shape": {"type": "box", "half_extents": [0.4, 0.4, 0.4]}, "position": [)" +
              std::string(x) + ", 0.4, 0]}";
  }
  const std::string s = scene("row", bodies + "]}");
  const std::vector<std::string> view = {"--size",          "320x240", "--camera",
                                         "0,0.4,9,0,0.4,0", "--steps", "5"};
  std::vector<std::string> with_halves = view;
  with_halves.insert(with_halves.end(), {"--draw", "halves"});
  const Image img = shot(s, png("halves"), with_halves);
  ASSERT_EQ(img.width, 320);
  const Projection cam{320, 240, 0.4, 9};
  // The centres of the boxes' front faces (z = 0.4).
  const auto at = [&](double x) { return chroma(img, cam.px(x, 0.4), cam.py(0.4, 0.4)); };
  const auto a = at(-3), b = at(-2), c = at(-1), d = at(2.5);
  // One colour per half, up to 8-bit rounding.
  EXPECT_LT(distance(a, b), 0.02);
  EXPECT_LT(distance(c, d), 0.02);
  EXPECT_GT(distance(b, c), 0.1);
  // Each the library's colour of its half: nearer its own half's chromaticity than the other's.
  const auto chroma_of = [](DebugColor k) {
    const double t = double(k.r) + k.g + k.b;
    return std::array<double, 3>{k.r / t, k.g / t, k.b / t};
  };
  const auto half0 = chroma_of(kSolverHalfColors[0]), half1 = chroma_of(kSolverHalfColors[1]);
  EXPECT_LT(distance(a, half0), distance(a, half1));
  EXPECT_LT(distance(d, half1), distance(d, half0));
  // Without the overlay the boxes keep their own colours: the picture differs on every box.
  const Image plain = shot(s, png("halves_off"), view);
  for (const double x : {-3.0, -2.0, -1.0, 2.5}) {
    const int px = int(cam.px(x, 0.4)), py = int(cam.py(0.4, 0.4));
    EXPECT_NE(std::memcmp(img.at(px, py), plain.at(px, py), 3), 0) << x;
  }
}

// Sensors are drawn translucent green: a body behind a sensor shows through it, where a solid
// body of the same shape hides it completely.
TEST_F(ViewerTest, SensorsAreTranslucentAndGreen) {
  const auto scene_text = [](bool sensor, bool behind) {
    std::string t =
        R"({"gravity": [0, 0, 0], "bodies": [
      {"motion": "static", "sensor": )" +
        std::string(sensor ? "true" : "false") +
        R"(, "shape": {"type": "box", "half_extents": [1, 1, 1]}, "position": [0, 0, 0]})";
    if (behind) {
      t +=
          R"(, {"shape": {"type": "box", "half_extents": [0.4, 0.4, 0.4]}, "position": [0, 0, -3]})";
    }
    return t + "]}";
  };
  const std::vector<std::string> view = {"--size", "320x240", "--camera", "0,0,10,0,0,0"};
  const auto render = [&](bool sensor, bool behind) {
    const std::string name = std::string(sensor ? "sensor" : "solid") + (behind ? "_behind" : "");
    return shot(scene(name, scene_text(sensor, behind)), png(name), view);
  };
  const Image sensor = render(true, false), sensor_behind = render(true, true);
  const Image solid = render(false, false), solid_behind = render(false, true);
  // The small box (front face at z = -2.6) spans f 0.4 / 12.6 = 9.2 pixels each way from the
  // centre: the central 12 x 12 pixels lie inside it and inside the big box's outline.
  std::size_t through_sensor = 0, through_solid = 0, green = 0, centre = 0;
  for (int y = 114; y < 126; ++y) {
    for (int x = 154; x < 166; ++x) {
      ++centre;
      through_sensor += std::memcmp(sensor.at(x, y), sensor_behind.at(x, y), 3) != 0;
      through_solid += std::memcmp(solid.at(x, y), solid_behind.at(x, y), 3) != 0;
      const uint8_t* c = sensor.at(x, y);
      green += c[1] > c[0] + 20 && c[1] > c[2] + 10;
    }
  }
  EXPECT_EQ(through_sensor, centre) << "what is behind a sensor shows through it";
  EXPECT_EQ(through_solid, 0u) << "a solid box hides it";
  EXPECT_EQ(green, centre);
  EXPECT_NE(sensor.rgb, solid.rgb);
}

// A program recording (elan/recorder.hpp) plays on the timeline: at any step the viewer's state
// is the one `elan replay --until` reaches.
TEST_F(ViewerTest, ProgramRecordingStateIsTheReplaysAtTheStep) {
  const RecordedProgram program = record_program(2);
  const std::string rec = temp_path("program_view.rec");
  files_.push_back(rec);
  write(rec, std::string(program.recording.begin(), program.recording.end()));
  for (const char* step : {"0", "45", "120"}) {
    Json view;
    shot(rec, png("program"), {"--step", step, "--size", "64x64"}, &view);
    const Result replay = run_elan({"replay", rec, "--until", step});
    ASSERT_EQ(replay.status, 0) << replay.err;
    const Json r = Json::parse(replay.out);
    EXPECT_EQ(view["state_hash"], r["state_hash"]) << "step " << step;
    EXPECT_EQ(view["steps"], std::stoi(step));
  }
}

// Needs no display: the scene is checked before any window opens.
TEST(ViewerErrors, BadSceneExitsTwoWithTheUsualMessageBeforeAnyWindow) {
  const std::string path = temp_path("bad.json");
  write(path, R"({"bodies": [{"shape": {"type": "sphere", "radius": -1}}]})");
  const Result run = run_elan({"run", path});
  const Result view = run_with_env("env -u DISPLAY -u WAYLAND_DISPLAY", {"view", path});
  std::remove(path.c_str());
  EXPECT_EQ(view.status, 2);
  EXPECT_EQ(view.err, run.err);  // the same one line, and nothing about a display
  EXPECT_NE(view.err.find("radius"), std::string::npos) << view.err;
  EXPECT_EQ(count_lines(view.err), 1u);
}

TEST(ViewerErrors, ScreenshotWithoutDisplayFailsWithOneClearLine) {
  const std::string s = temp_path("small.json"), out = temp_path("none.png");
  write(s, kSmallScene);
  const Result r =
      run_with_env("env -u DISPLAY -u WAYLAND_DISPLAY", {"view", s, "--screenshot", out});
  std::remove(s.c_str());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("no display"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("xvfb-run"), std::string::npos) << r.err;
  EXPECT_TRUE(read(out).empty());
}

TEST(ViewerErrors, BadOptionsExitTwo) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"view"},
                                               {"view", "x.json", "--size", "10x10"},
                                               {"view", "x.json", "--camera", "1,2,3"},
                                               {"view", "x.json", "--camera", "0,0,0,0,0,0"},
                                               {"view", "x.json", "--every", "2"},
                                               {"view", "x.json", "--draw", "bounds,boxes"},
                                               {"view", "x.json", "--draw", "com,com"},
                                               {"view", "x.json", "--draw", ""}}) {
    const Result r = run_elan(args);
    EXPECT_EQ(r.status, 2) << args.back();
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  }
}

}  // namespace
}  // namespace elan::test
