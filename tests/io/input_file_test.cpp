// Reading a user's file whole (io/input_file.hpp) and quoting user text in
// messages (printable, io/input_error.hpp).
#include "io/input_file.hpp"

#include <doctest/doctest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>

#include "io/input_error.hpp"
#include "scratch_directory.hpp"

namespace xshell::test {
namespace {

namespace fs = std::filesystem;

const InputFileKind kSmall{"test file", 1000};

// The message of the InputError that reading `path` raises, within 10 s
// (a reader that blocks fails the check; a writer then unblocks it).
std::string refusal(const fs::path& path, const InputFileKind& kind = kSmall) {
  auto reading = std::async(std::launch::async, [&]() -> std::string {
    try {
      read_input_file(path.string(), kind, "cannot open test file");
    } catch (const InputError& e) {
      return e.what();
    }
    return "(read)";
  });
  if (reading.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    FAIL_CHECK("reading " << path << " blocked");
    std::ofstream(path) << "";  // the writer a FIFO's reader waits for
  }
  return reading.get();
}

}  // namespace

TEST_CASE("input file: a regular file is read whole") {
  ScratchDirectory dir("regular");
  std::string text;
  for (int i = 0; i < 200000; ++i) text += static_cast<char>(i % 251);  // NULs included
  std::ofstream(dir / "f", std::ios::binary) << text;
  CHECK(read_input_file((dir / "f").string(), {"test file", 1 << 20}, "x") == text);
  std::ofstream(dir / "empty") << "";
  CHECK(read_input_file((dir / "empty").string(), kSmall, "x").empty());
}

TEST_CASE("input file: a folder or a FIFO or a device or a socket is refused unread") {
  ScratchDirectory dir("kinds");
  fs::create_directory(dir / "folder");
  CHECK(refusal(dir / "folder") == "cannot open test file: it is a folder, not a file");
  REQUIRE(::mkfifo((dir / "fifo").c_str(), 0600) == 0);
  CHECK(refusal(dir / "fifo") ==
        "cannot open test file: it is a FIFO (named pipe), not a regular file");
  CHECK(refusal("/dev/zero") == "cannot open test file: it is a device, not a regular file");
  CHECK(refusal("/dev/null") == "cannot open test file: it is a device, not a regular file");
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  REQUIRE(fd >= 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string socket_path = (dir / "socket").string();
  if (socket_path.size() < sizeof address.sun_path) {
    std::copy(socket_path.begin(), socket_path.end(), address.sun_path);
    REQUIRE(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
    CHECK(refusal(dir / "socket") == "cannot open test file: it is a socket, not a regular file");
  }
  ::close(fd);
  CHECK(refusal(dir / "missing") == "cannot open test file: No such file or directory");
}

TEST_CASE("input file: a file above its kind's limit is refused before it is read") {
  ScratchDirectory dir("size");
  std::ofstream(dir / "small") << std::string(1000, 'x');
  CHECK(read_input_file((dir / "small").string(), kSmall, "x").size() == 1000);
  std::ofstream(dir / "large") << std::string(1001, 'x');
  const std::string message = refusal(dir / "large");
  CHECK(message.find("it has 1001 bytes; a test file may have at most 1000") != std::string::npos);
  // A sparse file of 300 MiB costs no disk: refused from its size alone,
  // as a configuration or a linkage (256 MiB at most).
  { std::ofstream(dir / "sparse") << ""; }
  fs::resize_file(dir / "sparse", std::uintmax_t{300} << 20);
  for (const InputFileKind& kind : {kConfigurationFile, kLinkageFile}) {
    CAPTURE(kind.name);
    const auto start = std::chrono::steady_clock::now();
    const std::string big = refusal(dir / "sparse", kind);
    CHECK(big.find("it has 314572800 bytes; a " + std::string(kind.name) +
                   " may have at most 268435456 (256 MiB)") != std::string::npos);
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(2));
  }
  CHECK(kStateFile.max_bytes == std::uintmax_t{1} << 30);
}

TEST_CASE("input file: a NUL byte in the name is refused and not cut short") {
  const std::string name = std::string("/etc/hostname") + '\0' + "x";
  CHECK_THROWS_WITH_AS(read_input_file(name, kSmall, "cannot open test file"),
                       "cannot open test file: a file name cannot contain a NUL byte", InputError);
}

TEST_CASE("printable: control characters are escaped and long text shortened around an ellipsis") {
  CHECK(printable("plain text") == "plain text");
  CHECK(printable(std::string("a\0b", 3)) == "a\\0b");
  CHECK(printable("line\nnext\r\ttab\x01\x7f") == "line\\nnext\\r\\ttab\\x01\\x7f");
  const std::string long_text = std::string(1000, 'a') + "/grid.obj";
  const std::string shown = printable(long_text);
  CHECK(shown.size() == kMaxQuotedChars);
  CHECK(shown.find("...") != std::string::npos);
  CHECK(shown.substr(0, 5) == "aaaaa");
  CHECK(shown.substr(shown.size() - 9) == "/grid.obj");  // the end of a path is kept
  CHECK(printable(long_text, 10) == "aaaa...obj");
  // A UTF-8 character is never split: "é" is two bytes.
  std::string accents;
  for (int i = 0; i < 300; ++i) accents += "\xC3\xA9";
  const std::string cut = printable(accents, 11);
  CHECK(cut == "\xC3\xA9\xC3\xA9...\xC3\xA9\xC3\xA9");
  // Bounded whatever the input: 100 MB shown in at most 200 characters.
  CHECK(printable(std::string(100'000'000, 'p')).size() == kMaxQuotedChars);
}

}  // namespace xshell::test
