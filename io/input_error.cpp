#include "input_error.hpp"

namespace xshell {

InputError::InputError(const std::string& message) : std::runtime_error(message) {}

}  // namespace xshell
