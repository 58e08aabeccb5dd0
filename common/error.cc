#include "common/error.h"

namespace granasym::internal {

CheckFailure::CheckFailure(const char* file, int line, const char* condition)
    : file_(file), line_(line), condition_(condition) {}

CheckFailure::~CheckFailure() noexcept(false) {
  std::ostringstream out;
  out << "internal check failed at " << file_ << ":" << line_ << ": (" << condition_ << ")";
  const std::string message = stream_.str();
  if (!message.empty()) out << ": " << message;
  throw InvariantError(out.str());
}

}  // namespace granasym::internal
