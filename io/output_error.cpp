#include "output_error.hpp"

#include "input_error.hpp"  // printable

namespace xshell {

namespace {
// The path quoted as every message quotes user text (escaped, at most
// kMaxQuotedChars), and a reason even when the system gave none.
std::string message(const std::filesystem::path& path, const std::string& reason) {
  return "cannot write '" + printable(path.string()) +
         "': " + (reason.empty() ? "the system gave no reason" : reason);
}
}  // namespace

OutputError::OutputError(const std::filesystem::path& path, const std::string& reason)
    : std::runtime_error(message(path, reason)), path_(path) {}

}  // namespace xshell
