// SPDX-License-Identifier: MIT
// `elan batch` hands over to the Python batch runner: the sweep, the Dask cluster and the table are
// Python's (pandas, distributed), so the C++ command only finds the interpreter and the package.
#include "tools/batch_command.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace elan::cli {
#if defined(ELAN_HAVE_PYTHON)
namespace {

namespace fs = std::filesystem;

bool is_package(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "elan" / "__init__.py", ec);
}

// The folder to put first on PYTHONPATH, or empty to leave the interpreter's own path alone.
// In the build tree the package sits beside this executable (<build>/tools/elan and
// <build>/tools/python/elan), which also keeps two build trees from using each other's module;
// an installed elan uses the folder `cmake --install` put the package in, which is the
// interpreter's site-packages unless ELAN_PYTHON_INSTALL_DIR chose another.
std::string package_parent() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && is_package(self.parent_path() / "python")) {
    return (self.parent_path() / "python").string();
  }
#if defined(ELAN_PYTHON_INSTALL_DIR)
  if (is_package(ELAN_PYTHON_INSTALL_DIR)) return ELAN_PYTHON_INSTALL_DIR;
#endif
  return {};
}

}  // namespace
#endif

void exec_batch(std::span<const std::string> args) {
#if defined(ELAN_HAVE_PYTHON)
  // ELAN_PYTHON overrides the interpreter: another one with the same ABI, or a wrapper.
  const char* env_python = std::getenv("ELAN_PYTHON");
  const std::string python =
      env_python != nullptr && *env_python != '\0' ? env_python : ELAN_PYTHON_EXECUTABLE;
  const std::string parent = package_parent();
  if (!parent.empty()) {
    const char* old = std::getenv("PYTHONPATH");
    const std::string path = old != nullptr && *old != '\0' ? parent + ":" + old : parent;
    ::setenv("PYTHONPATH", path.c_str(), 1);
  }
  // argparse's messages then name the command the user typed.
  ::setenv("ELAN_BATCH_PROG", "elan batch", 1);
  std::vector<std::string> words = {python, "-m", "elan.batch"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  ::execv(python.c_str(), argv.data());
  throw std::runtime_error("batch: cannot run the Python interpreter " + python + ": " +
                           std::strerror(errno) + " (set ELAN_PYTHON to another)");
#else
  (void)args;
  throw std::runtime_error(
      "batch: this elan was built without the Python module (pybind11, NumPy or the Python "
      "headers were not found when it was configured; see docs/batch.md)");
#endif
}

}  // namespace elan::cli
