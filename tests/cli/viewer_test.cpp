// SPDX-License-Identifier: MIT
// Tests of `elan view`: pictures rendered off screen (--screenshot) under a display (Xvfb with
// Mesa's software renderer in the test script), checked pixel by pixel, the viewer's state hash
// against `elan run`'s, and the errors that come before any window. Skipped when no display is
// set (the script runs them under `xvfb-run -a`).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
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
                                               {"view", "x.json", "--every", "2"}}) {
    const Result r = run_elan(args);
    EXPECT_EQ(r.status, 2) << args.back();
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  }
}

}  // namespace
}  // namespace elan::test
