// SPDX-License-Identifier: MIT
// Trajectory CSV of `elan run --trajectory`: one row per non-static body per sampled step, with
// every value printed so that it reads back to the same bits.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "elan/world.hpp"

namespace elan::cli {

class TrajectoryWriter {
 public:
  /// Opens `path` and writes the header; throws std::runtime_error naming the file.
  TrajectoryWriter(const std::string& path, const World& world);
  ~TrajectoryWriter();
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;

  void write(const World& world, uint64_t step, double time);
  /// Flushes and closes; throws std::runtime_error when any write failed (e.g. disk full).
  void close();

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  std::vector<BodyId> bodies_;        // non-static bodies, in index order
  std::vector<std::size_t> indices_;  // their indices, for the `body` column
  std::string line_;
};

}  // namespace elan::cli
