// Output that cannot be written: OutputError naming the path, and nothing
// left behind, neither the target nor a temporary file.
#include <doctest/doctest.h>

#include <fstream>

#include "demo_snapshot.hpp"
#include "io/atomic_file.hpp"
#include "io/output_error.hpp"
#include "io/vtk/rods_file.hpp"
#include "io/vtk/vtk_series.hpp"
#include "vtk_test_support.hpp"

namespace xshell::test {
namespace {

// Runs `write`, which must throw OutputError whose message contains `path`.
template <class Write>
void check_output_error(Write&& write, const std::filesystem::path& path, int& checks) {
  bool thrown = false;
  try {
    write();
  } catch (const OutputError& e) {
    thrown = true;
    CAPTURE(e.what());
    XSHELL_COUNTED_CHECK(checks, std::string(e.what()).find(path.string()) != std::string::npos);
    XSHELL_COUNTED_CHECK(checks, e.path() == path);
  }
  XSHELL_COUNTED_CHECK(checks, thrown);
}

// Whether a file can be created in `directory` (root ignores permissions).
bool can_create_in(const std::filesystem::path& directory) {
  const auto probe = directory / "probe";
  const bool ok = static_cast<bool>(std::ofstream(probe));
  std::filesystem::remove(probe);
  return ok;
}

}  // namespace

TEST_CASE("atomicity: a read-only directory throws OutputError and leaves nothing") {
  ScratchDirectory dir("readonly");
  const auto locked = dir.path() / "locked";
  std::filesystem::create_directory(locked);
  std::filesystem::permissions(
      locked, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (can_create_in(locked)) {
    MESSAGE(
        "running with privileges that ignore directory permissions (root?): "
        "the read-only directory case is not checked here; the cases below are");
    return;
  }
  int checks = 0;
  const auto path = locked / "rods.vtp";
  check_output_error([&] { write_rods_file(demo_snapshot(), path); }, path, checks);
  XSHELL_COUNTED_CHECK(checks, std::filesystem::is_empty(locked));
  CHECK(checks == 4);
}

TEST_CASE("atomicity: a directory that cannot exist throws OutputError and leaves nothing") {
  // A parent that is a regular file: not writable, whoever runs the test.
  ScratchDirectory dir("notadir");
  const auto blocker = dir.path() / "blocker";
  std::ofstream(blocker) << "a file, not a directory\n";
  int checks = 0;
  const auto path = blocker / "rods.vtp";
  check_output_error([&] { write_rods_file(demo_snapshot(), path); }, path, checks);
  check_output_error([&] { VtkSeries series(blocker / "run"); }, blocker / "run", checks);
  XSHELL_COUNTED_CHECK(checks, file_names(dir.path()) == std::set<std::string>{"blocker"});
  CHECK(checks == 3 + 3 + 1);
}

TEST_CASE("atomicity: a failed rename removes the temporary file") {
  // The target name is taken by a directory: the temporary file is written,
  // then rename(2) fails.
  ScratchDirectory dir("rename");
  const auto path = dir.path() / "rods.vtp";
  std::filesystem::create_directory(path);
  int checks = 0;
  check_output_error([&] { write_rods_file(demo_snapshot(), path); }, path, checks);
  XSHELL_COUNTED_CHECK(checks, file_names(dir.path()).empty());  // no temporary file
  XSHELL_COUNTED_CHECK(checks, std::filesystem::is_directory(path));
  CHECK(checks == 5);
}

TEST_CASE("atomicity: a failed step leaves the series index and directory consistent") {
  ScratchDirectory dir("series_fail");
  VtkSeries series(dir.path());
  REQUIRE(series.write(demo_snapshot(0.0), true));
  // Block the solids file of step 1: rods, frames and joints of that step are
  // written first and must be removed again.
  std::filesystem::create_directory(dir.path() / "solids_000001.vtp");
  int checks = 0;
  const auto blocked = dir.path() / "solids_000001.vtp";
  check_output_error([&] { series.write(demo_snapshot(1.0), true); }, blocked, checks);
  XSHELL_COUNTED_CHECK(checks, std::filesystem::is_directory(blocked));  // not ours to remove
  XSHELL_COUNTED_CHECK(checks, series.steps_written() == 1);
  XSHELL_COUNTED_CHECK(checks, series.entries().size() == 4);
  XSHELL_COUNTED_CHECK(
      checks, file_names(dir.path()) ==
                  std::set<std::string>{"rods_000000.vtp", "frames_000000.vtp", "joints_000000.vtp",
                                        "solids_000000.vtp", "series.pvd"});
  // Once the obstacle is gone the same step number is written.
  std::filesystem::remove(blocked);
  XSHELL_COUNTED_CHECK(checks, series.write(demo_snapshot(1.0), true));
  XSHELL_COUNTED_CHECK(checks, std::filesystem::is_regular_file(blocked));
  CHECK(checks == 3 + 6);
}

TEST_CASE("atomicity: write_file_atomically replaces content whole") {
  ScratchDirectory dir("replace");
  const auto path = dir.path() / "a.txt";
  write_file_atomically(path, "first version, longer than the second\n");
  write_file_atomically(path, "second\n");
  std::ifstream in(path);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(content == "second\n");
  CHECK(file_names(dir.path()) == std::set<std::string>{"a.txt"});
  CHECK(is_temporary_file_name(".a.txt.tmp-123-4"));
  CHECK_FALSE(is_temporary_file_name("a.txt"));
}

}  // namespace xshell::test
