// Errors: an always-on check macro for programming errors and the exception
// type for bad user input (scene files, tables, CSV data, flags).
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

// A failure of the program itself or of a library call (HDF5, the file system).
class RuntimeError : public std::runtime_error {
 public:
  explicit RuntimeError(const std::string& message) : std::runtime_error(message) {}
};

namespace internal {
// Collects the message of a failed check and throws RuntimeError when the
// full statement has been streamed (at the end of the full expression).
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
