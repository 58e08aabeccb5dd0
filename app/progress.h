// Progress of long runs on the command line: an updating status line on a
// terminal, plain periodic lines otherwise (logs, CI), rate-limited by
// wall-clock time. The libraries never print; they hand text to the program.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace granasym {

class Progress {
 public:
  struct Options {
    // Seconds between plain lines when stderr is not a terminal.
    double plain_interval_s = 10.0;
    // Seconds between updates of the status line on a terminal.
    double terminal_interval_s = 0.25;
    bool quiet = false;  // report nothing
  };

  explicit Progress(Options options);
  Progress();
  // True when an update is due; cheap to call every step.
  bool Due();
  // Prints `text` (one line, no newline) as the status line or a plain line.
  void Report(const std::string& text);
  // Ends the status line (terminal) before other output.
  void Finish();
  bool is_terminal() const { return is_terminal_; }

 private:
  Options options_;
  bool is_terminal_;
  bool line_open_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace granasym
