#pragma once
// The one exception type of conform: bad input (a file, an argument, degenerate geometry handed in).
// Its message names the input and what is wrong, so that a user can act on it; the CLI turns it into exit code 2.

#include <stdexcept>
#include <string>

namespace conform {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace conform
