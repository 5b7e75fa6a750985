// SPDX-License-Identifier: MIT
#include "tools/viewer/panels.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cinttypes>
#include <filesystem>
#include <thread>
#include <vector>

#include "elan/debug_draw.hpp"
#include "elan/limits.hpp"

namespace elan::viewer {
namespace {

const char* motion_name(MotionType m) {
  return m == MotionType::Static ? "static" : m == MotionType::Kinematic ? "kinematic" : "dynamic";
}

const char* shape_name(ShapeType t) {
  switch (t) {
    case ShapeType::Sphere:
      return "sphere";
    case ShapeType::Box:
      return "box";
    case ShapeType::Capsule:
      return "capsule";
    case ShapeType::Cylinder:
      return "cylinder";
    case ShapeType::ConvexHull:
      return "convex hull";
    case ShapeType::Plane:
      return "plane";
    case ShapeType::Mesh:
      return "mesh";
    case ShapeType::Heightfield:
      return "heightfield";
    case ShapeType::Compound:
      return "compound";
  }
  return "?";
}

// The scene files beside the open one (and in ./scenes), sorted.
std::vector<std::string> scene_files(const std::string& current) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  std::error_code ec;
  for (const fs::path& dir : {fs::path(current).parent_path(), fs::path("scenes")}) {
    if (dir.empty() || !fs::is_directory(dir, ec)) continue;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      if (e.path().extension() == ".json") out.push_back(e.path().string());
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void controls(AppState& app) {
  Simulation& sim = *app.sim;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Simulation");
  ImGui::TextWrapped("%s", sim.source().name.c_str());
  ImGui::Text("step %" PRIu64 "   t = %.2f s", sim.step_count(),
              double(sim.step_count()) * double(sim.timestep()));
  if (ImGui::Button(app.paused ? "Play (Space)" : "Pause (Space)")) app.paused = !app.paused;
  ImGui::SameLine();
  if (ImGui::Button("Step (N)")) app.step_once = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset (R)")) app.reset_request = true;
  ImGui::SliderFloat("speed", &app.speed, 0.05f, 1.0f, "%.2fx");
  const bool replay = app.timeline != nullptr;
  if (!replay) {
    if (ImGui::Button("Shoot ball (B)")) app.shoot_request = true;
    ImGui::SameLine();
  }
  if (ImGui::Button("Frame all (F)")) app.frame_request = true;

  if (!replay && ImGui::CollapsingHeader("World", ImGuiTreeNodeFlags_DefaultOpen)) {
    // The panel edits a copy of the world's settings; apply_settings changes what differs.
    LiveSettings live = sim.settings();
    bool changed = false;
    float g[3] = {float(live.gravity.x()), float(live.gravity.y()), float(live.gravity.z())};
    if (ImGui::DragFloat3("gravity", g, 0.1f, -100.0f, 100.0f, "%.2f")) {
      live.gravity = Vec3(Real(g[0]), Real(g[1]), Real(g[2]));
      changed = true;
    }
    changed |= ImGui::Checkbox("sleeping", &live.sleeping);
    changed |= ImGui::SliderInt("substeps", &live.substeps, 1, 16);
    changed |= ImGui::SliderInt("iterations", &live.iterations, 1, 16);
    changed |= ImGui::SliderInt("threads", &live.threads, 1,
                                std::max(1, int(std::thread::hardware_concurrency())));
    if (changed) {
      try {
        sim.apply(live);
      } catch (const std::exception& e) {
        app.message = e.what();
      }
    }
    static std::vector<std::string> files;
    if (ImGui::BeginCombo("open scene", nullptr, ImGuiComboFlags_NoPreview)) {
      if (files.empty()) files = scene_files(sim.source().name);
      for (const std::string& f : files) {
        if (ImGui::Selectable(f.c_str())) app.open_request = f;
      }
      ImGui::EndCombo();
    } else {
      files.clear();
    }
  }
  if (ImGui::CollapsingHeader("Overlays")) {
    ImGui::CheckboxFlags("bounds", &app.overlays, kDrawBounds);
    ImGui::CheckboxFlags("contacts", &app.overlays, kDrawContacts);
    ImGui::CheckboxFlags("joints (anchors)", &app.overlays, kDrawJoints);
    ImGui::CheckboxFlags("centres of mass", &app.overlays, kDrawCentersOfMass);
    ImGui::CheckboxFlags("islands (colours)", &app.overlays, kDrawIslands);
    ImGui::CheckboxFlags("solver halves (colours, cut)", &app.overlays, kDrawSolverHalves);
  }
  if (!app.message.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", app.message.c_str());
  ImGui::End();
}

void statistics(AppState& app) {
  const World& world = app.sim->world();
  const StepStats& s = world.last_step();
  ImGui::SetNextWindowPos(ImVec2(10, 430), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Statistics");
  ImGui::Text("bodies %zu   awake %zu   joints %zu", world.body_count(), s.awake,
              world.joint_count());
  ImGui::Text("pairs %zu   manifolds %zu   contacts %zu", s.pairs, s.manifolds, s.contacts);
  ImGui::Text("frame %.1f ms (%.0f fps)", app.frame_ms, app.frame_ms > 0 ? 1000 / app.frame_ms : 0);
  if (!app.step_ms.values.empty()) {
    ImGui::PlotLines("step ms", app.step_ms.values.data(), int(app.step_ms.values.size()), 0,
                     nullptr, 0.0f, FLT_MAX, ImVec2(0, 50));
  }
  if (!app.kinetic_energy.values.empty()) {
    ImGui::PlotLines("kinetic J", app.kinetic_energy.values.data(),
                     int(app.kinetic_energy.values.size()), 0, nullptr, 0.0f, FLT_MAX,
                     ImVec2(0, 50));
  }
  if (ImGui::BeginTable("stages", 2)) {
    const StepProfile& p = s.profile;
    const std::pair<const char*, double> rows[] = {
        {"bounds", p.bounds},   {"pairs", p.pairs},     {"collide", p.collide},
        {"islands", p.islands}, {"split", p.split},     {"packets", p.packets},
        {"color", p.color},     {"bundles", p.bundles}, {"prepare", p.prepare},
        {"solve", p.solve},     {"ccd", p.ccd},         {"finalize", p.finalize},
        {"total", p.total}};
    for (const auto& [name, ms] : rows) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(name);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f ms", ms);
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

void inspector(AppState& app) {
  if (!app.selected) return;
  const World& world = app.sim->world();
  if (*app.selected >= world.body_count()) {
    app.selected.reset();
    return;
  }
  const std::size_t i = *app.selected;
  const BodyId id = world.body_at(i);
  ImGui::SetNextWindowPos(ImVec2(350, 10), ImGuiCond_FirstUseEver);
  ImGui::Begin("Body");
  const auto& bodies = app.sim->source().scene.bodies;
  const std::string name = i < bodies.size() ? bodies[i].name : std::string("(shot ball)");
  ImGui::Text("body %zu  %s", i, name.c_str());
  ImGui::Text("%s %s, %s", motion_name(world.motion_type(id)),
              shape_name(app.sim->body_shape(i).type), world.is_awake(id) ? "awake" : "asleep");
  ImGui::Text("mass %.4g kg", double(world.mass(id)));
  const Vec3 p = world.position(id), v = world.linear_velocity(id), w = world.angular_velocity(id);
  ImGui::Text("position  %.3f %.3f %.3f m", double(p.x()), double(p.y()), double(p.z()));
  ImGui::Text("velocity  %.3f %.3f %.3f m/s", double(v.x()), double(v.y()), double(v.z()));
  ImGui::Text("angular   %.3f %.3f %.3f rad/s", double(w.x()), double(w.y()), double(w.z()));
  ImGui::Checkbox("follow (C)", &app.follow);
  ImGui::End();
}

void timeline(AppState& app) {
  if (!app.timeline) return;
  Timeline& t = *app.timeline;
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + 350, vp->Pos.y + vp->Size.y - 90),
                          ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(vp->Size.x - 360, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Timeline");
  int step = int(app.sim->step_count());
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderInt("##step", &step, 0, int(t.length()))) {
    t.seek(*app.sim, uint64_t(step));
    app.paused = true;
  }
  if (ImGui::Button("<"))
    t.seek(*app.sim, app.sim->step_count() > 0 ? app.sim->step_count() - 1 : 0);
  ImGui::SameLine();
  if (ImGui::Button(">")) t.seek(*app.sim, app.sim->step_count() + 1);
  ImGui::SameLine();
  if (t.matches(*app.sim)) {
    ImGui::TextColored(ImVec4(0.4f, 1, 0.4f, 1), "hash matches the recording");
  } else {
    ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "hash differs from the recording");
  }
  if (t.first_mismatch()) {
    ImGui::SameLine();
    ImGui::Text("(first difference at step %" PRIu64 ")", *t.first_mismatch());
  }
  if (!t.error().empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", t.error().c_str());
  ImGui::End();
}

}  // namespace

void draw_panels(AppState& app) {
  if (!app.show_panels) return;
  controls(app);
  statistics(app);
  inspector(app);
  timeline(app);
}

}  // namespace elan::viewer
