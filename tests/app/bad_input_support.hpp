// Helpers of the bad-input command tests (bad_input_test.cpp,
// bad_files_test.cpp): a rejected run's checks, and runs of the real program
// on a bad linkage or configuration written to a scratch directory.
#pragma once

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "reliability_support.hpp"

namespace xshell::test {

// A rejected run: status 2, one line naming what is wrong (every word of
// `words`), and no output directory.
inline void check_rejected(const CommandResult& r, const fs::path& dir,
                           const std::vector<std::string>& words) {
  INFO("stderr: " << r.errors);
  CHECK(r.status == 2);
  CHECK(r.errors.rfind("xshell: error: ", 0) == 0);
  CHECK(count_lines(r.errors) == 1);
  for (const auto& w : words) CHECK_MESSAGE(contains(r.errors, w), "missing: " << w);
  CHECK_FALSE(fs::exists(dir / "out"));
}

// Relaxes the OBJ `text` (as bad.obj) with the sample's material.
inline CommandResult relax_obj(const ScratchDirectory& dir, const std::string& text) {
  write_text(dir / "bad.obj", text);
  write_text(dir / "run.json", config_with("bad.obj"));
  return run_xshell("relax run.json", dir.path());
}

// Relaxes the configuration `text` (as run.json).
inline CommandResult relax_config(const ScratchDirectory& dir, const std::string& text,
                                  const std::string& options = "") {
  write_text(dir / "run.json", text);
  return run_xshell("relax run.json " + options, dir.path());
}

// The grid sample's configuration with `extra` keys.
inline std::string grid_config(const std::string& extra = "") {
  return config_with(grid_obj(), extra);
}

// `text` with the first `from` replaced by `to` (which must be there).
inline std::string replacing(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// grid_config() with the first `from` replaced by `to` (which must be there).
inline std::string grid_config_replacing(const std::string& from, const std::string& to,
                                         const std::string& extra = "") {
  return replacing(grid_config(extra), from, to);
}

inline const char* const kCross =  // one X joint (vertex 2), four free ends
    "v -1 -1 0\nv 1 1 0\nv 0 0 0\nv 1 -1 0\nv -1 1 0\n";

}  // namespace xshell::test
