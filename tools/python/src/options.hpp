// SPDX-License-Identifier: MIT
// Keyword arguments shared by several methods: broadphase names and worker counts.
#pragma once

#include <optional>
#include <string>

#include "elan/defs.hpp"

namespace elan::py {

/// 'sap', 'all-pairs' or 'tree'; elan.Error "broadphase" otherwise.
BroadphaseType broadphase_from_name(const std::string& name);
/// The worker count a `threads` argument stands for (None or 0 = all cores), resolved as
/// `elan run` resolves --threads; elan.Error "threads" out of range.
int threads_from(std::optional<int> threads);

}  // namespace elan::py
