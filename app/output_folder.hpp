// The output folder of a run: one writer at a time, no file of an earlier
// run left to be mistaken for this one's, and never an input overwritten.
//
//   - A lock: the run holds an exclusive flock(2) on DIR/.xshell-lock while
//     it writes; a second run on the same folder is refused (exit status 4)
//     before it touches anything. The system drops the lock when the run
//     ends in any way (SIGKILL included): a stale lock cannot exist.
//   - Stale outputs: before writing, a run removes from the folder every
//     file that an xshell run writes (output_file_names(), the step files
//     rods_NNNNNN.vtp, frames_, joints_, solids_ of a series), and nothing
//     else: a longer earlier run's later steps, or its engineering results,
//     would otherwise pass for this run's.
//   - Inputs: a configuration, linkage or --init state that is one of those
//     files (the same file, links followed) is refused (exit status 2)
//     before anything is written.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace xshell {

// Whether `name` (a file name, no folder) is one that a run writes.
bool is_output_file_name(const std::string& name);

// Returns "" or, when `input` is a file that writing outputs to `directory`
// would replace or remove, the reason in one line ("'state.json' is an
// output of a run into 'DIR'..."). `what` names the input ("the linkage").
std::string input_collision(const std::filesystem::path& input, const std::string& what,
                            const std::filesystem::path& directory);

// The exclusive lock of an output folder (created if needed). Throws
// OutputError when the folder cannot be made or locked, naming the folder
// and, when another run holds it, saying so.
class OutputFolderLock {
 public:
  explicit OutputFolderLock(const std::filesystem::path& directory);
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

 private:
  int fd_ = -1;
};

// Removes the files of `directory` that a run writes (is_output_file_name);
// returns how many. Throws OutputError when one cannot be removed.
int remove_stale_outputs(const std::filesystem::path& directory);

}  // namespace xshell
