// SPDX-License-Identifier: MIT
// elan::viewer::run: the window and its loop (input, stepping at the chosen speed, drawing, the
// panels), and the off-screen path of --screenshot and --frames. The simulation is stepped with
// the scene's own timestep whatever the frame rate, so its states are those of `elan run`.
#include <imgui.h>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <chrono>
#include <cinttypes>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "tools/viewer/app_state.hpp"
#include "tools/viewer/gl.hpp"
#include "tools/viewer/overlay.hpp"
#include "tools/viewer/panels.hpp"
#include "tools/viewer/renderer.hpp"
#include "tools/viewer/scene_view.hpp"
#include "tools/viewer/screenshot.hpp"
#include "tools/viewer/viewer.hpp"

namespace elan::viewer {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

std::string g_glfw_error;
volatile std::sig_atomic_t g_quit = 0;

void on_glfw_error(int, const char* description) {
  g_glfw_error = description;
}
void on_signal(int) {
  g_quit = 1;
}

std::string hex(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
  return buf;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// One line on stderr, exit status 2.
int fail(const std::string& message) {
  std::fprintf(stderr, "elan: view: %s\n", one_line(message).c_str());
  return 2;
}

// GLFW for the lifetime of a run.
struct GlfwSession {
  bool ok = false;
  GlfwSession() {
    glfwSetErrorCallback(on_glfw_error);
    ok = glfwInit() == GLFW_TRUE;
  }
  ~GlfwSession() {
    if (ok) glfwTerminate();
  }
};

// `samples`: multisampling of a visible window's framebuffer (off screen the target has its own).
GLFWwindow* open_window(int width, int height, bool visible, const std::string& title,
                        int samples = 0) {
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_SAMPLES, visible ? samples : 0);
  GLFWwindow* w = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (w != nullptr) glfwMakeContextCurrent(w);
  return w;
}

// Whether the current context renders in software (Mesa's llvmpipe, softpipe or swrast).
bool is_software_renderer() {
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (name == nullptr) return false;
  const std::string r(name);
  for (const char* soft : {"llvmpipe", "softpipe", "swrast"}) {
    if (r.find(soft) != std::string::npos) return true;
  }
  return false;
}

// The default view: every non-static body's bounding box (all bodies' when every body is
// static), seen from the default yaw and pitch.
void frame_bodies(Camera& camera, const Simulation& sim, float aspect) {
  const World& world = sim.world();
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f), hi = -lo;
  for (bool statics : {false, true}) {
    for (std::size_t i = 0; i < world.body_count(); ++i) {
      const BodyId id = world.body_at(i);
      if ((world.motion_type(id) == MotionType::Static) != statics) continue;
      // A plane is unbounded: it cannot be framed.
      const float r = bounding_radius(sim.body_shape(i));
      if (!(r < 1e4f)) continue;
      const Aabb b = world.bounds(id);
      lo = lo.cwiseMin(b.lo.cast<float>());
      hi = hi.cwiseMax(b.hi.cast<float>());
    }
    if (lo.x() <= hi.x()) break;
  }
  if (!(lo.x() <= hi.x())) lo = hi = Eigen::Vector3f::Zero();
  camera.yaw = 0.6f;
  camera.pitch = 0.4f;
  camera.frame(lo, hi, aspect);
}

void place_camera(Camera& camera, const cli::ViewOptions& o, const Simulation& sim, float aspect) {
  if (o.has_camera) {
    camera.look_at({float(o.camera[0]), float(o.camera[1]), float(o.camera[2])},
                   {float(o.camera[3]), float(o.camera[4]), float(o.camera[5])});
  } else {
    frame_bodies(camera, sim, aspect);
  }
}

Json camera_json(const Camera& c) {
  const Eigen::Vector3f e = c.eye();
  return Json::array({e.x(), e.y(), e.z(), c.target.x(), c.target.y(), c.target.z()});
}

DetailView detail_view(const Camera& camera, int height) {
  return {camera.eye(), float(height) / 2 / std::tan(camera.fov_y / 2)};
}

// Moves to the requested step: stepping a scene, seeking a recording.
void go_to(Simulation& sim, Timeline* timeline, uint64_t step) {
  if (timeline != nullptr) {
    timeline->seek(sim, step);
    // Off screen, a recorded call that fails on replay ends the run as `elan replay` would.
    if (!timeline->error().empty()) throw cli::RecordingError(timeline->error());
    return;
  }
  while (sim.step_count() < step) sim.step();
}

