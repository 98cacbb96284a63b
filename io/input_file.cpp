#include "input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "input_error.hpp"

namespace xshell {
namespace {

// Why a file of this mode is not read, or "" for a regular file.
std::string refusal(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "it is a folder, not a file";
  if (S_ISFIFO(mode)) return "it is a FIFO (named pipe), not a regular file";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "it is a device, not a regular file";
  if (S_ISSOCK(mode)) return "it is a socket, not a regular file";
  return "it is not a regular file";
}

std::string too_large(std::uintmax_t bytes, const InputFileKind& kind, bool at_least) {
  return (at_least ? "it has more than " : "it has ") + std::to_string(bytes) + " bytes; a " +
         kind.name + " may have at most " + std::to_string(kind.max_bytes) + " (" +
         std::to_string(kind.max_bytes >> 20) + " MiB)";
}

// Closes the descriptor on every path out.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

std::string read_input_file(const std::string& path, const InputFileKind& kind,
                            const std::string& failure) {
  auto fail = [&](const std::string& reason) { throw InputError(failure + ": " + reason); };
  if (path.find('\0') != std::string::npos) fail("a file name cannot contain a NUL byte");
  // Looked at before opening: opening a device or a FIFO may block or act.
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) fail(std::strerror(errno));
  if (const std::string why = refusal(info.st_mode); !why.empty()) fail(why);
  // Non-blocking, so that a file replaced by a FIFO since stat() cannot
  // block the open; checked again on the descriptor.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK));
  if (fd.get() < 0) fail(std::strerror(errno));
  if (::fstat(fd.get(), &info) != 0) fail(std::strerror(errno));
  if (const std::string why = refusal(info.st_mode); !why.empty()) fail(why);
  const auto size = static_cast<std::uintmax_t>(info.st_size);
  if (size > kind.max_bytes) fail(too_large(size, kind, false));

  // Read to the end, whatever the size said (a file may grow, /proc files
  // say 0), but never past the limit.
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(std::string("read error: ") + std::strerror(errno));
    }
    if (n == 0) break;
    if (text.size() + static_cast<std::size_t>(n) > kind.max_bytes)
      fail(too_large(kind.max_bytes, kind, true));
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace xshell
