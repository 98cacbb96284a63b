#include "full_program.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>

#include "exit_status.hpp"

namespace xshell {

int run_in_full_program(char** argv) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) {
    std::cerr << "xshell: error: cannot find this program's own path to run " << kFullProgramName
              << " beside it (" << error.message() << ")\n";
    return kExitInternalError;
  }
  const std::string full = (self.parent_path() / kFullProgramName).string();
  execv(full.c_str(), argv);
  std::cerr << "xshell: error: this command runs in " << full << ", which could not be started ("
            << std::strerror(errno) << "): install it beside xshell\n";
  return kExitInternalError;
}

}  // namespace xshell
