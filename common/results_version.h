// What decides a cached result besides its inputs. A study keys every case
// on its canonical scene, its parent's key, its thread count and this
// results key (study/plan.h), not on the program version: a commit that
// changes no result (documentation, figures, the report, calibration)
// keeps every cached case.
//
// kResultsVersion is raised whenever a change of the code changes what a run
// computes: the DEM's positions, stresses and detected states, the sample
// generator's packings, or a model's element test. tests/dem/
// golden_results_test.cc ties it to golden outputs (a short run of each
// contact law and each stage type, and a model element test): a change of
// results without a new version fails the test suite, and raising the
// version asks for new golden values (see that test).
#pragma once

#include <string>

namespace granasym {

inline constexpr int kResultsVersion = 1;

// "results v1; GNU 12.2.0; Release; x86_64 avx2 fma": the version and the
// build options that change rounding (compiler and its version, build type,
// the instruction sets the build targets, e.g. FMA contraction).
std::string ResultsKey();

}  // namespace granasym
