// SPDX-License-Identifier: MIT
// The program recorder (elan/recorder.hpp): recording a world's calls and steps, and replaying
// a recording, with recordings as bytes.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <span>
#include <string>

#include "convert.hpp"
#include "elan/recorder.hpp"
#include "errors.hpp"
#include "options.hpp"
#include "py_world.hpp"

namespace elan::py {

void bind_recording(pybind11::module_& m, pybind11::class_<PyWorld>& c) {
  using pybind11::arg;
  pybind11::register_exception<RecordingError>(m, "RecordingError", PyExc_ValueError);
  c.def(
      "start_recording",
      [](PyWorld& w, uint64_t keyframe_every, const std::string& name) {
        RecordOptions o;
        o.keyframe_every = keyframe_every;
        o.name = name;
        start_recording(w.get(), o);
      },
      pybind11::kw_only(), arg("keyframe_every") = 60, arg("name") = "",
      "Starts recording this world: its state now, then every state-changing call and every "
      "step with its state hash (elan/recorder.hpp). keyframe_every: a full snapshot every K "
      "steps (0: none), for locating a divergence. Restarts a running recording.");
  c.def_property_readonly(
      "is_recording", [](const PyWorld& w) { return is_recording(w.get()); },
      "Whether a recording is running.");
  c.def(
      "save_recording", [](const PyWorld& w) { return to_bytes(save_recording(w.get())); },
      "The recording so far as bytes (it goes on); b'' when not recording.");
  c.def(
      "stop_recording", [](PyWorld& w) { return to_bytes(stop_recording(w.get())); },
      "Stops recording and returns the recording as bytes (`elan replay FILE` plays a file of "
      "them).");
  m.def(
      "replay_recording",
      [](const pybind11::bytes& b, std::optional<int> threads, std::optional<std::string> bp,
         std::optional<uint64_t> until) {
        ReplayOptions o;
        o.threads = threads_from(threads.value_or(1));
        if (bp) o.broadphase = broadphase_from_name(*bp);
        o.until = until;
        const std::string_view s = b;
        ReplayResult r;
        {
          pybind11::gil_scoped_release release;
          r = replay_recording(
              std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(s.data()), s.size()), o);
        }
        pybind11::dict d;
        d["match"] = r.match;
        d["steps"] = r.steps;
        d["mismatch_step"] = r.mismatch_step;
        d["expected"] = r.expected;
        d["actual"] = r.actual;
        d["error"] = r.error;
        d["snapshot"] = to_bytes(r.snapshot);
        return d;
      },
      arg("recording"), pybind11::kw_only(), arg("threads") = 1,
      arg("broadphase") = pybind11::none(), arg("until") = pybind11::none(),
      "Replays a program recording (stop_recording() bytes) from its start, comparing every "
      "step's state hash: a dict with match, steps, mismatch_step, expected and actual "
      "(hashes), error (a recorded call that failed) and snapshot (the world where it stopped, "
      "for World.load_snapshot). Raises elan.RecordingError for a corrupt recording.");
}

}  // namespace elan::py
