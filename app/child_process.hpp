// A child process run from an argument vector (no shell), its standard input
// and output connected to this process by pipes and its standard error
// discarded. It runs in a process group of its own, so that a terminal's
// Ctrl-C reaches only xshell, which decides what the child does next; and
// when xshell dies, the child reads the end of its input. The destructor
// closes both pipes and waits for the child to end.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace xshell {

class ChildProcess {
 public:
  // Starts argv (argv[0] looked up on PATH) with `environment` (NAME=VALUE
  // entries); running() is false when it could not be started.
  ChildProcess(const std::vector<std::string>& argv, const std::vector<std::string>& environment);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool running() const { return pid_ > 0; }
  // The next line of its output without the newline; "" at its end.
  std::string read_line();
  // Writes `text` to its input; false when it has closed it.
  bool write(const std::string& text);
  // Closes its input and waits; its exit status, or -1 when it was killed
  // by a signal or never started.
  int wait();

 private:
  pid_t pid_ = -1;
  int input_ = -1, output_ = -1;  // our ends of its stdin and stdout
  int status_ = -1;
};

// This process's environment with `name`=`value` set (replacing any entry
// of that name).
std::vector<std::string> environment_with(const std::string& name, const std::string& value);

}  // namespace xshell
