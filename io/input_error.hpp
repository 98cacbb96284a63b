// The one exception type for rejected user input (configuration, linkage
// files, states, command-line values). Its message is complete and meant for
// the user as it is: it names the file, the line or key, and what is wrong.
// The command line maps it to exit status 2.
//
// A message is one line of bounded length whatever the input: every piece of
// user text it quotes (a path, a key, a token of the file) goes through
// printable(), which escapes control characters (a NUL byte would otherwise
// cut the message short, a newline split it) and shortens the text to
// kMaxQuotedChars characters.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace xshell {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message);
};

// Most characters of user text a message quotes (before escaping).
constexpr std::size_t kMaxQuotedChars = 200;

// `text` as a message quotes it: control characters escaped ("\0", "\n",
// "\r", "\t", else "\xNN"), and text longer than `max_chars` shortened to
// its beginning and its end around "..." (without splitting a UTF-8
// character), `max_chars` characters in all.
std::string printable(std::string_view text, std::size_t max_chars = kMaxQuotedChars);

}  // namespace xshell
