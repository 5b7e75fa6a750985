// SPDX-License-Identifier: MIT
// The program recorder and replayer (elan/recorder.hpp). The call stream of a recording is a
// sequence of records u16 op | u32 n | n bytes of arguments, written value by value as
// core/world/recorder_hooks.hpp's put() does: integers little-endian, Real as its bit pattern,
// ids as (slot, generation), a quaternion as w x y z, a span as u64 count and its values, and
// for the creating calls the id they returned last. Box2D v3's recording of world commands is the
// model: a replay re-issues the same calls on the same starting state, so any difference in the
// result is the engine's.
#include <cstring>
#include <string>

#include "core/world/recorder_hooks.hpp"
#include "core/world/world_access.hpp"
#include "elan/recorder.hpp"
#include "elan/snapshot.hpp"

namespace elan {
namespace detail {

namespace {

template <class T>
void put_vector(ByteWriter& w, const std::vector<T>& v) {
  w.u32(uint32_t(v.size()));
  for (const T& x : v) put(w, x);
}

}  // namespace

void put(ByteWriter& w, const ShapeDef& d) {
  w.u8(uint8_t(d.type));
  w.real(d.radius);
  w.real(d.half_height);
  w.vec3(d.half_extents);
  put_vector(w, d.points);
  w.vec3(d.normal);
  w.real(d.offset);
  put_vector(w, d.vertices);
  w.u32(uint32_t(d.triangles.size()));
  for (const auto& t : d.triangles) {
    for (uint32_t k : t) w.u32(k);
  }
  put_vector(w, d.heights);
  w.u32(d.columns);
  w.real(d.spacing_x);
  w.real(d.spacing_z);
  w.u32(uint32_t(d.children.size()));
  for (const CompoundChild& c : d.children) {
    put(w, c.shape);
    put(w, c.position);
    put(w, c.orientation);
  }
  w.u64(d.user_data);
}

void put(ByteWriter& w, const BodyDef& d) {
  put(w, d.motion);
  put(w, d.shape);
  put(w, d.position);
  put(w, d.orientation);
  put(w, d.linear_velocity);
  put(w, d.angular_velocity);
  put(w, d.mass.has_value());
  put(w, d.mass.value_or(Real(0)));
  put(w, d.density);
  put(w, d.friction);
  put(w, d.restitution);
  put(w, d.linear_damping);
  put(w, d.angular_damping);
  put(w, d.category_bits);
  put(w, d.mask_bits);
  put(w, d.awake);
  put(w, d.sensor);
  put(w, d.gravity_scale);
  put(w, d.user_data);
}

void put(ByteWriter& w, const JointLimits& m) {
  put(w, m.enabled);
  put(w, m.lower);
  put(w, m.upper);
}
void put(ByteWriter& w, const JointMotor& m) {
  put(w, m.enabled);
  put(w, m.speed);
  put(w, m.max_force);
}
void put(ByteWriter& w, const JointSpring& m) {
  put(w, m.enabled);
  put(w, m.frequency);
  put(w, m.damping_ratio);
  put(w, m.target);
}

void put(ByteWriter& w, const JointDef& d) {
  w.u8(uint8_t(d.type));
  put(w, d.body_a);
  put(w, d.body_b);
  put(w, d.anchor);
  put(w, d.has_anchor);
  put(w, d.anchor_b);
  put(w, d.axis);
  put(w, d.limits);
  put(w, d.motor);
  put(w, d.spring);
  put(w, d.min_length);
  put(w, d.max_length);
  put(w, d.swing_limit);
  put(w, d.friction);
  put(w, d.constraint_hertz);
  put(w, d.constraint_damping_ratio);
  put(w, d.collide_connected);
  put(w, d.break_force);
  put(w, d.user_data);
}

std::size_t open_call(std::vector<uint8_t>& calls, Call op) {
  const std::size_t start = calls.size();
  ByteWriter w(calls);
  w.u8(uint8_t(uint16_t(op)));
  w.u8(uint8_t(uint16_t(op) >> 8));
  w.u32(0);
  return start;
}

void close_call(std::vector<uint8_t>& calls, std::size_t start) {
  const uint32_t n = uint32_t(calls.size() - start - 6);
  for (int i = 0; i < 4; ++i) calls[start + 2 + i] = uint8_t(n >> (8 * i));
}

void record_step(const World& world, Real dt) {
  CallLog& log = *state_of(world).recorder;
  Recording& r = log.rec;
  const std::size_t start = open_call(r.calls, Call::Step);
  ByteWriter w(r.calls);
  w.real(dt);
  close_call(r.calls, start);
  if (r.steps == 0) r.timestep = double(dt);
  ++r.steps;
  r.hashes.push_back(world.state_hash());
  if (log.keyframe_every != 0 && r.steps % log.keyframe_every == 0) {
    r.keyframes.push_back(Keyframe{r.steps, save_snapshot(world)});
  }
}

namespace {

// The names of Call's values, in its order from Step.
constexpr const char* kCallNames[] = {
    "step",
    "create_shape",
    "destroy_shape",
    "create_body",
    "destroy_body",
    "create_joint",
    "destroy_joint",
    "set_joint_motor",
    "set_joint_spring",
    "set_joint_limits",
    "set_joint_swing_limit",
    "set_joint_lengths",
    "set_joint_friction",
    "set_linear_velocity",
    "set_angular_velocity",
    "set_position",
    "set_orientation",
    "set_transform",
    "apply_force",
    "apply_force_at",
    "apply_torque",
    "apply_impulse",
    "apply_linear_impulse",
    "apply_angular_impulse",
    "move_kinematic",
    "wake",
    "sleep",
    "set_friction",
    "set_restitution",
    "set_mass",
    "set_collision_filter",
    "set_motion_type",
    "set_gravity_scale",
    "set_damping",
    "set_shape",
    "set_sensor",
    "set_gravity",
    "set_user_data(BodyId)",
    "set_user_data(ShapeId)",
    "set_user_data(JointId)",
    "set_center_of_mass_positions",
    "set_linear_velocities",
    "set_angular_velocities",
    "set_hit_event_threshold",
    "set_substeps",
    "set_iterations",
    "restore_snapshot",
    "restore_rollback",
    "set_sleep_enabled",
};
static_assert(std::size(kCallNames) == std::size_t(Call::End) - 1, "a name for every call");

// Reads a call's arguments back, in put()'s order.
class Args {
 public:
  explicit Args(std::span<const uint8_t> bytes) : in_(bytes, "recording") {}
  bool flag() { return in_.u8() != 0; }
  int i32() { return int(int32_t(in_.u32())); }
  uint32_t u32() { return in_.u32(); }
  uint64_t u64() { return in_.u64(); }
  Real real() { return in_.real(); }
  Vec3 vec3() { return in_.vec3(); }
  Quat quat() {
    const Real w = real(), x = real(), y = real();
    return Quat(w, x, y, real());
  }
  Transform transform() {
    Transform t;
    t.position = vec3();
    t.rotation = quat();
    return t;
  }
  BodyId body() {
    BodyId id;
    id.slot = u32();
    id.generation = u32();
    return id;
  }
  ShapeId shape() { return ShapeId{u32()}; }
  JointId joint() {
    JointId id;
    id.slot = u32();
    id.generation = u32();
    return id;
  }
  MotionType motion() {
    const uint8_t m = in_.u8();
    if (m > uint8_t(MotionType::Dynamic)) in_.fail("bad motion type");
    return MotionType(m);
  }
  std::vector<Real> reals() {
    const uint64_t n = u64();
    if (n > in_.remaining() / sizeof(Real)) in_.fail("value count runs past the end");
    std::vector<Real> v(n);
    for (Real& x : v) x = real();
    return v;
  }
  std::vector<uint8_t> bytes() {
    const uint64_t n = u64();
    in_.need(n);
    std::vector<uint8_t> v(n);
    for (uint8_t& x : v) x = in_.u8();
    return v;
  }
  template <class T, class F>
  std::vector<T> list(std::size_t min_bytes, F&& read) {
    const uint32_t n = in_.count(min_bytes, "list");
    std::vector<T> v;
    v.reserve(n);
    for (uint32_t i = 0; i < n; ++i) v.push_back(read());
    return v;
  }
  ShapeDef shape_def(int depth = 0) {
    if (depth > 8) in_.fail("compound nesting too deep");
    ShapeDef d;
    const uint8_t type = in_.u8();
    if (type > uint8_t(ShapeType::Compound)) in_.fail("bad shape type");
    d.type = ShapeType(type);
    d.radius = real();
    d.half_height = real();
    d.half_extents = vec3();
    d.points = list<Vec3>(3 * sizeof(Real), [&] { return vec3(); });
    d.normal = vec3();
    d.offset = real();
    d.vertices = list<Vec3>(3 * sizeof(Real), [&] { return vec3(); });
    d.triangles = list<std::array<uint32_t, 3>>(12, [&] {
      const uint32_t a = u32(), b = u32();
      return std::array<uint32_t, 3>{a, b, u32()};
    });
    d.heights = list<Real>(sizeof(Real), [&] { return real(); });
    d.columns = u32();
    d.spacing_x = real();
    d.spacing_z = real();
    d.children = list<CompoundChild>(1, [&] {
      CompoundChild c;
      c.shape = shape_def(depth + 1);
      c.position = vec3();
      c.orientation = quat();
      return c;
    });
    d.user_data = u64();
    return d;
  }
  BodyDef body_def() {
    BodyDef d;
    d.motion = motion();
    d.shape = shape();
    d.position = vec3();
    d.orientation = quat();
    d.linear_velocity = vec3();
    d.angular_velocity = vec3();
    const bool has_mass = flag();
    const Real mass = real();
    if (has_mass) d.mass = mass;
    d.density = real();
    d.friction = real();
    d.restitution = real();
    d.linear_damping = real();
    d.angular_damping = real();
    d.category_bits = u32();
    d.mask_bits = u32();
    d.awake = flag();
    d.sensor = flag();
    d.gravity_scale = real();
    d.user_data = u64();
    return d;
  }
  JointLimits limits() {
    JointLimits m;
    m.enabled = flag();
    m.lower = real();
    m.upper = real();
    return m;
  }
  JointMotor motor() {
    JointMotor m;
    m.enabled = flag();
    m.speed = real();
    m.max_force = real();
    return m;
  }
  JointSpring spring() {
    JointSpring m;
    m.enabled = flag();
    m.frequency = real();
    m.damping_ratio = real();
    m.target = real();
    return m;
  }
  JointDef joint_def() {
    JointDef d;
    const uint8_t type = in_.u8();
    if (type > uint8_t(JointType::Cone)) in_.fail("bad joint type");
    d.type = JointType(type);
    d.body_a = body();
    d.body_b = body();
    d.anchor = vec3();
    d.has_anchor = flag();
    d.anchor_b = vec3();
    d.axis = vec3();
    d.limits = limits();
    d.motor = motor();
    d.spring = spring();
    d.min_length = real();
    d.max_length = real();
    d.swing_limit = real();
    d.friction = real();
    d.constraint_hertz = real();
    d.constraint_damping_ratio = real();
    d.collide_connected = flag();
    d.break_force = real();
    d.user_data = u64();
    return d;
  }
  void done() const {
    if (in_.remaining() != 0) in_.fail("trailing argument bytes");
  }

