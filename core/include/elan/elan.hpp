// SPDX-License-Identifier: MIT
// The whole public API of elan in one include.
#pragma once

#include "elan/debug_draw.hpp"
#include "elan/defs.hpp"
#include "elan/error.hpp"
#include "elan/events.hpp"
#include "elan/ids.hpp"
#include "elan/limits.hpp"
#include "elan/math.hpp"
#include "elan/profile.hpp"
#include "elan/queries.hpp"
#include "elan/recorder.hpp"
#include "elan/recording.hpp"
#include "elan/scene.hpp"
#include "elan/snapshot.hpp"
#include "elan/thread_pool.hpp"
#include "elan/world.hpp"
