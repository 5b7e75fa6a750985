// SPDX-License-Identifier: MIT
// ThreadPool: the workers a world runs its step on, which several worlds may share. An opaque
// handle, so that the public API names no threading library (elan/tbb_interop.hpp wraps a
// caller's oneTBB arena).
#pragma once

#include <memory>

namespace elan {

namespace detail {
struct ThreadPoolAccess;
}

/// Worker threads for World::step and step_all. A world given none (WorldDef::thread_pool) makes
/// its own of WorldDef::threads workers; give several worlds one pool to share its workers, or
/// wrap the application's own oneTBB arena (elan/tbb_interop.hpp) so that steps run in it.
/// Results are bit-identical whatever the pool and its size.
///
/// Neither copyable nor movable: worlds keep its address, so it must outlive every world that
/// uses it. Its methods may be called from any thread.
class ThreadPool {
 public:
  /// A pool of `threads` workers, the calling thread included; 0 = all cores. Throws
  /// elan::Error "threads" outside 0..1024.
  explicit ThreadPool(int threads = 0);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// How many threads a step run in this pool may use: the worker count of a world using it.
  int threads() const;

 private:
  friend struct detail::ThreadPoolAccess;
  struct Impl;
  explicit ThreadPool(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace elan
