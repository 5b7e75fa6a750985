// SPDX-License-Identifier: MIT
// How World methods reach the program recorder (elan/recorder.hpp). A recorded method starts
// with
//
//     if (state_->recorder) [[unlikely]] return detail::recorded(*state_, Call::X, [&] { return
//     X(args); }, args...);
//
// (ELAN_RECORDED below): one predictable branch when no recorder is attached. When one is, the
// recorder is detached while the method runs again (so the calls it makes itself are not
// recorded twice), and the call's arguments (and the id it returned) are appended only when it
// returned normally: a call that throws changed nothing and is not recorded.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "core/world/byte_io.hpp"
#include "core/world/world_state.hpp"
#include "elan/defs.hpp"
#include "elan/joints.hpp"
#include "elan/recording.hpp"
#include "elan/world.hpp"

namespace elan::detail {

// The recorded calls' codes: the recording format's, so never renumbered (new ones go last).
enum class Call : uint16_t {
  Step = 1,
  CreateShape,
  DestroyShape,
  CreateBody,
  DestroyBody,
  CreateJoint,
  DestroyJoint,
  SetJointMotor,
  SetJointSpring,
  SetJointLimits,
  SetJointSwingLimit,
  SetJointLengths,
  SetJointFriction,
  SetLinearVelocity,
  SetAngularVelocity,
  SetPosition,
  SetOrientation,
  SetTransform,
  ApplyForce,
  ApplyForceAt,
  ApplyTorque,
  ApplyImpulse,
  ApplyLinearImpulse,
  ApplyAngularImpulse,
  MoveKinematic,
  Wake,
  Sleep,
  SetFriction,
  SetRestitution,
  SetMass,
  SetCollisionFilter,
  SetMotionType,
  SetGravityScale,
  SetDamping,
  SetShape,
  SetSensor,
  SetGravity,
  SetBodyUserData,
  SetShapeUserData,
  SetJointUserData,
  SetCenterOfMassPositions,
  SetLinearVelocities,
  SetAngularVelocities,
  SetHitEventThreshold,
  SetSubsteps,
  SetIterations,
  RestoreSnapshot,
  RestoreRollback,
  SetSleepEnabled,
  End,  // one past the last
};

// A recording in progress: the recording's header and starting state, and what has been
// appended since.
struct CallLog {
  Recording rec;
  uint64_t keyframe_every = 0;
};

// Arguments, value by value in the recording's byte order (Real as its bit pattern).
inline void put(ByteWriter& w, bool v) {
  w.u8(v ? 1 : 0);
}
inline void put(ByteWriter& w, int v) {
  w.u32(uint32_t(v));
}
inline void put(ByteWriter& w, uint32_t v) {
  w.u32(v);
}
inline void put(ByteWriter& w, uint64_t v) {
  w.u64(v);
}
inline void put(ByteWriter& w, Real v) {
  w.real(v);
}
inline void put(ByteWriter& w, const Vec3& v) {
  w.vec3(v);
}
inline void put(ByteWriter& w, const Quat& q) {
  w.real(q.w());
  w.real(q.x());
  w.real(q.y());
  w.real(q.z());
}
inline void put(ByteWriter& w, const Transform& t) {
  put(w, t.position);
  put(w, t.rotation);
}
inline void put(ByteWriter& w, BodyId id) {
  w.u32(id.slot);
  w.u32(id.generation);
}
inline void put(ByteWriter& w, ShapeId id) {
  w.u32(id.index);
}
inline void put(ByteWriter& w, JointId id) {
  w.u32(id.slot);
  w.u32(id.generation);
}
inline void put(ByteWriter& w, MotionType t) {
  w.u8(uint8_t(t));
}
inline void put(ByteWriter& w, std::span<const Real> v) {
  w.u64(v.size());
  for (Real x : v) w.real(x);
}
inline void put(ByteWriter& w, std::span<const uint8_t> v) {
  w.u64(v.size());
  w.bytes(v.data(), v.size());
}
void put(ByteWriter& w, const ShapeDef& d);
void put(ByteWriter& w, const BodyDef& d);
void put(ByteWriter& w, const JointDef& d);
void put(ByteWriter& w, const JointMotor& m);
void put(ByteWriter& w, const JointSpring& m);
void put(ByteWriter& w, const JointLimits& m);

// Opens a call's record (u16 op, u32 length patched by close_call) and returns its start.
std::size_t open_call(std::vector<uint8_t>& calls, Call op);
void close_call(std::vector<uint8_t>& calls, std::size_t start);

template <class F, class... Args>
auto recorded(WorldState& s, Call op, F&& call, const Args&... args) {
  // Detached while the call runs: nested public calls are not recorded again.
  std::shared_ptr<CallLog> log = std::move(s.recorder);
  struct Reattach {
    WorldState& s;
    std::shared_ptr<CallLog>& log;
    ~Reattach() { s.recorder = std::move(log); }
  } reattach{s, log};
  std::vector<uint8_t>& calls = log->rec.calls;
  if constexpr (std::is_void_v<decltype(call())>) {
    call();
    const std::size_t start = open_call(calls, op);
    ByteWriter w(calls);
    (put(w, args), ...);
    close_call(calls, start);
  } else {
    auto result = call();
    const std::size_t start = open_call(calls, op);
    ByteWriter w(calls);
    (put(w, args), ...);
    put(w, result);
    close_call(calls, start);
    return result;
  }
}

// After a step of `dt` taken by a recorded world: the step, its state hash, maybe a keyframe.
void record_step(const World& world, Real dt);

}  // namespace elan::detail

// The first line of a recorded World method: `method` is the call itself (re-entered with the
// recorder detached), the rest are its arguments as recorded.
#define ELAN_RECORDED(op, call, ...) \
  if (state_->recorder) [[unlikely]] \
  return ::elan::detail::recorded(   \
      *state_, ::elan::detail::Call::op, [&] { return call; }, __VA_ARGS__)
