// Runs a program and collects what it printed: `hpsf golden` renders each case with the hpsf binary itself, as
// `hpsf render` or `hpsf replay` would be run by hand, so a golden case is exactly a command line.
#ifndef HPSF_TOOLS_HPSF_SUBPROCESS_H
#define HPSF_TOOLS_HPSF_SUBPROCESS_H

#include <string>
#include <vector>

namespace hpsf {

struct ProcessResult {
  int exit_code = -1;  // the program's exit status, or 128 + the signal that ended it
  int signal = 0;      // the signal that ended it, 0 when it exited
  std::string output;  // stdout and stderr together, or stderr alone when stdout went to a file
};

// argv[0] is the program's path; it runs in `folder` (empty: this process's). With `stdout_file`, its stdout is
// written there (created or truncated), so a report it prints is not interleaved with what it says on stderr.
// Throws std::runtime_error when it cannot be started.
ProcessResult RunProcess(const std::vector<std::string>& argv, const std::string& folder = "",
                         const std::string& stdout_file = "");

// This program's own path (/proc/self/exe).
std::string SelfPath();

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_SUBPROCESS_H
