// SPDX-License-Identifier: MIT
// The exception type the library throws for invalid arguments (never out of World::step).
#pragma once

#include <stdexcept>
#include <string>

namespace elan {

/// Thrown by creation and setter calls for an invalid argument. `field` names what was wrong
/// (e.g. "shape.radius"), so a scene loader can point at it.
class Error : public std::invalid_argument {
 public:
  Error(std::string field, const std::string& message)
      : std::invalid_argument(field.empty() ? message : field + ": " + message),
        field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

}  // namespace elan
