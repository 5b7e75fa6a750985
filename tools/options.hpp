// Command-line options of `elan run` and `elan replay`: hand-written parsing, strict numbers.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "elan/defs.hpp"

namespace elan::cli {

/// A bad command line: reported with a hint to --help, exit status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunOptions {
  bool help = false;
  std::string scene;
  uint64_t steps = 600;
  std::optional<double> timestep;  // s; overrides the scene's
  std::optional<int> substeps;
  std::optional<int> iterations;
  int threads = 0;  // 0 = all cores
  BroadphaseType broadphase = BroadphaseType::SweepAndPrune;
  std::string trajectory;  // CSV path, empty = none
  uint64_t every = 1;
  bool has_every = false;
  std::string record;  // recording path, empty = none
};

struct ReplayOptions {
  bool help = false;
  std::string file;
  int threads = 0;                           // 0 = all cores
  std::optional<BroadphaseType> broadphase;  // default: the recorded one
};

/// `args` are the words after the command name. Throw UsageError.
RunOptions parse_run_options(std::span<const std::string> args);
ReplayOptions parse_replay_options(std::span<const std::string> args);

const char* broadphase_name(BroadphaseType type);
/// Worker count that `threads` (0 = all cores) stands for.
int resolve_threads(int threads);

extern const char* const kMainUsage;
extern const char* const kRunUsage;
extern const char* const kReplayUsage;

}  // namespace elan::cli
