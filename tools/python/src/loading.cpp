// SPDX-License-Identifier: MIT
// Worlds from scene files and scene text (README "Scene file"), loaded as `elan run` loads them.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>

#include "elan/defs.hpp"
#include "elan/run_summary.hpp"
#include "elan/scene.hpp"
#include "errors.hpp"
#include "options.hpp"
#include "py_world.hpp"

namespace py = pybind11;

namespace elan::py {

BroadphaseType broadphase_from_name(const std::string& name) {
  if (name == "sap") return BroadphaseType::SweepAndPrune;
  if (name == "all-pairs") return BroadphaseType::AllPairs;
  if (name == "tree") return BroadphaseType::Tree;
  raise("broadphase", "expected 'sap', 'all-pairs' or 'tree', got '" + name + "'");
}

int threads_from(std::optional<int> threads) {
  if (threads && (*threads < 0 || *threads > kMaxThreads)) {
    raise("threads", "must be in 0.." + std::to_string(kMaxThreads) + " (0 = all cores), got " +
                         std::to_string(*threads));
  }
  return resolve_threads(threads.value_or(0));
}

namespace {

// As `elan run` does: the scene's settings, the worker count resolved (the summary reports the
// workers that run), then the bodies and joints in scene order.
std::unique_ptr<PyWorld> from_scene(const Scene& scene, const std::string& name,
                                    std::optional<int> threads, const std::string& broadphase) {
  WorldDef def = scene.world;
  def.threads = threads_from(threads);
  def.broadphase = broadphase_from_name(broadphase);
  World w(def);
  load_into(scene, w, name);
  auto out = std::make_unique<PyWorld>(std::move(w));
  out->timestep = scene.timestep;
  out->scene = name;
  return out;
}

}  // namespace

void bind_loading(pybind11::class_<PyWorld>& c) {
  c.def_static(
      "from_scene_file",
      [](const std::string& path, std::optional<int> threads, const std::string& broadphase) {
        const Scene scene = load_scene(path);
        return from_scene(scene, path, threads, broadphase);
      },
      pybind11::arg("path"), pybind11::arg("threads") = pybind11::none(),
      pybind11::arg("broadphase") = "sap",
      "A world holding the scene file `path` (JSON, README \"Scene file\"; OBJ files it names are "
      "read relative to it), loaded as `elan run` loads it: body i is the scene's body i.\n"
      "threads: worker count (None or 0 = all cores; results are the same for any count).\n"
      "broadphase: 'sap', 'all-pairs' or 'tree' (same results).\n"
      "Raises elan.Error naming the field for an invalid scene.");
  c.def_static(
      "from_scene_json",
      [](const std::string& text, std::optional<std::string> base_dir, std::optional<int> threads,
         const std::string& broadphase) {
        // The name is what messages and summary() show; OBJ paths resolve against its folder.
        const std::string name = base_dir ? *base_dir + "/<string>" : "<string>";
        const Scene scene = parse_scene(text, name);
        return from_scene(scene, name, threads, broadphase);
      },
      pybind11::arg("text"), pybind11::arg("base_dir") = pybind11::none(),
      pybind11::arg("threads") = pybind11::none(), pybind11::arg("broadphase") = "sap",
      "A world holding the scene given as JSON text (README \"Scene file\"). base_dir: the "
      "folder OBJ file names are relative to (default: the working directory). threads and "
      "broadphase as in from_scene_file.");
}

}  // namespace elan::py
