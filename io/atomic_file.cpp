#include "atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include "output_error.hpp"

namespace xshell {
namespace {

constexpr const char* kTemporaryTag = ".tmp-";

// Owns a temporary file until commit(): removed on every other path out.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::filesystem::path& target) : target_(target) {
    static std::atomic<unsigned long> counter{0};
    const std::string name = "." + target.filename().string() + kTemporaryTag +
                             std::to_string(::getpid()) + "-" + std::to_string(counter++);
    path_ = target.parent_path() / name;
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    if (!committed_) {
      std::error_code ignored;
      std::filesystem::remove(path_, ignored);
    }
  }

  void write(std::string_view bytes) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    if (!out) throw OutputError(target_, std::strerror(errno));
    errno = 0;
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    // The system's reason when it gave one (a full disk: "No space left on
    // device"; a file size limit: "File too large").
    if (!out)
      throw OutputError(target_, "write to temporary file '" + path_.string() + "' failed" +
                                     (errno != 0 ? std::string(": ") + std::strerror(errno) : ""));
  }

  void commit() {
    std::error_code error;
    std::filesystem::rename(path_, target_, error);
    if (error) throw OutputError(target_, error.message());
    committed_ = true;
  }

 private:
  std::filesystem::path target_;
  std::filesystem::path path_;
  bool committed_ = false;
};

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  if (path.filename().empty()) throw OutputError(path, "not a file name");
  TemporaryFile temporary(path);
  temporary.write(bytes);
  temporary.commit();
}

bool is_temporary_file_name(const std::string& name) {
  return !name.empty() && name.front() == '.' && name.find(kTemporaryTag) != std::string::npos;
}

}  // namespace xshell
