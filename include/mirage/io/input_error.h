// SPDX-License-Identifier: MIT
// The exception io/ throws for bad input; its message names the file, line, key and value.
#pragma once

#include <stdexcept>
#include <string>

namespace mirage::io {

/// Bad input (scenario, recorded data, command line). what() is a complete one-line message.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mirage::io
