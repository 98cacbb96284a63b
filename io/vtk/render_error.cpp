#include "render_error.hpp"

namespace xshell {

RenderError::RenderError(const std::string& message) : std::runtime_error(message) {}

}  // namespace xshell
