// Raised when a linkage cannot be built from its input (a graph the model
// cannot represent, a support that does not apply to its vertex, ...). The
// message is meant for the user; the command line maps it to exit status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace xshell {

class ModelError : public std::invalid_argument {
 public:
  explicit ModelError(const std::string& message) : std::invalid_argument(message) {}
};

}  // namespace xshell
