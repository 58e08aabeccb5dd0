// Where a DEM run starts: a new sample (generated from the scene's GSD or read
// from its packing), or the saved state of another run that the scene forks
// from (`[sample] state`, and `stage`); either with the provenance of its
// start (a SHA-256 of the packing or of the parent's engine state); and the
// lines the run's log starts with.
#pragma once

#include <string>
#include <vector>

#include "dem/engine.h"
#include "dem/run_files.h"
#include "dem/scene.h"

namespace granasym::dem {

// The provenance of a run of `scene` on `threads` threads, without its start:
// the program version, the canonical scene and its SHA-256, the CPU.
Provenance RunProvenance(const Scene& scene, int threads);

// The scene's own sample into contents->sample (and generation), and the
// provenance of that start.
void StartFromSample(const Scene& scene, RunContents* contents);

// A scene that starts where another run stopped: the parent's sample into
// `contents` (so that the engine orders the particles and sums the solid
// volume as the parent did, and strains count from the same origin), the
// provenance of the fork, and the exact engine state it continues: the
// parent's final state, or the end state of its stage scene.parent->stage.
// InputError when the parent is not a result file or that state cannot be
// continued.
Engine::State StartFromParent(const Scene& scene, RunContents* contents);

// The run's first lines: the spheres and threads, the time step against the
// contact durations of `sample`, the time-step rule ("fixed" or
// AdaptiveTimeStep::Describe()) and, when scaled, the contact stiffness.
std::vector<std::string> StartLines(const Scene& scene, const Packing& sample, int threads,
                                    double time_step, const std::string& time_step_rule);

}  // namespace granasym::dem
