// SPDX-License-Identifier: MIT
// `elan batch`: runs `python3 -m elan.batch` (tools/python/elan/batch.py, docs/batch.md) with the
// interpreter the Python module was built for and the module on its path.
#pragma once

#include <span>
#include <string>

namespace elan::cli {

/// Replaces this process with the Python batch runner, passing `args` (the words after `batch`)
/// through. Returns only on failure: throws std::runtime_error when this elan was built without the
/// Python module or the interpreter cannot be started.
[[noreturn]] void exec_batch(std::span<const std::string> args);

}  // namespace elan::cli
