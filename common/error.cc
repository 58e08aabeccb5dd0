#include "common/error.h"

namespace granasym::internal {

void FailCheck(const char* file, int line, const char* condition, const std::string& message) {
  std::ostringstream out;
  out << "internal check failed at " << file << ":" << line << ": (" << condition << ")";
  if (!message.empty()) out << ": " << message;
  throw RuntimeError(out.str());
}

}  // namespace granasym::internal
