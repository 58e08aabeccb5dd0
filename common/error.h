// Errors, in three kinds that callers treat differently:
//  - InputError: bad user input (scene files, tables, CSV data, flags);
//  - RuntimeError: a numerical failure or a failed library call, which a run
//    loop reports as a failed run with its results so far; its FileError: a
//    file that cannot be written (a full disk, a size limit), which ends the
//    command (status 1) with what was kept;
//  - InvariantError: a programming error (a violated invariant, thrown by
//    GRANASYM_CHECK), which no run loop swallows.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace granasym {

// Bad user input. The message names the file, the key or line, the value and
// what would be valid; the command-line program prints it and exits non-zero.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// A numerical failure, or a failed call of a library (HDF5) or of the file system.
class RuntimeError : public std::runtime_error {
 public:
  explicit RuntimeError(const std::string& message) : std::runtime_error(message) {}
};

// A file that cannot be created, written or renamed into place (no space left,
// a file-size limit, no permission). The message names the file and the
// system's reason; the writer has removed its temporary file and left the file
// under the final name as it was. Not a failure of the run: a run loop does
// not turn it into a failed run (nothing could record one), it ends the
// command and says what was kept.
class FileError : public RuntimeError {
 public:
  explicit FileError(const std::string& message) : RuntimeError(message) {}
};

// A violated invariant: a bug in granasym, never a property of the input.
class InvariantError : public std::logic_error {
 public:
  explicit InvariantError(const std::string& message) : std::logic_error(message) {}
};

namespace internal {
// Collects the message of a failed check and throws when the
// full statement has been streamed (at the end of the full expression).
// Throws InvariantError.
class CheckFailure {
 public:
  CheckFailure(const char* file, int line, const char* condition);
  ~CheckFailure() noexcept(false);
  std::ostringstream& stream() { return stream_; }

 private:
  const char* file_;
  int line_;
  const char* condition_;
  std::ostringstream stream_;
};
}  // namespace internal

}  // namespace granasym

// Always-on invariant check with a streamed message:
//   GRANASYM_CHECK(n > 0) << "cell has no particles";
// The message is built only when the check fails.
#define GRANASYM_CHECK(condition) \
  if (condition) {                \
  } else                          \
    ::granasym::internal::CheckFailure(__FILE__, __LINE__, #condition).stream()
