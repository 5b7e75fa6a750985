// SPDX-License-Identifier: MIT
// ThreadPool: a oneTBB arena, either its own or the caller's (elan/tbb_interop.hpp).
#include "elan/thread_pool.hpp"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <optional>
#include <string>

#include "core/world/thread_pool_access.hpp"
#include "elan/defs.hpp"
#include "elan/error.hpp"
#include "elan/tbb_interop.hpp"

namespace elan {

struct ThreadPool::Impl {
  std::optional<tbb::task_arena> own;  // empty when the arena is the caller's
  tbb::task_arena* arena = nullptr;
};

ThreadPool::ThreadPool(int threads) : impl_(std::make_unique<Impl>()) {
  if (threads < 0 || threads > kMaxThreads) {
    throw Error("threads", "must be in 0.." + std::to_string(kMaxThreads));
  }
  impl_->own.emplace(threads > 0 ? threads : std::max(1, tbb::info::default_concurrency()));
  impl_->arena = &*impl_->own;
}

ThreadPool::ThreadPool(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

ThreadPool::~ThreadPool() = default;

int ThreadPool::threads() const {
  return std::max(1, impl_->arena->max_concurrency());
}

tbb::task_arena& detail::ThreadPoolAccess::arena(ThreadPool& pool) {
  return *pool.impl_->arena;
}

ThreadPool detail::ThreadPoolAccess::wrap(tbb::task_arena& arena) {
  auto impl = std::make_unique<ThreadPool::Impl>();
  impl->arena = &arena;
  return ThreadPool(std::move(impl));
}

ThreadPool wrap_tbb_arena(tbb::task_arena& arena) {
  return detail::ThreadPoolAccess::wrap(arena);
}

}  // namespace elan
