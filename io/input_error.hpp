// The one exception type for rejected user input (configuration, linkage
// files, states, command-line values). Its message is complete and meant for
// the user as it is: it names the file, the line or key, and what is wrong.
// The command line maps it to exit status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace xshell {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message);
};

}  // namespace xshell
