#include "input_error.hpp"

namespace xshell {

InputError::InputError(const std::string& message) : std::runtime_error(message) {}

namespace {

bool is_continuation_byte(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

void append_escaped(std::string& out, std::string_view text) {
  static const char* const kHex = "0123456789abcdef";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte != 0x7F) {
      out += c;
      continue;
    }
    switch (c) {
      case '\0':
        out += "\\0";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        out += "\\x";
        out += kHex[byte >> 4];
        out += kHex[byte & 0xF];
    }
  }
}

}  // namespace

std::string printable(std::string_view text, std::size_t max_chars) {
  std::string out;
  if (text.size() <= max_chars) {
    append_escaped(out, text);
    return out;
  }
  const std::string_view ellipsis = "...";
  const std::size_t kept = max_chars > ellipsis.size() ? max_chars - ellipsis.size() : 0;
  std::size_t head = kept - kept / 2;         // the beginning: up to here
  std::size_t tail = text.size() - kept / 2;  // the end: from here
  while (head > 0 && is_continuation_byte(text[head])) --head;
  while (tail < text.size() && is_continuation_byte(text[tail])) ++tail;
  append_escaped(out, text.substr(0, head));
  out += ellipsis;
  append_escaped(out, text.substr(tail));
  return out;
}

}  // namespace xshell
