// SPDX-License-Identifier: MIT
// The engine's own access to a ThreadPool's oneTBB arena, which the public header keeps opaque.
#pragma once

#include <tbb/task_arena.h>

#include "elan/thread_pool.hpp"

namespace elan::detail {

struct ThreadPoolAccess {
  static tbb::task_arena& arena(ThreadPool& pool);
  static ThreadPool wrap(tbb::task_arena& arena);
};

// The arena a step run in `pool` executes in.
inline tbb::task_arena& arena_of(ThreadPool& pool) {
  return ThreadPoolAccess::arena(pool);
}

}  // namespace elan::detail
