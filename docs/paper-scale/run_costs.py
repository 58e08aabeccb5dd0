#!/usr/bin/env python3
"""Cost of each DEM case of a granasym study folder, from the files the run left.

Usage: run_costs.py STUDY_DIR [LOG] > run_costs.csv

STUDY_DIR  a study folder (cases/r<K>/<case>/{case.toml,done.toml,result.h5})
LOG        optional: the captured output of `granasym study run` (with
           `/usr/bin/time -v` appended); adds the per-case times it printed
           ("r1/x: computed in T s") and the run's elapsed and CPU time.

Writes one CSV row per DEM case to stdout and a summary (totals, medians,
range, the costliest cases) to stderr.

Steps: a forked case starts from its parent's saved state, so its engine step
counter (done.toml `steps`, result.h5 summary `steps`) includes the parent's
steps, which this case did not compute. The case's own steps are the engine
steps less the step of its first output row (series/step[0]); these are the
steps it computed, and what `granasym study status` calls "steps of their own".
Cost: us_per_particle_step = wall_s * threads / (particles * own_steps) * 1e6,
wall_s from done.toml (the whole case: reading the parent, the loop, writing).
"""
import csv
import glob
import os
import re
import statistics
import sys
import tomllib

import h5py


def read_toml(path):
    with open(path, "rb") as f:
        return tomllib.load(f)


def read_log(path):
    """Per-case times, the total line and /usr/bin/time numbers of a run log."""
    case_wall, total = {}, {}
    with open(path, errors="replace") as f:
        for line in f:
            m = re.match(r"^(\S+/\S+): computed in ([0-9.]+) s", line)
            if m:
                case_wall[m.group(1)] = float(m.group(2))
            m = re.match(r"^(\d+) cases in ([0-9.]+) s", line)
            if m:
                total["cases"], total["study_wall_s"] = int(m.group(1)), float(m.group(2))
            m = re.search(r"User time \(seconds\): ([0-9.]+)", line)
            if m:
                total["user_s"] = float(m.group(1))
            m = re.search(r"System time \(seconds\): ([0-9.]+)", line)
            if m:
                total["system_s"] = float(m.group(1))
            m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([0-9:.]+)", line)
            if m:
                secs = 0.0
                for part in m.group(1).split(":"):
                    secs = secs * 60 + float(part)
                total["elapsed_s"] = secs
    return case_wall, total


def case_row(case_dir, study_dir):
    case = read_toml(os.path.join(case_dir, "case.toml"))
    done = read_toml(os.path.join(case_dir, "done.toml"))
    with h5py.File(os.path.join(case_dir, "result.h5"), "r") as f:
        summary = dict(f["summary"].attrs)
        engine = dict(f["final_state/engine"].attrs)
        steps = f["series/step"][:]
        dts = f["series/time_step_s"][:]
        times = f["series/time_s"][:]
        particles_h5 = int(f["final_state/positions"].shape[0])
    engine_steps = int(engine["step"])
    start_step = int(steps[0])
    own_steps = engine_steps - start_step
    particles = int(done["particles"])
    if particles != particles_h5 or particles != int(summary["particles"]):
        raise SystemExit(f"{case_dir}: particle counts disagree: done.toml {particles}, "
                         f"positions {particles_h5}, summary {summary['particles']}")
    threads = int(summary.get("threads", case.get("threads", 1)))
    wall = float(done["wall_seconds"])
    loop_wall = float(summary["loop_wall_s"])
    ps = particles * own_steps
    # check: the simulated time of the case's own rows over its time step is its own steps
    steps_from_time = (float(times[-1]) - float(times[0])) / float(dts[-1])
    return {
        "case": case["id"],
        "parent": case.get("parent", "") or "sample",
        "parent_stage": case.get("parent_stage", ""),
        "stages": int(summary["stages_completed"]),
        "time_step_s": f"{float(dts[-1]):.3g}",
        "particles": particles,
        "start_step": start_step,
        "engine_steps": engine_steps,
        "own_steps": own_steps,
        "particle_steps": ps,
        "threads": threads,
        "wall_s": f"{wall:.3f}",
        "loop_wall_s": f"{loop_wall:.3f}",
        "us_per_particle_step": f"{wall * threads / ps * 1e6:.4f}",
        "us_per_particle_step_loop": f"{loop_wall * threads / ps * 1e6:.4f}",
        "us_if_engine_steps_counted": f"{wall * threads / (particles * engine_steps) * 1e6:.4f}",
        "neighbor_builds": int(summary["neighbor_builds"]),
        "own_steps_from_time": f"{steps_from_time:.1f}",
    }


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        sys.stderr.write(__doc__)
        return 2
    study = argv[1]
    log_wall, total = ({}, {})
    if len(argv) > 2:
        log_wall, total = read_log(argv[2])
    rows = [case_row(d, study) for d in sorted(glob.glob(os.path.join(study, "cases", "r*", "*")))
            if os.path.exists(os.path.join(d, "done.toml"))]
    for r in rows:
        r["log_wall_s"] = log_wall.get(r["case"], "")
    fields = list(rows[0].keys())
    w = csv.DictWriter(sys.stdout, fieldnames=fields, lineterminator="\n")
    w.writeheader()
    w.writerows(rows)

    err = sys.stderr
    us = [float(r["us_per_particle_step"]) for r in rows]
    us_loop = [float(r["us_per_particle_step_loop"]) for r in rows]
    ps = sum(r["particle_steps"] for r in rows)
    wall = sum(float(r["wall_s"]) for r in rows)
    err.write(f"{len(rows)} DEM cases, particles {sorted({r['particles'] for r in rows})}, "
              f"threads {sorted({r['threads'] for r in rows})}\n")
    err.write(f"own steps {sum(r['own_steps'] for r in rows)}, particle-steps {ps:.4g}, "
              f"sum of case wall {wall:.1f} s\n")
    err.write(f"us/particle-step (case wall x threads): median {statistics.median(us):.4f}, "
              f"range {min(us):.4f}-{max(us):.4f}; whole programme {wall / ps * 1e6:.4f}\n")
    err.write(f"us/particle-step (stepping loop only): median {statistics.median(us_loop):.4f}, "
              f"range {min(us_loop):.4f}-{max(us_loop):.4f}\n")
    if total:
        err.write("run log: " + ", ".join(f"{k} {v:g}" for k, v in total.items()) + "\n")
        if "user_s" in total:
            cpu = total["user_s"] + total.get("system_s", 0.0)
            err.write(f"CPU time of the whole run / particle-steps: {cpu / ps * 1e6:.4f} us "
                      f"(independent of the per-case wall times)\n")
        missing = [r["case"] for r in rows if r["log_wall_s"] == ""]
        diff = max((abs(float(r["wall_s"]) - r["log_wall_s"]) for r in rows if r["log_wall_s"] != ""),
                   default=0.0)
        err.write(f"log vs done.toml wall: largest difference {diff:.3f} s; not in log: {missing or 'none'}\n")
    mism = max(abs(float(r["own_steps_from_time"]) / r["own_steps"] - 1) for r in rows)
    err.write(f"simulated time / time step vs own steps: largest relative difference {mism:.2e}\n")
    err.write("costliest cases (case wall s, own steps, us/particle-step):\n")
    for r in sorted(rows, key=lambda r: -float(r["wall_s"]))[:5]:
        err.write(f"  {r['case']:24s} {float(r['wall_s']):8.1f} {r['own_steps']:8d} "
                  f"{float(r['us_per_particle_step']):.4f}  dt {r['time_step_s']}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
