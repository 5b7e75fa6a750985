// SPDX-License-Identifier: MIT
// Interoperation with oneTBB: the one public header that includes TBB, for applications that
// run their own task arenas and want elan's steps inside them. Everything else in elan/ is free
// of TBB (a unit test checks it).
#pragma once

#include <tbb/task_arena.h>

#include "elan/thread_pool.hpp"

namespace elan {

/// A ThreadPool that runs steps inside `arena`, the caller's own, with the arena's concurrency as
/// the worker count. The pool does not own the arena: `arena` must outlive the pool.
ThreadPool wrap_tbb_arena(tbb::task_arena& arena);

}  // namespace elan
