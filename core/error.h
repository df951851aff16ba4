// Errors in what a user handed hpsf (an option, a file, a record): the command line reports the message,
// which names the option or the file and place, and exits with code 3.
#ifndef HPSF_CORE_ERROR_H
#define HPSF_CORE_ERROR_H

#include <stdexcept>
#include <string>

namespace hpsf {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An invalid FilterConfig value; the message starts with the option's name, e.g. "--fingerprint-bits: ...".
class ConfigError : public InputError {
 public:
  ConfigError(const std::string& option, const std::string& problem) : InputError(option + ": " + problem) {}
};

// A check failed where the command cannot go on (a HashCache update the checker refutes in the middle of a sweep):
// main prints the message and exits kExitCheckFailed, with no output of the run that failed.
class CheckFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr int kExitOk = 0;
inline constexpr int kExitWarn = 1;
inline constexpr int kExitCheckFailed = 2;
inline constexpr int kExitBadInput = 3;
// hpsf itself failed: an exception escaped a command (a bug in hpsf, or a resource it could not get). main prints
// the message; no verdict was reached. A signal that ends the process is reported by the gate as a crash.
inline constexpr int kExitInternalError = 4;

}  // namespace hpsf

#endif  // HPSF_CORE_ERROR_H
