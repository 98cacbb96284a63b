// xshell and xshell-full (app/full_program.hpp): xshell runs relax and
// fabricate without loading VTK's rendering libraries or IPOPT, and hands
// render and design to xshell-full beside it.
#include <doctest/doctest.h>

#include <cstdio>
#include <memory>

#include "reliability_support.hpp"
#include "skip.hpp"

namespace xshell::test {

namespace {

// The shared libraries a program names (readelf -d), one per line, or
// nullopt when readelf cannot be run.
std::optional<std::string> needed_libraries(const fs::path& program) {
  const std::string command = "readelf -d '" + program.string() + "' 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return std::nullopt;
  std::string out;
  char line[4096];
  while (std::fgets(line, sizeof line, pipe.get()))
    if (contains(line, "(NEEDED)")) out += line;
  if (out.empty()) return std::nullopt;
  return out;
}

}  // namespace

TEST_CASE("xshell names neither VTK's rendering libraries nor IPOPT, xshell-full both") {
  const fs::path lean = XSHELL_BINARY, full = fs::path(XSHELL_BINARY).parent_path() / "xshell-full";
  const auto lean_needs = needed_libraries(lean), full_needs = needed_libraries(full);
  if (!lean_needs || !full_needs) return report_skip("readelf cannot be run here");
  INFO("xshell needs:\n" << *lean_needs);
  for (const char* part : {"Rendering", "ipopt", "X11", "GLEW"})
    CHECK_MESSAGE(!contains(*lean_needs, part), part);
  CHECK(contains(*lean_needs, "cholmod"));
  CHECK(contains(*lean_needs, "vtkIOXML"));
  INFO("xshell-full needs:\n" << *full_needs);
  CHECK(contains(*full_needs, "Rendering"));
  CHECK(contains(*full_needs, "ipopt"));
}

TEST_CASE("xshell hands render and design to xshell-full beside it, and says so without it") {
  ScratchDirectory dir("full-program");
  const fs::path alone = dir / "alone";
  fs::create_directory(alone);
  fs::copy_file(XSHELL_BINARY, alone / "xshell");
  auto run = [&](const std::string& args) {
    return run_program(alone / "xshell", args, dir.path());
  };
  for (const char* command : {"render missing.vtp --out p.png", "design missing.json"}) {
    const CommandResult r = run(command);
    INFO(command << ": " << r.errors);
    CHECK(r.status == 1);
    CHECK(r.errors.rfind("xshell: error: ", 0) == 0);
    CHECK(count_lines(r.errors) == 1);
    CHECK(contains(r.errors, (alone / "xshell-full").string()));
  }
  // Its own commands and usage errors need no xshell-full.
  CHECK(run("--version").status == 0);
  CHECK(run("render").status == 2);  // the inputs are missing: caught before handing over
  // With xshell-full beside it, the same commands reach it: a missing input
  // file is invalid input (status 2), said by xshell-full.
  fs::create_symlink(fs::path(XSHELL_BINARY).parent_path() / "xshell-full", alone / "xshell-full");
  for (const char* command : {"render missing.vtp --out p.png", "design missing.json"}) {
    const CommandResult r = run(command);
    INFO(command << ": " << r.errors);
    CHECK(r.status == 2);
    CHECK(contains(r.errors, "missing"));
    CHECK(!contains(r.errors, "xshell-full"));
  }
}

}  // namespace xshell::test
