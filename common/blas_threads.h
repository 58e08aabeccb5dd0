// OpenBLAS's thread pool, where the system's BLAS is OpenBLAS built with
// pthreads (Debian's libopenblas0-pthread, which e.g. the lammps and yade
// packages install). granasym reaches BLAS only through Ceres and SuiteSparse
// in calibration, on problems far too small for threads; but the pool starts
// when the library loads, and each of its threads spins in sched_yield for
// 2^28 time-stamp ticks (about 0.1 s) before it sleeps. On a 2-core machine
// that spin takes a core from a 2-thread DEM run: in a run of half a second
// on 2 threads it made one run in two about a quarter slower
// (bench/README.md, eighth round).
#pragma once

namespace granasym {

enum class BlasPool {
  kAbsent,      // no OpenBLAS in the process: nothing to do
  kNoPool,      // OpenBLAS built serial or with OpenMP: no pool of its own (and its
                // openblas_set_num_threads would set the process's OpenMP default)
  kLeftToUser,  // OPENBLAS_NUM_THREADS (or GOTO_NUM_THREADS) is set: the user's choice stands
  kStopped,     // OpenBLAS set to one thread and its pool's threads ended
};

// Keeps OpenBLAS on the calling thread: sets it to one thread and ends its
// pool (a later threaded call would start the pool again; with one thread
// there is none). Call first in main, before any other thread exists.
BlasPool KeepBlasSerial();

}  // namespace granasym
