// SIGINT/SIGTERM ask a running simulation or study to stop (it checkpoints,
// writes its results and the program exits with status 130). The flag is the
// program's; the libraries only see the stop requests of their options.
#pragma once

namespace granasym {

// Installs the handlers for its lifetime and restores the previous ones.
class SignalGuard {
 public:
  SignalGuard();
  ~SignalGuard();
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

// True once a signal arrived while a SignalGuard was installed.
bool InterruptRequested();

}  // namespace granasym