 private:
  ByteReader in_;
};

// One record's header in a call stream.
struct CallHeader {
  uint16_t op = 0;
  std::size_t args = 0;  // offset of the arguments
  std::size_t size = 0;
};

CallHeader read_header(const std::vector<uint8_t>& calls, std::size_t at) {
  if (calls.size() - at < 6) throw RecordingError("corrupt recording: a call runs past the end");
  CallHeader h;
  h.op = uint16_t(calls[at] | (calls[at + 1] << 8));
  uint32_t n = 0;
  for (int i = 0; i < 4; ++i) n |= uint32_t(calls[at + 2 + i]) << (8 * i);
  h.args = at + 6;
  h.size = n;
  if (n > calls.size() - h.args) {
    throw RecordingError("corrupt recording: a call runs past the end");
  }
  if (h.op == 0 || h.op >= uint16_t(Call::End)) {
    throw RecordingError("corrupt recording: unknown call " + std::to_string(h.op));
  }
  return h;
}

template <class Id>
void expect_id(Id got, Id recorded, const char* what) {
  if (!(got == recorded)) {
    throw Error("id", std::string(what) + " returned another id than recorded");
  }
}

// Re-issues one recorded call (not a step) on `w`.
void apply_call(World& w, Call op, Args& a) {
  switch (op) {
    case Call::Step:
      break;
    case Call::CreateShape: {
      const ShapeDef d = a.shape_def();
      expect_id(w.create_shape(d), a.shape(), "create_shape");
      break;
    }
    case Call::DestroyShape:
      w.destroy_shape(a.shape());
      break;
    case Call::CreateBody: {
      const BodyDef d = a.body_def();
      expect_id(w.create_body(d), a.body(), "create_body");
      break;
    }
    case Call::DestroyBody:
      w.destroy_body(a.body());
      break;
    case Call::CreateJoint: {
      const JointDef d = a.joint_def();
      expect_id(w.create_joint(d), a.joint(), "create_joint");
      break;
    }
    case Call::DestroyJoint:
      w.destroy_joint(a.joint());
      break;
    case Call::SetJointMotor: {
      const JointId j = a.joint();
      w.set_joint_motor(j, a.motor());
      break;
    }
    case Call::SetJointSpring: {
      const JointId j = a.joint();
      w.set_joint_spring(j, a.spring());
      break;
    }
    case Call::SetJointLimits: {
      const JointId j = a.joint();
      w.set_joint_limits(j, a.limits());
      break;
    }
    case Call::SetJointSwingLimit: {
      const JointId j = a.joint();
      w.set_joint_swing_limit(j, a.real());
      break;
    }
    case Call::SetJointLengths: {
      const JointId j = a.joint();
      const Real lo = a.real();
      w.set_joint_lengths(j, lo, a.real());
      break;
    }
    case Call::SetJointFriction: {
      const JointId j = a.joint();
      w.set_joint_friction(j, a.real());
      break;
    }
    case Call::SetLinearVelocity: {
      const BodyId b = a.body();
      w.set_linear_velocity(b, a.vec3());
      break;
    }
    case Call::SetAngularVelocity: {
      const BodyId b = a.body();
      w.set_angular_velocity(b, a.vec3());
      break;
    }
    case Call::SetPosition: {
      const BodyId b = a.body();
      w.set_position(b, a.vec3());
      break;
    }
    case Call::SetOrientation: {
      const BodyId b = a.body();
      w.set_orientation(b, a.quat());
      break;
    }
    case Call::SetTransform: {
      const BodyId b = a.body();
      w.set_transform(b, a.transform());
      break;
    }
    case Call::ApplyForce: {
      const BodyId b = a.body();
      w.apply_force(b, a.vec3());
      break;
    }
    case Call::ApplyForceAt: {
      const BodyId b = a.body();
      const Vec3 f = a.vec3();
      w.apply_force_at(b, f, a.vec3());
      break;
    }
    case Call::ApplyTorque: {
      const BodyId b = a.body();
      w.apply_torque(b, a.vec3());
      break;
    }
    case Call::ApplyImpulse: {
      const BodyId b = a.body();
      const Vec3 j = a.vec3();
      w.apply_impulse(b, j, a.vec3());
      break;
    }
    case Call::ApplyLinearImpulse: {
      const BodyId b = a.body();
      w.apply_linear_impulse(b, a.vec3());
      break;
    }
    case Call::ApplyAngularImpulse: {
      const BodyId b = a.body();
      w.apply_angular_impulse(b, a.vec3());
      break;
    }
    case Call::MoveKinematic: {
      const BodyId b = a.body();
      const Transform t = a.transform();
      w.move_kinematic(b, t, a.real());
      break;
    }
    case Call::Wake:
      w.wake(a.body());
      break;
    case Call::Sleep:
      w.sleep(a.body());
      break;
    case Call::SetFriction: {
      const BodyId b = a.body();
      w.set_friction(b, a.real());
      break;
    }
    case Call::SetRestitution: {
      const BodyId b = a.body();
      w.set_restitution(b, a.real());
      break;
    }
    case Call::SetMass: {
      const BodyId b = a.body();
      w.set_mass(b, a.real());
      break;
    }
    case Call::SetCollisionFilter: {
      const BodyId b = a.body();
      const uint32_t category = a.u32();
      w.set_collision_filter(b, category, a.u32());
      break;
    }
    case Call::SetMotionType: {
      const BodyId b = a.body();
      w.set_motion_type(b, a.motion());
      break;
    }
    case Call::SetGravityScale: {
      const BodyId b = a.body();
      w.set_gravity_scale(b, a.real());
      break;
    }
    case Call::SetDamping: {
      const BodyId b = a.body();
      const Real linear = a.real();
      w.set_damping(b, linear, a.real());
      break;
    }
    case Call::SetShape: {
      const BodyId b = a.body();
      w.set_shape(b, a.shape());
      break;
    }
    case Call::SetSensor: {
      const BodyId b = a.body();
      w.set_sensor(b, a.flag());
      break;
    }
    case Call::SetGravity:
      w.set_gravity(a.vec3());
      break;
    case Call::SetBodyUserData: {
      const BodyId b = a.body();
      w.set_user_data(b, a.u64());
      break;
    }
    case Call::SetShapeUserData: {
      const ShapeId s = a.shape();
      w.set_user_data(s, a.u64());
      break;
    }
    case Call::SetJointUserData: {
      const JointId j = a.joint();
      w.set_user_data(j, a.u64());
      break;
    }
    case Call::SetCenterOfMassPositions:
    case Call::SetLinearVelocities:
    case Call::SetAngularVelocities: {
      const std::vector<Real> x = a.reals(), y = a.reals(), z = a.reals();
      if (op == Call::SetCenterOfMassPositions) w.set_center_of_mass_positions(x, y, z);
      if (op == Call::SetLinearVelocities) w.set_linear_velocities(x, y, z);
      if (op == Call::SetAngularVelocities) w.set_angular_velocities(x, y, z);
      break;
    }
    case Call::SetHitEventThreshold:
      w.set_hit_event_threshold(a.real());
      break;
    case Call::SetSubsteps:
      w.set_substeps(a.i32());
      break;
    case Call::SetIterations:
      w.set_iterations(a.i32());
      break;
    case Call::RestoreSnapshot:
      restore_snapshot(w, a.bytes());
      break;
    case Call::RestoreRollback:
      restore_rollback(w, a.bytes());
      break;
    case Call::SetSleepEnabled:
      w.set_sleep_enabled(a.flag());
      break;
    case Call::End:
      break;
  }
  a.done();
}

// Offset in r.calls just after the `step`-th step record (0 for step 0).
std::size_t offset_after_step(const Recording& r, uint64_t step) {
  std::size_t at = 0;
  for (uint64_t seen = 0; seen < step;) {
    if (at >= r.calls.size()) {
      throw RecordingError("corrupt recording: fewer steps in the calls than recorded");
    }
    const CallHeader h = read_header(r.calls, at);
    at = h.args + h.size;
    if (h.op == uint16_t(Call::Step)) ++seen;
  }
  return at;
}

}  // namespace
}  // namespace detail

void start_recording(World& world, const RecordOptions& options) {
  detail::WorldState& s = detail::state_of(world);
  s.recorder.reset();
  auto log = std::make_shared<detail::CallLog>();
  Recording& r = log->rec;
  r.version = kRecordingVersion;
  r.real_bytes = sizeof(Real);
  r.engine_version = kEngineVersion;
  r.promise = kDeterminismPromise;
  r.substeps = s.def.substeps;
  r.iterations = s.def.iterations;
  r.threads = uint32_t(s.threads);
  r.broadphase = uint32_t(s.def.broadphase);
  r.scene_name = options.name;
  r.initial_snapshot = save_snapshot(world);
  r.keyframe_every = options.keyframe_every;
  log->keyframe_every = options.keyframe_every;
  if (options.keyframe_every != 0) r.keyframes.push_back(Keyframe{0, r.initial_snapshot});
  r.hashes.push_back(world.state_hash());
  s.recorder = std::move(log);
}

bool is_recording(const World& world) {
  return detail::state_of(world).recorder != nullptr;
}

std::vector<uint8_t> save_recording(const World& world) {
  const detail::WorldState& s = detail::state_of(world);
  if (!s.recorder) return {};
  const std::string bytes = encode_recording(s.recorder->rec);
  return std::vector<uint8_t>(bytes.begin(), bytes.end());
}

std::vector<uint8_t> stop_recording(World& world) {
  std::vector<uint8_t> bytes = save_recording(world);
  detail::state_of(world).recorder.reset();
  return bytes;
}

std::vector<RecordedCall> list_calls(const Recording& r) {
  std::vector<RecordedCall> out;
  uint64_t step = 0;
  for (std::size_t at = 0; at < r.calls.size();) {
    const detail::CallHeader h = detail::read_header(r.calls, at);
    out.push_back(RecordedCall{step, h.op, h.args, h.size});
    if (h.op == uint16_t(detail::Call::Step)) ++step;
    at = h.args + h.size;
  }
  return out;
}

std::string_view recorded_call_name(uint16_t op) {
  if (op == 0 || op >= uint16_t(detail::Call::End)) return {};
  return detail::kCallNames[op - 1];
}

std::vector<std::string_view> recorded_call_names() {
  return std::vector<std::string_view>(std::begin(detail::kCallNames),
                                       std::end(detail::kCallNames));
}

World recording_start_world(const Recording& r, int threads, BroadphaseType broadphase) {
  if (!r.is_program()) {
    throw RecordingError(r.scene_name +
                         ": a scene recording starts from its scene (load Recording::scene_text)");
  }
  try {
    World w = load_snapshot(r.initial_snapshot);
    w.set_threads(threads);
    w.set_broadphase(broadphase);
    return w;
  } catch (const Error& e) {
    throw RecordingError(std::string("corrupt recording: starting snapshot: ") + e.what());
  }
}

Replayer::Replayer(const Recording& recording, World world, uint64_t start_step)
    : r_(&recording), world_(std::move(world)), step_(start_step) {
  if (start_step > recording.steps) {
    throw RecordingError("replay from step " + std::to_string(start_step) + ": the recording has " +
                         std::to_string(recording.steps) + " steps");
  }
  if (recording.is_program()) next_call_ = detail::offset_after_step(recording, start_step);
}

uint64_t Replayer::steps() const {
  return r_->steps;
}

uint64_t Replayer::expected_hash() const {
  return r_->hashes[step_];
}

namespace detail {
namespace {

// Applies the calls recorded from offset `at` of r.calls up to the next step record, and takes
// that step, the `step`-th (1-based, for messages). Returns the offset after the step record.
std::size_t replay_calls(World& world, const Recording& r, std::size_t at, uint64_t step,
                         uint32_t& status) {
  for (;;) {
    if (at >= r.calls.size()) {
      throw RecordingError("corrupt recording: fewer steps in the calls than recorded");
    }
    const CallHeader h = read_header(r.calls, at);
    at = h.args + h.size;
    Args args(std::span<const uint8_t>(r.calls).subspan(h.args, h.size));
    try {
      if (h.op == uint16_t(Call::Step)) {
        const Real dt = args.real();
        args.done();
        status = world.step(dt);
        return at;
      }
      apply_call(world, Call(h.op), args);
    } catch (const Error& e) {
      throw RecordingError("before step " + std::to_string(step) + ": the recorded call " +
                           std::string(recorded_call_name(h.op)) + " fails on replay: " + e.what());
    }
  }
}

}  // namespace
}  // namespace detail

uint32_t replay_step(World& world, const Recording& r, uint64_t step) {
  if (step >= r.steps) throw RecordingError("the recording has no step left");
  if (!r.is_program()) return world.step(Real(r.timestep));
  uint32_t status = 0;
  detail::replay_calls(world, r, detail::offset_after_step(r, step), step + 1, status);
  return status;
}

bool Replayer::advance() {
  if (step_ >= r_->steps) throw RecordingError("the recording has no step left");
  if (!r_->is_program()) {
    world_.step(Real(r_->timestep));
  } else {
    uint32_t status = 0;
    next_call_ = detail::replay_calls(world_, *r_, next_call_, step_ + 1, status);
  }
  ++step_;
  return world_.state_hash() == r_->hashes[step_];
}

ReplayResult replay_recording(std::span<const uint8_t> bytes, const ReplayOptions& options) {
  const std::string_view view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const Recording r = decode_recording(view, "recording");
  check_recording_build(r, "recording");
  const BroadphaseType broadphase = options.broadphase.value_or(BroadphaseType(r.broadphase));
  Replayer replay(r, recording_start_world(r, options.threads, broadphase));
  ReplayResult out;
  const uint64_t until = std::min(options.until.value_or(r.steps), r.steps);
  while (replay.step() < until) {
    bool same = false;
    try {
      same = replay.advance();
    } catch (const RecordingError& e) {
      out.match = false;
      out.mismatch_step = replay.step() + 1;
      out.error = e.what();
      break;
    }
    if (!same) {
      out.match = false;
      out.mismatch_step = replay.step();
      out.expected = replay.expected_hash();
      out.actual = replay.actual_hash();
      break;
    }
  }
  out.steps = replay.step();
  out.snapshot = save_snapshot(replay.world());
  return out;
}

}  // namespace elan
