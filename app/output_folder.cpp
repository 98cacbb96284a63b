#include "output_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "io/input_error.hpp"
#include "io/output_error.hpp"

namespace xshell {

namespace fs = std::filesystem;

namespace {

constexpr const char* kLockName = ".xshell-lock";

// Every fixed name a run (relax, fabricate or design) writes into its folder.
constexpr std::array<const char*, 16> kFixedNames = {
    "series.pvd",      "state.json",          "summary.json",    "reactions.vtp",
    "stresses.vtp",    "joint_forces.vtp",    "modes.vtp",       "fabrication.json",
    "fabrication.csv", "fabrication.svg",     "deployment.csv",  "deployment.png",
    "design.json",     "deployed_state.json", "flat_state.json", "flat_layout.obj"};

// rods_NNNNNN.vtp, frames_..., joints_..., solids_...: a series' step file
// (six digits or more).
bool is_step_file_name(const std::string& name) {
  for (const char* part : {"rods_", "frames_", "joints_", "solids_"}) {
    const std::string prefix = part;
    if (name.rfind(prefix, 0) != 0 || name.size() < prefix.size() + 6 + 4) continue;
    if (name.compare(name.size() - 4, 4, ".vtp") != 0) continue;
    const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - 4);
    bool all = true;
    for (char c : digits) all = all && std::isdigit(static_cast<unsigned char>(c));
    if (all) return true;
  }
  return false;
}

}  // namespace

bool is_output_file_name(const std::string& name) {
  for (const char* fixed : kFixedNames)
    if (name == fixed) return true;
  return is_step_file_name(name);
}

std::string input_collision(const fs::path& input, const std::string& what,
                            const fs::path& directory) {
  std::error_code error;
  const fs::path name = input.filename();
  if (!is_output_file_name(name.string())) {
    // A link to an output under another name: compare the files.
    if (!fs::is_directory(directory, error)) return "";
    for (const auto& entry : fs::directory_iterator(directory, error)) {
      const std::string entry_name = entry.path().filename().string();
      if (is_output_file_name(entry_name) && fs::equivalent(entry.path(), input, error))
        return what + " '" + printable(input.string()) + "' is the output file '" +
               printable(entry_name) + "' of the output directory '" +
               printable(directory.string()) +
               "', which the run would replace: choose another output directory (--out)";
    }
    return "";
  }
  const fs::path folder = input.has_parent_path() ? input.parent_path() : fs::path(".");
  if (!fs::exists(directory, error) || !fs::equivalent(folder, directory, error)) return "";
  return what + " '" + printable(input.string()) + "' is in the output directory '" +
         printable(directory.string()) + "' under a name the run writes (" +
         printable(name.string()) +
         "), so the run would replace it: choose another output directory (--out) or rename it";
}

OutputFolderLock::OutputFolderLock(const fs::path& directory) {
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) throw OutputError(directory, error.message());
  const fs::path lock = directory / kLockName;
  fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw OutputError(lock, std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int cause = errno;
    ::close(fd_);
    fd_ = -1;
    throw OutputError(directory, cause == EWOULDBLOCK
                                     ? "another xshell run is writing to this output directory "
                                       "(it holds " +
                                           std::string(kLockName) +
                                           "): wait for it, or choose another (--out)"
                                     : std::string(std::strerror(cause)));
  }
}

OutputFolderLock::~OutputFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

int remove_stale_outputs(const fs::path& directory) {
  std::error_code error;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(directory, error))
    if (entry.is_regular_file(error) && is_output_file_name(entry.path().filename().string()))
      stale.push_back(entry.path());
  if (error) throw OutputError(directory, error.message());
  for (const fs::path& path : stale) {
    fs::remove(path, error);
    if (error) throw OutputError(path, "cannot remove the earlier run's file: " + error.message());
  }
  return static_cast<int>(stale.size());
}

}  // namespace xshell
