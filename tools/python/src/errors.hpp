// SPDX-License-Identifier: MIT
// Argument checks of the binding: they throw elan::Error, which Python sees as elan.Error.
#pragma once

#include <string>

namespace elan::py {

/// Throws elan::Error(field, message) (elan.Error in Python).
[[noreturn]] void raise(const std::string& field, const std::string& message);

}  // namespace elan::py
