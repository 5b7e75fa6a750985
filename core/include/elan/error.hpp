// SPDX-License-Identifier: MIT
// The exception type the library throws for invalid arguments (never out of World::step).
#pragma once

#include <stdexcept>
#include <string>

#include "elan/one_line.hpp"

namespace elan {

/// Thrown by creation and setter calls for an invalid argument. `field` names what was wrong
/// (e.g. "shape.radius"), so a scene loader can point at it. Control characters in the message
/// are escaped (one_line), so that a user string in it keeps it on one line.
class Error : public std::invalid_argument {
 public:
  Error(std::string field, const std::string& message)
      : std::invalid_argument(one_line(field.empty() ? message : field + ": " + message)),
        field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

}  // namespace elan
