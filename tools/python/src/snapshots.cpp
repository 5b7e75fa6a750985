// SPDX-License-Identifier: MIT
// Snapshots as bytes (elan/snapshot.hpp), rollback states, pickle support, world comparison.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <span>
#include <string>

#include "convert.hpp"
#include "elan/run_summary.hpp"
#include "elan/snapshot.hpp"
#include "errors.hpp"
#include "options.hpp"
#include "py_world.hpp"

namespace elan::py {
namespace {

std::span<const uint8_t> view_of(const pybind11::bytes& b) {
  char* data = nullptr;
  pybind11::ssize_t size = 0;
  PyBytes_AsStringAndSize(b.ptr(), &data, &size);
  return {reinterpret_cast<const uint8_t*>(data), std::size_t(size)};
}

// A world from a snapshot with the saved settings, its thread count capped at the cores that
// run here (results do not depend on it).
std::unique_ptr<PyWorld> from_snapshot(const pybind11::bytes& b, std::optional<int> threads) {
  World world = load_snapshot(view_of(b));
  world.set_threads(threads ? threads_from(threads) : resolve_threads(world.settings().threads));
  return std::make_unique<PyWorld>(std::move(world));
}

}  // namespace

void bind_snapshots(pybind11::class_<PyWorld>& c) {
  using pybind11::arg;
  c.def(
      "save_snapshot", [](const PyWorld& w) { return to_bytes(save_snapshot(w.get())); },
      "The whole state as bytes: restoring it and stepping gives the same bits as never having "
      "stopped, for any thread count and broadphase (format: elan/snapshot.hpp).");
  c.def(
      "restore_snapshot",
      [](PyWorld& w, const pybind11::bytes& b) { restore_snapshot(w.get(), view_of(b)); },
      arg("snapshot"),
      "Replaces the whole state with a snapshot's (the thread count and broadphase are kept). "
      "elan.Error 'snapshot' for bytes that are not a valid snapshot (the world is unchanged). "
      "Column views taken before are invalid.");
  c.def_static(
      "load_snapshot",
      [](const pybind11::bytes& b, std::optional<int> threads, double timestep) {
        auto w = from_snapshot(b, threads);
        w->timestep = Real(timestep);
        return w;
      },
      arg("snapshot"), pybind11::kw_only(), arg("threads") = pybind11::none(),
      arg("timestep") = 1.0 / 60.0, "A new world from save_snapshot() bytes.");
  c.def(
      "save_rollback", [](const PyWorld& w) { return to_bytes(save_rollback(w.get())); },
      "What a step changes, as bytes, to put this same world back later (no body created or "
      "destroyed in between).");
  c.def(
      "restore_rollback",
      [](PyWorld& w, const pybind11::bytes& b) { restore_rollback(w.get(), view_of(b)); },
      arg("state"), "Puts the world back into a save_rollback() state (elan.Error 'rollback').");
  c.def(
      "compare",
      [](const PyWorld& a, const PyWorld& b) -> pybind11::object {
        const Divergence d = compare_worlds(a.get(), b.get());
        if (!d.found) return pybind11::none();
        pybind11::dict out;
        out["body"] = d.body;
        out["field"] = d.field;
        out["value"] = d.value_a;
        out["other"] = d.value_b;
        return out;
      },
      arg("other"),
      "The first stored difference from `other`, bit for bit: None, or a dict with the dense "
      "body index, the field ('px' ... 'wz', 'sleep_time', 'flags', 'body_count') and both "
      "values.");
  // pickle: the snapshot plus what the Python object adds (default timestep, name, totals).
  c.def(pybind11::pickle(
      [](const PyWorld& w) {
        return pybind11::make_tuple(to_bytes(save_snapshot(w.get())), double(w.timestep), w.scene,
                                    w.totals.steps, w.totals.status);
      },
      [](const pybind11::tuple& t) {
        if (t.size() != 5) raise("snapshot", "not a pickled elan.World");
        auto w = from_snapshot(t[0].cast<pybind11::bytes>(), std::nullopt);
        w->timestep = Real(t[1].cast<double>());
        w->scene = t[2].cast<std::string>();
        w->totals.steps = t[3].cast<uint64_t>();
        w->totals.status = t[4].cast<uint32_t>();
        return w;
      }));
}

}  // namespace elan::py
