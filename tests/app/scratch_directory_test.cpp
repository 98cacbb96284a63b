// The tests' scratch directories (tests/scratch_directory.hpp): fresh,
// private, and gone at scope exit whatever their content's permissions.
#include "scratch_directory.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>

#include "skip.hpp"

namespace xshell::test {

namespace fs = std::filesystem;

TEST_CASE("scratch directory: fresh, private, and removed with read-only content") {
  if (std::getenv("XSHELL_KEEP_TEST_FILES")) XSHELL_SKIP("XSHELL_KEEP_TEST_FILES keeps them");
  fs::path first, second;
  {
    const ScratchDirectory a("scratch"), b("scratch");
    first = a.path();
    second = b.path();
    CHECK(first != second);
    CHECK(first.parent_path() == fs::temp_directory_path());
    CHECK(first.filename().string().rfind("xshell-test-scratch-", 0) == 0);
    REQUIRE(fs::is_directory(first));
    CHECK(fs::is_empty(first));
    CHECK((fs::status(first).permissions() & fs::perms::all) == fs::perms::owner_all);
    fs::create_directories(a / "locked" / "deeper");
    std::ofstream(a / "locked" / "deeper" / "file.txt") << "text";
    fs::permissions(a / "locked" / "deeper", fs::perms::owner_read | fs::perms::owner_exec);
    fs::permissions(a / "locked", fs::perms::none);
    fs::permissions(first, fs::perms::owner_read | fs::perms::owner_exec);
  }
  CHECK(!fs::exists(first));
  CHECK(!fs::exists(second));
}

TEST_CASE("scratch directory: remove_all removes the ones in scope (a skipped case's)") {
  if (std::getenv("XSHELL_KEEP_TEST_FILES")) XSHELL_SKIP("XSHELL_KEEP_TEST_FILES keeps them");
  const ScratchDirectory a("scratch-live");
  std::ofstream(a / "file.txt") << "text";
  REQUIRE(fs::exists(a / "file.txt"));
  ScratchDirectory::remove_all();
  CHECK(!fs::exists(a.path()));
}

}  // namespace xshell::test
