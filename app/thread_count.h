// Thread counts of the command line: more threads than the hardware has only
// make a run slower (each waits for a core), so a larger request is capped
// with a warning.
#pragma once

#include <cstdio>

#include "common/provenance.h"

namespace granasym {

inline int CapThreads(int requested, const char* flag) {
  const int hardware = HardwareThreads();
  if (requested <= hardware) return requested;
  std::fprintf(stderr,
               "warning: %s %d is more than the %d hardware threads of this machine: using %d\n",
               flag, requested, hardware, hardware);
  return hardware;
}

}  // namespace granasym
