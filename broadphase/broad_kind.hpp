// SPDX-License-Identifier: MIT
// A body's kind as the broadphase pairs it: static, kinematic, sleeping or awake.
#pragma once

#include <cstdint>

#include "core/base/body_store.hpp"

namespace elan::detail {

enum class BroadKind : uint8_t { Static, Kinematic, Sleeping, Awake };

// From the motion type and the awake and frozen flags: a frozen dynamic body (quarantined) counts
// as sleeping, so it pairs only with kinematic bodies.
inline BroadKind broad_kind(const BodyStore& b, std::size_t i) {
  switch (MotionType(b.motion[i])) {
    case MotionType::Static:
      return BroadKind::Static;
    case MotionType::Kinematic:
      return BroadKind::Kinematic;
    case MotionType::Dynamic:
      break;
  }
  return b.is_awake(i) && !(b.flags[i] & kFrozen) ? BroadKind::Awake : BroadKind::Sleeping;
}

}  // namespace elan::detail