int headless(const cli::ViewOptions& o, Simulation& sim, Timeline* timeline) {
  GLFWwindow* window = open_window(o.width, o.height, false, "elan view");
  if (window == nullptr) return fail("no OpenGL 3.3 core context: " + g_glfw_error);
  Renderer renderer;
  std::string error;
  OffscreenTarget target;
  if (!renderer.init(error) || !target.create(o.width, o.height, 4, error)) return fail(error);
  SceneView view;
  Camera camera;
  const float aspect = float(o.width) / float(o.height);
  std::optional<std::size_t> highlight;
  if (o.body) highlight = std::size_t(*o.body);
  const uint64_t last = timeline != nullptr ? o.step.value_or(o.steps) : o.steps;

  double render_seconds = 0;
  std::size_t pictures = 0;
  double step_seconds = 0;
  const auto render = [&](const std::string& path) {
    const auto t0 = Clock::now();
    const DetailView detail = detail_view(camera, o.height);
    view.update(sim, renderer, std::nullopt, highlight, o.draw, &detail);
    draw_overlays(sim.world(), o.draw, renderer);
    target.bind();
    renderer.draw(camera.projection(aspect) * camera.view(), camera.eye(), o.width, o.height);
    const std::vector<uint8_t> rgb = target.read_rgb();
    render_seconds += seconds_since(t0);
    ++pictures;
    return write_png(path, o.width, o.height, rgb, error);
  };

  Json out;
  out["scene"] = sim.source().name;
  if (!o.frames.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.frames, ec);
    if (ec) return fail(o.frames + ": cannot create the directory: " + ec.message());
    place_camera(camera, o, sim, aspect);
    for (uint64_t step = sim.step_count();; ++step) {
      const auto t0 = Clock::now();
      go_to(sim, timeline, step);
      step_seconds += seconds_since(t0);
      if (step % o.every == 0) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05zu.png", pictures);
        if (!render((std::filesystem::path(o.frames) / name).string())) return fail(error);
      }
      if (step >= last) break;
    }
    out["frames"] = pictures;
    out["directory"] = o.frames;
  } else {
    const auto t0 = Clock::now();
    go_to(sim, timeline, last);
    step_seconds += seconds_since(t0);
    place_camera(camera, o, sim, aspect);
    if (!render(o.screenshot)) return fail(error);
    out["screenshot"] = o.screenshot;
  }
  glfwDestroyWindow(window);
  out["steps"] = sim.step_count();
  out["state_hash"] = hex(sim.world().state_hash());
  out["width"] = o.width;
  out["height"] = o.height;
  out["camera"] = camera_json(camera);
  out["ms_per_step"] = sim.step_count() == 0 ? 0.0 : 1000 * step_seconds / double(sim.step_count());
  out["ms_per_picture"] = pictures == 0 ? 0.0 : 1000 * render_seconds / double(pictures);
  std::printf("%s\n", out.dump(-1, ' ', false, Json::error_handler_t::replace).c_str());
  return 0;
}

void on_scroll(GLFWwindow* window, double, double dy) {
  auto* app = static_cast<AppState*>(glfwGetWindowUserPointer(window));
  if (app != nullptr && !ImGui::GetIO().WantCaptureMouse) app->camera.zoom(float(dy));
}

// Replaces the simulation with the scene file `path`; errors go to the panel.
void open_scene(AppState& app, const std::string& path) {
  try {
    Source source;
    source.name = path;
    source.scene = load_scene(path);
    source.def = source.scene.world;
    source.def.threads = app.sim->world().settings().threads;
    source.timestep = source.scene.timestep;
    World world(source.def);
    load_into(source.scene, world, path);
    app.timeline.reset();
    app.sim = std::make_unique<Simulation>(std::move(source), std::move(world));
    app.selected.reset();
    app.highlighted.reset();
    app.dragger.end();
    app.drag_stiffness = drag_stiffness(app.sim->world());
    app.frame_request = true;
    app.message.clear();
  } catch (const std::exception& e) {
    app.message = one_line(e.what());
  }
}

