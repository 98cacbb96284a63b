// The one exception type for output that could not be written: a VTK file, a
// .pvd collection, a picture. Its message names the path that failed and why
// (e.g. "cannot write '/runs/a/rods_000003.vtp': Permission denied"), so the
// command line can show it to the user as it is.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace xshell {

class OutputError : public std::runtime_error {
 public:
  // path: the file (or directory) that could not be written; reason: why.
  OutputError(const std::filesystem::path& path, const std::string& reason);

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace xshell
