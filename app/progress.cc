#include "app/progress.h"

#include <unistd.h>

namespace granasym {

Progress::Progress() : Progress(Options{}) {}

Progress::Progress(Options options)
    : options_(options),
      is_terminal_(isatty(fileno(stderr)) != 0),
      last_(std::chrono::steady_clock::now()) {}

bool Progress::Due() {
  if (options_.quiet) return false;
  const auto now = std::chrono::steady_clock::now();
  const double interval = is_terminal_ ? options_.terminal_interval_s : options_.plain_interval_s;
  if (std::chrono::duration<double>(now - last_).count() < interval) return false;
  last_ = now;
  return true;
}

void Progress::Report(const std::string& text) {
  if (options_.quiet) return;
  if (is_terminal_) {
    std::fprintf(stderr, "\r\033[K%s", text.c_str());
    line_open_ = true;
  } else {
    std::fprintf(stderr, "%s\n", text.c_str());
  }
  std::fflush(stderr);
}

void Progress::Finish() {
  if (line_open_) std::fprintf(stderr, "\n");
  line_open_ = false;
}

}  // namespace granasym
