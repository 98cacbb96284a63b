#include "output_error.hpp"

namespace xshell {

OutputError::OutputError(const std::filesystem::path& path, const std::string& reason)
    : std::runtime_error("cannot write '" + path.string() + "': " + reason), path_(path) {}

}  // namespace xshell
