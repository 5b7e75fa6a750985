// SPDX-License-Identifier: MIT
// Ray and shape casts, overlaps, closest points, the character mover, and batched rays over
// NumPy arrays (cast in parallel on the world's pool, without the GIL).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include "convert.hpp"
#include "errors.hpp"
#include "py_world.hpp"

namespace elan::py {
namespace {

constexpr uint32_t kAll = 0xFFFFFFFFu;

pybind11::object ray_hit(const std::optional<RayHit>& h) {
  if (!h) return pybind11::none();
  pybind11::dict d;
  d["body"] = to_int(h->body);
  d["distance"] = double(h->distance);
  d["point"] = tuple3(h->point);
  d["normal"] = tuple3(h->normal);
  return d;
}

pybind11::dict shape_hit(const ShapeCastHit& h) {
  pybind11::dict d;
  d["body"] = to_int(h.body);
  d["fraction"] = double(h.fraction);
  d["point"] = tuple3(h.point);
  d["normal"] = tuple3(h.normal);
  return d;
}

pybind11::dict point_hit(const PointHit& h) {
  pybind11::dict d;
  d["body"] = to_int(h.body);
  d["point"] = tuple3(h.point);
  d["distance"] = double(h.distance);
  d["normal"] = tuple3(h.normal);
  return d;
}

pybind11::array_t<uint64_t> id_array(const std::vector<BodyId>& ids) {
  pybind11::array_t<uint64_t> out(pybind11::ssize_t(ids.size()));
  for (std::size_t i = 0; i < ids.size(); ++i) out.mutable_data()[i] = to_int(ids[i]);
  return out;
}

struct RayRecord {
  int64_t body;
  Real distance;
  Real point[3], normal[3];
};

}  // namespace

void bind_queries(pybind11::class_<PyWorld>& c) {
  using pybind11::arg;
  const double inf = std::numeric_limits<double>::infinity();
  c.def(
      "cast_ray",
      [](const PyWorld& w, V3 origin, V3 direction, double max_distance, uint32_t category_bits,
         uint32_t mask_bits, bool include_sensors, bool any) {
        const QueryFilter f = filter(category_bits, mask_bits, include_sensors);
        const World& world = w.get();
        return ray_hit(
            any ? world.cast_ray_any(vec3(origin), vec3(direction), Real(max_distance), f)
                : world.cast_ray(vec3(origin), vec3(direction), Real(max_distance), f));
      },
      arg("origin"), arg("direction"), arg("max_distance") = inf, pybind11::kw_only(),
      arg("category_bits") = kAll, arg("mask_bits") = kAll, arg("include_sensors") = false,
      arg("any") = false,
      "The closest body the ray from origin (m) along direction (any non-zero length) enters "
      "within max_distance (m): None or a dict with body, distance (m), point (m), normal. "
      "any=True: some hit (cheaper; line of sight). Filter: a body passes when (its category & "
      "mask_bits) and (its mask & category_bits) are non-zero.");
  c.def(
      "cast_ray_all",
      [](const PyWorld& w, V3 origin, V3 direction, double max_distance, uint32_t category_bits,
         uint32_t mask_bits, bool include_sensors) {
        std::vector<RayHit> hits;
        w.get().cast_ray_all(vec3(origin), vec3(direction), Real(max_distance), hits,
                             filter(category_bits, mask_bits, include_sensors));
        pybind11::list out;
        for (const RayHit& h : hits) out.append(ray_hit(h));
        return out;
      },
      arg("origin"), arg("direction"), arg("max_distance") = inf, pybind11::kw_only(),
      arg("category_bits") = kAll, arg("mask_bits") = kAll, arg("include_sensors") = false,
      "Every body the ray enters, sorted by distance: a list of dicts as cast_ray's.");
  c.def(
      "cast_rays",
      [](const PyWorld& w, pybind11::handle origins, pybind11::handle directions,
         pybind11::object max_distance, uint32_t category_bits, uint32_t mask_bits,
         bool include_sensors) {
        const World& world = w.get();
        const std::vector<Vec3> o = vec3_rows(origins, "origins");
        const std::vector<Vec3> d = vec3_rows(directions, "directions");
        if (d.size() != o.size()) raise("directions", "must have as many rows as origins");
        std::vector<Ray> rays(o.size());
        if (max_distance.is_none()) {
          for (std::size_t i = 0; i < rays.size(); ++i) rays[i] = Ray{o[i], d[i], Real(1e30f)};
        } else if (pybind11::isinstance<pybind11::float_>(max_distance) ||
                   pybind11::isinstance<pybind11::int_>(max_distance)) {
          const Real m = Real(max_distance.cast<double>());
          for (std::size_t i = 0; i < rays.size(); ++i) rays[i] = Ray{o[i], d[i], m};
        } else {
          const auto m = rows(max_distance, 0, "max_distance");
          if (std::size_t(m.shape(0)) != rays.size()) {
            raise("max_distance", "must have one value per ray");
          }
          for (std::size_t i = 0; i < rays.size(); ++i) rays[i] = Ray{o[i], d[i], Real(m.at(i))};
        }
        std::vector<RayHit> hits(rays.size());
        const QueryFilter f = filter(category_bits, mask_bits, include_sensors);
        {
          pybind11::gil_scoped_release release;
          world.cast_rays(rays, hits, f);
        }
        std::vector<RayRecord> records(hits.size());
        for (std::size_t i = 0; i < hits.size(); ++i) {
          const RayHit& h = hits[i];
          RayRecord& r = records[i];
          r.body = to_array_int(h.body);
          r.distance = h.body.is_null() ? std::numeric_limits<Real>::infinity() : h.distance;
          for (int k = 0; k < 3; ++k) {
            r.point[k] = h.point[k];
            r.normal[k] = h.normal[k];
          }
        }
        pybind11::array out(
            record_dtype({{"body", offsetof(RayRecord, body), "<i8"},
                          {"distance", offsetof(RayRecord, distance), real_format()},
                          {"point", offsetof(RayRecord, point), real3_format()},
                          {"normal", offsetof(RayRecord, normal), real3_format()}},
                         sizeof(RayRecord)),
            pybind11::array::ShapeContainer{pybind11::ssize_t(records.size())});
        if (!records.empty()) {
          std::memcpy(out.mutable_data(), records.data(), records.size() * sizeof(RayRecord));
        }
        return out;
      },
      arg("origins"), arg("directions"), arg("max_distance") = pybind11::none(),
      pybind11::kw_only(), arg("category_bits") = kAll, arg("mask_bits") = kAll,
      arg("include_sensors") = false,
      "Closest hits of many rays at once, in parallel on the world's workers: origins and "
      "directions are (n, 3) arrays (m; any non-zero length), max_distance None, a number or an "
      "(n,) array (m). Returns a structured array of n records: body (int64, -1 for no hit), "
      "distance (m, inf for no hit), point (m), normal.");
  c.def(
      "cast_shape",
      [](const PyWorld& w, uint32_t shape, V3 position, Q4 orientation, V3 translation, bool all,
         uint32_t category_bits, uint32_t mask_bits, bool include_sensors) -> pybind11::object {
        const World& world = w.get();
        const Transform start{vec3(position), quat(orientation)};
        const QueryFilter f = filter(category_bits, mask_bits, include_sensors);
        if (all) {
          std::vector<ShapeCastHit> hits;
          world.cast_shape_all(ShapeId{shape}, start, vec3(translation), hits, f);
          pybind11::list out;
          for (const ShapeCastHit& h : hits) out.append(shape_hit(h));
          return out;
        }
        const auto h = world.cast_shape(ShapeId{shape}, start, vec3(translation), f);
        if (!h) return pybind11::none();
        return shape_hit(*h);
      },
      arg("shape"), arg("position"), arg("orientation") = Q4{1, 0, 0, 0},
      arg("translation") = V3{0, 0, 0}, pybind11::kw_only(), arg("all") = false,
      arg("category_bits") = kAll, arg("mask_bits") = kAll, arg("include_sensors") = false,
      "Sweeps `shape` from the pose (position m, orientation w x y z) along translation (m): "
      "the first body it touches as a dict (body, fraction in [0, 1], point m, normal from the "
      "body towards the shape) or None; all=True: a list of every hit by fraction.");
  c.def(
      "overlap_shape",
      [](const PyWorld& w, uint32_t shape, V3 position, Q4 orientation, uint32_t category_bits,
         uint32_t mask_bits, bool include_sensors) {
        std::vector<BodyId> out;
        w.get().overlap_shape(ShapeId{shape}, Transform{vec3(position), quat(orientation)}, out,
                              filter(category_bits, mask_bits, include_sensors));
        return id_array(out);
      },
      arg("shape"), arg("position"), arg("orientation") = Q4{1, 0, 0, 0}, pybind11::kw_only(),
      arg("category_bits") = kAll, arg("mask_bits") = kAll, arg("include_sensors") = false,
      "Ids of the bodies whose exact shape overlaps `shape` at the pose, in dense index order.");
  c.def(
      "overlap_box",
      [](const PyWorld& w, V3 lo, V3 hi, uint32_t category_bits, uint32_t mask_bits,
         bool include_sensors) {
        std::vector<BodyId> out;
        w.get().overlap_box(vec3(lo), vec3(hi), out,
                            filter(category_bits, mask_bits, include_sensors));
        return id_array(out);
      },
      arg("lo"), arg("hi"), pybind11::kw_only(), arg("category_bits") = kAll,
      arg("mask_bits") = kAll, arg("include_sensors") = false,
      "Ids of the bodies whose bounding box overlaps the box lo..hi (m, world).");
  c.def(
      "overlap_point",
      [](const PyWorld& w, V3 point, uint32_t category_bits, uint32_t mask_bits,
         bool include_sensors) {
        std::vector<BodyId> out;
        w.get().overlap_point(vec3(point), out, filter(category_bits, mask_bits, include_sensors));
        return id_array(out);
      },
      arg("point"), pybind11::kw_only(), arg("category_bits") = kAll, arg("mask_bits") = kAll,
      arg("include_sensors") = false, "Ids of the bodies whose solid contains the point (m).");
  c.def(
      "closest_point",
      [](const PyWorld& w, V3 point, std::optional<uint64_t> body, double max_distance,
         uint32_t category_bits, uint32_t mask_bits, bool include_sensors) -> pybind11::object {
        const World& world = w.get();
        if (body) return point_hit(world.closest_point(body_id(*body), vec3(point)));
        const auto h = world.closest_point(vec3(point), Real(max_distance),
                                           filter(category_bits, mask_bits, include_sensors));
        if (!h) return pybind11::none();
        return point_hit(*h);
      },
      arg("point"), pybind11::kw_only(), arg("body") = pybind11::none(), arg("max_distance") = inf,
      arg("category_bits") = kAll, arg("mask_bits") = kAll, arg("include_sensors") = false,
      "The closest surface point to `point` (m): of `body` when given, else of any body within "
      "max_distance (None if none). A dict: body, point (m), distance (m, negative inside), "
      "normal.");
  c.def(
      "move_character",
      [](const PyWorld& w, V3 position, V3 displacement, double radius, double half_height,
         double step_height, double max_slope, double skin, int max_iterations,
         uint32_t category_bits, uint32_t mask_bits) {
        CharacterMoveDef def;
        def.radius = Real(radius);
        def.half_height = Real(half_height);
        def.step_height = Real(step_height);
        def.max_slope = Real(max_slope);
        def.skin = Real(skin);
        def.max_iterations = max_iterations;
        def.filter = filter(category_bits, mask_bits, false);
        const CharacterMoveResult r =
            w.get().move_character(vec3(position), vec3(displacement), def);
        pybind11::dict d;
        d["position"] = tuple3(r.position);
        d["on_ground"] = r.on_ground;
        d["ground_normal"] = tuple3(r.ground_normal);
        d["ground_body"] = body_or_none(r.ground_body);
        return d;
      },
      arg("position"), arg("displacement"), pybind11::kw_only(), arg("radius") = 0.3,
      arg("half_height") = 0.6, arg("step_height") = 0.3, arg("max_slope") = 0.785398163397448,
      arg("skin") = 0.01, arg("max_iterations") = 4, arg("category_bits") = kAll,
      arg("mask_bits") = kAll,
      "Moves a vertical capsule centred at position (m) by displacement (m), sliding along "
      "walls and climbing steps up to step_height (m), not ground steeper than max_slope "
      "(rad). Returns position, on_ground, ground_normal, ground_body. Reads the world only.");
}

}  // namespace elan::py
