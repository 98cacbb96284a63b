// Atomic replacement of a file: the bytes go to a temporary file in the same
// directory, which is then renamed over the target (rename(2) is atomic within
// one file system). A reader, or a run interrupted at any moment, sees either
// the previous complete file or the new complete file, never a truncated one.
// On any failure the temporary file is removed and OutputError is thrown.
#pragma once

#include <filesystem>
#include <string_view>

namespace xshell {

// path: the target file; its directory must exist. bytes: the whole content.
// Throws OutputError naming `path` when the temporary file cannot be created
// or written, or the rename fails.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

// Whether `name` is the name of a temporary file made by write_file_atomically
// (".<target name>.tmp-<pid>-<count>"); lets tests and cleanup tools spot
// leftovers of a process that was killed between write and rename.
bool is_temporary_file_name(const std::string& name);

}  // namespace xshell
