// SPDX-License-Identifier: MIT
// Runs the built `elan` binary from a test (ELAN_CLI is its path) and captures exit status,
// standard output and standard error; plus the file helpers the command-line tests share.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace elan::test {

// One static ground, two spheres ("a", "b") and a box falling onto it and tumbling.
inline const char* const kSmallScene = R"({
  "timestep": 0.01,
  "bodies": [
    {"name": "ground", "motion": "static", "shape": {"type": "box", "half_extents": [10, 1, 10]},
     "position": [0, -1, 0]},
    {"name": "a", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 0.6, 0]},
    {"name": "b", "shape": {"type": "sphere", "radius": 0.5}, "position": [1.5, 2, 0],
     "linear_velocity": [0, 0, 1]},
    {"shape": {"type": "box", "half_extents": [0.4, 0.3, 0.2]}, "position": [-1.5, 1, 0.2],
     "angular_velocity": [0, 2, 0]}
  ]
})";

// The number of lines of a captured stream: a one-line message counts 1.
inline std::size_t count_lines(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

struct Result {
  int status = -1;  // exit status; a death by signal shows as 128 + signal through the shell
  std::string out;
  std::string err;
};

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') {
      q.append("'\\''");
    } else {
      q.push_back(c);
    }
  }
  q.push_back('\'');
  return q;
}

inline std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// A path unique to the running test, so ctest may run tests in parallel.
inline std::string temp_path(const std::string& name) {
  std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  for (char& c : test) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return ::testing::TempDir() + "elan_cli_" + std::to_string(getpid()) + "_" + test + "_" + name;
}

// With `timeout_seconds` > 0 the binary runs under timeout(1), killed after that long: a test of
// a former hang then fails (status 124, or 137 after the KILL) instead of hanging the suite.
// `env_prefix` (e.g. "env -u DISPLAY") goes before the whole command.
inline Result run_elan(const std::vector<std::string>& args, int timeout_seconds = 0,
                       const std::string& env_prefix = "") {
  const std::string out = temp_path("stdout"), err = temp_path("stderr");
  std::string cmd = env_prefix.empty() ? "" : env_prefix + " ";
  if (timeout_seconds > 0)
    cmd.append("timeout -k 5 ").append(std::to_string(timeout_seconds)).append(" ");
  cmd.append(quote(ELAN_CLI));
  // Appends only: GCC 12 warns falsely (-Wrestrict) on `" " + std::string`.
  for (const std::string& a : args) cmd.append(" ").append(quote(a));
  cmd.append(" >").append(quote(out)).append(" 2>").append(quote(err)).append(" </dev/null");
  const int rc = std::system(cmd.c_str());
  Result r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = read(out);
  r.err = read(err);
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

}  // namespace elan::test
