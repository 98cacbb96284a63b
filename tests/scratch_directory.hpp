// The tests' scratch space: a fresh directory of the current user's, made
// by mkdtemp under the system's temporary directory (TMPDIR, else /tmp), so
// that runs by other users or in parallel never meet, and removed with
// everything in it at scope exit (read-only parts made writable first: some
// tests take permissions away), or when a skipped case ends its process
// (tests/skip.hpp). With XSHELL_KEEP_TEST_FILES set the directory stays and
// its path is printed, to look at a test's files.
#pragma once

#include <doctest/doctest.h>
#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <system_error>
#include <vector>

namespace xshell::test {

class ScratchDirectory {
 public:
  // `name` (letters, digits, '-', '_') appears in the directory's name.
  explicit ScratchDirectory(const std::string& name) {
    const std::string pattern =
        (std::filesystem::temp_directory_path() / ("xshell-test-" + name + "-XXXXXX")).string();
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    REQUIRE_MESSAGE(::mkdtemp(buffer.data()) != nullptr, "mkdtemp " << pattern);
    path_ = buffer.data();
    live().insert(this);
  }
  ~ScratchDirectory() {
    live().erase(this);
    remove();
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

  // Removes every scratch directory still in scope (before the process ends
  // without unwinding).
  static void remove_all() {
    for (ScratchDirectory* d : live()) d->remove();
  }

 private:
  static std::set<ScratchDirectory*>& live() {
    static std::set<ScratchDirectory*> all;
    return all;
  }

  void remove() const {
    if (std::getenv("XSHELL_KEEP_TEST_FILES")) {
      std::printf("kept %s\n", path_.c_str());
      return;
    }
    namespace fs = std::filesystem;
    std::error_code ignored;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ignored);
    for (auto it = fs::recursive_directory_iterator(path_, ignored);
         it != fs::recursive_directory_iterator(); it.increment(ignored))
      if (it->is_directory(ignored))
        fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ignored);
    fs::remove_all(path_, ignored);
  }

  std::filesystem::path path_;
};

}  // namespace xshell::test