void handle_input(AppState& app, GLFWwindow* window, int width, int height) {
  ImGuiIO& io = ImGui::GetIO();
  static double last_x = 0, last_y = 0;
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  // Cursor positions are in window coordinates; the framebuffer may be larger (HiDPI).
  int ww = 1, wh = 1;
  glfwGetWindowSize(window, &ww, &wh);
  const double sx = double(width) / std::max(ww, 1), sy = double(height) / std::max(wh, 1);
  const float dx = float(x - last_x), dy = float(y - last_y);
  last_x = x;
  last_y = y;
  const PixelRay ray = app.camera.ray(x * sx, y * sy, width, height);
  const bool replay = app.timeline != nullptr;

  if (!io.WantCaptureMouse) {
    const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !shift) {
      const std::optional<PickHit> hit = pick(app.sim->world(), ray);
      if (hit) {
        app.selected = hit->body;
        if (!replay) app.dragger.begin(app.sim->world(), *hit, app.camera);
      } else {
        app.selected.reset();
      }
    }
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left) && !app.dragger.active()) {
      if (shift) {
        app.camera.pan(dx, dy, height / std::max(1, int(sy)));
      } else if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0)) {
        app.camera.orbit(dx, dy);
      }
    }
    if (ImGui::IsMouseDown(ImGuiMouseButton_Right) || ImGui::IsMouseDown(ImGuiMouseButton_Middle)) {
      app.camera.pan(dx, dy, wh);
    }
  }
  if (app.dragger.active()) {
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      app.dragger.move(ray);
    } else {
      app.dragger.end();
    }
  }
  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_SPACE)) app.paused = !app.paused;
    if (ImGui::IsKeyPressed(GLFW_KEY_N)) app.step_once = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_R)) app.reset_request = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_F)) app.frame_request = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_B) && !replay) app.shoot_request = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_C) && app.selected) app.follow = !app.follow;
    if (ImGui::IsKeyPressed(GLFW_KEY_H)) app.show_panels = !app.show_panels;
    if (ImGui::IsKeyPressed(GLFW_KEY_S, false)) app.speed = app.speed < 1 ? 1.0f : 0.25f;
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window, GLFW_TRUE);
  }
  if (app.shoot_request) {
    app.shoot_request = false;
    app.sim->shoot(ray.origin.cast<Real>(), ray.direction.cast<Real>(), Real(0.25), Real(30));
  }
}

// Steps due this frame: simulated time advances by the wall time times the speed, in steps of
// the scene's timestep, at most four a frame (a slow frame slows the simulation down rather
// than piling up steps).
void advance(AppState& app, double frame_seconds, double& owed, double& step_seconds,
             uint64_t& steps_taken) {
  const double dt = double(app.sim->timestep());
  int due = 0;
  if (app.step_once) {
    due = 1;
    app.step_once = false;
    owed = 0;
  } else if (!app.paused) {
    owed += frame_seconds * double(app.speed);
    due = int(std::min(owed / dt, 4.0));
    owed = due == 4 ? 0 : owed - due * dt;
  }
  for (int k = 0; k < due; ++k) {
    if (app.timeline && app.sim->step_count() >= app.timeline->length()) {
      app.paused = true;
      break;
    }
    const auto t0 = Clock::now();
    app.dragger.apply(app.sim->world(), app.drag_stiffness);
    if (app.timeline) {
      app.timeline->advance(*app.sim);
      if (!app.timeline->error().empty()) app.paused = true;
    } else {
      app.sim->step();
    }
    const double s = seconds_since(t0);
    step_seconds += s;
    ++steps_taken;
    app.step_ms.push(float(app.sim->world().last_step().profile.total));
    app.kinetic_energy.push(float(app.sim->world().kinetic_energy()));
  }
}

