// Skipping a test case that cannot run here (the shared data folder is
// absent, there is no display, the tests run as root): CTest reports it as
// skipped instead of passed. CTest runs every case in a process of its own
// with XSHELL_TEST_SKIP_CODE set (tests/CMakeLists.txt, SKIP_RETURN_CODE);
// the process then ends with that code. Run by hand (the variable unset),
// the case only prints why and returns, and the program goes on.
#pragma once

#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "scratch_directory.hpp"

namespace xshell::test {

// Prints why the current case is skipped and, under CTest, ends the process
// with the skip code. Returns only when not run by CTest.
inline void report_skip(const std::string& reason) {
  std::printf("SKIPPED: %s\n", reason.c_str());
  std::fflush(stdout);
  if (const char* code = std::getenv("XSHELL_TEST_SKIP_CODE")) {
    ScratchDirectory::remove_all();
    std::exit(std::atoi(code));
  }
}

}  // namespace xshell::test

// Use as a statement in a test case: XSHELL_SKIP("why");
#define XSHELL_SKIP(reason)              \
  do {                                   \
    ::xshell::test::report_skip(reason); \
    return;                              \
  } while (false)
