#include "app/signals.h"

#include <csignal>

namespace granasym {
namespace {
volatile std::sig_atomic_t g_interrupt = 0;
extern "C" void HandleSignal(int) { g_interrupt = 1; }
}  // namespace

SignalGuard::SignalGuard() {
  g_interrupt = 0;
  previous_int_ = std::signal(SIGINT, HandleSignal);
  previous_term_ = std::signal(SIGTERM, HandleSignal);
}

SignalGuard::~SignalGuard() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

bool InterruptRequested() { return g_interrupt != 0; }

}  // namespace granasym
