// SPDX-License-Identifier: MIT
// The last step's events as NumPy structured arrays (one record per event, ids as int64, -1 for
// none), and the current contact manifolds.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

#include "convert.hpp"
#include "py_world.hpp"

namespace elan::py {
namespace {

struct BeginRecord {
  int64_t body_a, body_b;
  Real point[3], normal[3];
  Real normal_impulse;
};
struct PairRecord {
  int64_t a, b;
};
struct HitRecord {
  int64_t body_a, body_b;
  Real point[3], normal[3];
  Real approach_speed;
};
struct JointRemovedRecord {
  int64_t joint, body_a, body_b;
  uint8_t broke;
  Real force;
};

template <class Record>
pybind11::array records(const std::vector<Field>& fields, const std::vector<Record>& rows_) {
  pybind11::array out(record_dtype(fields, sizeof(Record)),
                      pybind11::array::ShapeContainer{pybind11::ssize_t(rows_.size())});
  if (!rows_.empty()) std::memcpy(out.mutable_data(), rows_.data(), rows_.size() * sizeof(Record));
  return out;
}

void put(Real* out, const Vec3& v) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

template <class Event>
pybind11::array pairs(std::span<const Event> events, const char* a, const char* b,
                      BodyId Event::*first, BodyId Event::*second) {
  std::vector<PairRecord> rows_;
  for (const Event& e : events) rows_.push_back({to_array_int(e.*first), to_array_int(e.*second)});
  return records({{a, offsetof(PairRecord, a), "<i8"}, {b, offsetof(PairRecord, b), "<i8"}}, rows_);
}

}  // namespace

void bind_events(pybind11::class_<PyWorld>& c) {
  c.def(
      "contact_begin_events",
      [](const PyWorld& w) {
        std::vector<BeginRecord> rows_;
        for (const ContactBeginEvent& e : w.get().contact_begin_events()) {
          BeginRecord r{to_array_int(e.body_a), to_array_int(e.body_b), {}, {}, e.normal_impulse};
          put(r.point, e.point);
          put(r.normal, e.normal);
          rows_.push_back(r);
        }
        return records({{"body_a", offsetof(BeginRecord, body_a), "<i8"},
                        {"body_b", offsetof(BeginRecord, body_b), "<i8"},
                        {"point", offsetof(BeginRecord, point), real3_format()},
                        {"normal", offsetof(BeginRecord, normal), real3_format()},
                        {"normal_impulse", offsetof(BeginRecord, normal_impulse), real_format()}},
                       rows_);
      },
      "Contacts that began in the last step: structured array with body_a, body_b (int64), "
      "point (m, world), normal (unit, from a to b), normal_impulse (N s).");
  c.def(
      "contact_end_events",
      [](const PyWorld& w) {
        return pairs(w.get().contact_end_events(), "body_a", "body_b", &ContactEndEvent::body_a,
                     &ContactEndEvent::body_b);
      },
      "Contacts that ended in the last step (or by destroy_body since): body_a, body_b.");
  c.def(
      "contact_hit_events",
      [](const PyWorld& w) {
        std::vector<HitRecord> rows_;
        for (const ContactHitEvent& e : w.get().contact_hit_events()) {
          HitRecord r{to_array_int(e.body_a), to_array_int(e.body_b), {}, {}, e.approach_speed};
          put(r.point, e.point);
          put(r.normal, e.normal);
          rows_.push_back(r);
        }
        return records({{"body_a", offsetof(HitRecord, body_a), "<i8"},
                        {"body_b", offsetof(HitRecord, body_b), "<i8"},
                        {"point", offsetof(HitRecord, point), real3_format()},
                        {"normal", offsetof(HitRecord, normal), real3_format()},
                        {"approach_speed", offsetof(HitRecord, approach_speed), real_format()}},
                       rows_);
      },
      "Contacts that began in the last step at least as fast as the hit threshold: body_a, "
      "body_b, point (m), normal, approach_speed (m/s).");
  c.def(
      "sensor_begin_events",
      [](const PyWorld& w) {
        return pairs(w.get().sensor_begin_events(), "sensor", "visitor", &SensorBeginEvent::sensor,
                     &SensorBeginEvent::visitor);
      },
      "Bodies that began overlapping a sensor in the last step: sensor, visitor.");
  c.def(
      "sensor_end_events",
      [](const PyWorld& w) {
        return pairs(w.get().sensor_end_events(), "sensor", "visitor", &SensorEndEvent::sensor,
                     &SensorEndEvent::visitor);
      },
      "Bodies that stopped overlapping a sensor: sensor, visitor.");
  c.def(
      "joint_removed_events",
      [](const PyWorld& w) {
        std::vector<JointRemovedRecord> rows_;
        for (const JointRemovedEvent& e : w.get().joint_removed_events()) {
          rows_.push_back({int64_t(to_int(e.joint)), to_array_int(e.body_a), to_array_int(e.body_b),
                           uint8_t(e.reason == JointRemoval::Broke), e.force});
        }
        return records({{"joint", offsetof(JointRemovedRecord, joint), "<i8"},
                        {"body_a", offsetof(JointRemovedRecord, body_a), "<i8"},
                        {"body_b", offsetof(JointRemovedRecord, body_b), "<i8"},
                        {"broke", offsetof(JointRemovedRecord, broke), "?"},
                        {"force", offsetof(JointRemovedRecord, force), real_format()}},
                       rows_);
      },
      "Joints that broke in the last step (broke=True, force in N) or left with a destroyed "
      "body: joint, body_a, body_b (-1: the world), broke, force.");
  c.def(
      "contacts",
      [](const PyWorld& w) {
        const World& world = w.get();
        pybind11::list out;
        for (std::size_t i = 0; i < world.contact_count(); ++i) {
          const ContactView v = world.contact(i);
          pybind11::list points;
          for (int k = 0; k < v.point_count; ++k) {
            const ContactPointView& p = v.points[k];
            pybind11::dict d;
            d["point"] = tuple3(p.point);
            d["separation"] = double(p.separation);
            d["normal_impulse"] = double(p.normal_impulse);
            d["tangent_impulse"] = double(p.tangent_impulse);
            points.append(d);
          }
          pybind11::dict m;
          m["body_a"] = to_int(v.body_a);
          m["body_b"] = to_int(v.body_b);
          m["normal"] = tuple3(v.normal);
          m["points"] = points;
          out.append(m);
        }
        return out;
      },
      "The current contact manifolds, in pair order: dicts with body_a, body_b, normal and "
      "points (point m, separation m, normal_impulse and tangent_impulse N s).");
}

}  // namespace elan::py
