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
[[noreturn]] void FailCheck(const char* file, int line, const char* condition,
                            const std::string& message);
}  // namespace internal

}  // namespace granasym

// Always-on invariant check with a streamed message:
//   GRANASYM_CHECK(n > 0) << "cell has no particles";
// The message is built only when the check fails.
#define GRANASYM_CHECK(condition)                                                  \
  for (std::ostringstream granasym_check_stream_; !(condition);                    \
       ::granasym::internal::FailCheck(__FILE__, __LINE__, #condition,             \
                                       granasym_check_stream_.str()))              \
  granasym_check_stream_