int interactive(const cli::ViewOptions& o, AppState& app) {
  const std::string title = "elan view - " + app.sim->source().name;
  GLFWwindow* window = open_window(o.width, o.height, true, title, 4);
  if (window == nullptr) return fail("no OpenGL 3.3 core context: " + g_glfw_error);
  // A software renderer (Mesa's llvmpipe under Xvfb) spends more than half a frame of a large
  // pile on 4x multisampling: the window is opened again without it.
  if (is_software_renderer()) {
    glfwDestroyWindow(window);
    window = open_window(o.width, o.height, true, title, 0);
    if (window == nullptr) return fail("no OpenGL 3.3 core context: " + g_glfw_error);
  }
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(window, &app);
  glfwSetScrollCallback(window, on_scroll);  // before ImGui's, which chains to it
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  Renderer renderer;
  std::string error;
  if (!renderer.init(error)) return fail(error);
  SceneView view;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  int width = 0, height = 0;
  glfwGetFramebufferSize(window, &width, &height);
  place_camera(app.camera, o, *app.sim, float(width) / float(std::max(height, 1)));
  double owed = 0, step_seconds = 0;
  uint64_t steps_taken = 0, frames = 0;
  const auto start = Clock::now();
  auto last = start;
  while (!glfwWindowShouldClose(window) && !g_quit) {
    glfwPollEvents();
    glfwGetFramebufferSize(window, &width, &height);
    if (width <= 0 || height <= 0) continue;  // minimised
    const float aspect = float(width) / float(height);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handle_input(app, window, width, height);
    draw_panels(app);
    if (!app.open_request.empty()) {
      open_scene(app, app.open_request);
      app.open_request.clear();
    }
    if (app.reset_request) {
      app.reset_request = false;
      app.dragger.end();
      if (app.timeline) {
        app.timeline->seek(*app.sim, 0);
      } else {
        app.sim->reset();
      }
    }
    const double frame_seconds = seconds_since(last);
    last = Clock::now();
    app.frame_ms = 0.9 * app.frame_ms + 0.1 * 1000 * frame_seconds;
    advance(app, frame_seconds, owed, step_seconds, steps_taken);
    if (app.frame_request) {
      app.frame_request = false;
      frame_bodies(app.camera, *app.sim, aspect);
    }
    if (app.follow && app.selected && *app.selected < app.sim->world().body_count()) {
      app.camera.target =
          app.sim->world().position(app.sim->world().body_at(*app.selected)).cast<float>();
    }

    const DetailView detail = detail_view(app.camera, height);
    view.update(*app.sim, renderer, app.selected, app.highlighted, app.overlays, &detail);
    draw_overlays(app.sim->world(), app.overlays, renderer);
    if (app.dragger.active()) {
      renderer.add_line(app.dragger.grab_point(app.sim->world()).cast<float>(),
                        app.dragger.target().cast<float>(), {1, 1, 1, 1});
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    renderer.draw(app.camera.projection(aspect) * app.camera.view(), app.camera.eye(), width,
                  height);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glfwSwapBuffers(window);
    ++frames;
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);

  // A summary as the off-screen path prints one: what a session did, and how fast.
  const double wall = seconds_since(start);
  Json out;
  out["scene"] = app.sim->source().name;
  out["steps"] = app.sim->step_count();
  out["state_hash"] = hex(app.sim->world().state_hash());
  out["frames"] = frames;
  out["frames_per_second"] = wall > 0 ? double(frames) / wall : 0.0;
  out["ms_per_step"] = steps_taken == 0 ? 0.0 : 1000 * step_seconds / double(steps_taken);
  std::printf("%s\n", out.dump(-1, ' ', false, Json::error_handler_t::replace).c_str());
  return 0;
}

}  // namespace

int run(const cli::ViewOptions& o, Source source, World world) {
  // The display is checked before any stepping, so that a missing one fails at once.
  GlfwSession glfw;
  if (!glfw.ok) {
    return fail("no display (" + g_glfw_error +
                "); to render off screen without a screen, run it under 'xvfb-run -a'");
  }
  AppState app;
  app.sim = std::make_unique<Simulation>(std::move(source), std::move(world));
  if (app.sim->source().recording)
    app.timeline = std::make_unique<Timeline>(*app.sim->source().recording);
  if (!o.screenshot.empty() || !o.frames.empty()) return headless(o, *app.sim, app.timeline.get());

  app.paused = o.paused;
  app.overlays = o.draw;
  app.drag_stiffness = drag_stiffness(app.sim->world());
  if (o.body) {
    app.highlighted = std::size_t(*o.body);
    app.selected = app.highlighted;
  }
  go_to(*app.sim, app.timeline.get(), app.timeline ? o.step.value_or(o.steps) : o.steps);
  if (o.step) app.paused = true;
  return interactive(o, app);
}

}  // namespace elan::viewer
