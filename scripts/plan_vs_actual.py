#!/usr/bin/env python3
"""`granasym study plan` against a study folder that ran: per case the planned
and the actual steps and seconds and their ratios, and the totals.

    scripts/plan_vs_actual.py STUDY_DIR PROGRAMME [--scale S] [--granasym BIN]
                              [--jobs N] [--cpu-seconds X] [--rerun] [--stages]

Run it from the folder the programme's relative paths (its GSD) resolve
from, as `study run` was. The actual figures of a case come from its folder:
its own steps from run.log (the steps of each stage of its last run, not
done.toml's `steps`, which counts from the first step of the sample, parent
cases included) and done.toml's cpu_seconds (the processor seconds of a
case run on one thread, which a shared or paused machine does not
inflate), else its wall_seconds. Cases of the folder that the programme does
not plan, and planned cases without a done.toml, are left out (and
counted). An older folder has wall seconds only, longer on a shared machine
than the machine alone would take (what the plan estimates): give the run's
processor seconds (`/usr/bin/time`'s user + system) with
--cpu-seconds to compare the study's total against them too, or --rerun:
each compared case's scene runs again (`granasym dem run`, into a temporary
folder) and its processor seconds replace the wall seconds (a study of
minutes: the tiny scale).
"""

import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
from collections import OrderedDict

STAGE_DONE = re.compile(r"^stage (\d+) '([^']*)' done after (\d+) steps: (.*)$")


def planned_cases(granasym, programme, scale, jobs):
    command = [granasym, "study", "plan", programme, "--scale", scale, "--tsv"]
    if jobs:
        command += ["--jobs", str(jobs)]
    text = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    lines = text.splitlines()
    header = lines[0].split("\t") if lines else []
    if "case" not in header or "seconds" not in header:
        sys.exit("plan_vs_actual: cannot read the plan's output:\n" + text)
    cases = OrderedDict()
    for line in lines[1:]:
        row = dict(zip(header, line.split("\t")))
        case = {
            "steps": float(row["steps"]),
            "seconds": float(row["seconds"]),
            "bound": row["at_most"] == "1",
        }
        # The low end of a bound's range (a plan of an older granasym has
        # none: the bound then).
        case["earliest_steps"] = float(row.get("earliest_steps", case["steps"]))
        case["earliest_seconds"] = float(row.get("earliest_seconds", case["seconds"]))
        cases[row["case"]] = case
    return cases


def read_toml_values(path):
    values = {}
    with open(path) as f:
        for line in f:
            m = re.match(r"^(\w+) = (.*)$", line.strip())
            if m:
                values[m.group(1)] = m.group(2).strip('"')
    return values


def actual_case(folder):
    done = os.path.join(folder, "done.toml")
    if not os.path.exists(done):
        return None
    values = read_toml_values(done)
    if values.get("termination") != "completed":
        return None
    stages = OrderedDict()
    log = os.path.join(folder, "run.log")
    if os.path.exists(log):
        with open(log) as f:
            for line in f:
                # A later run of the case (a rerun, or a restart that
                # continues a stage) writes its stages again: the last wins.
                m = STAGE_DONE.match(line)
                if m:
                    reason = m.group(4).split(" (")[0].split(":")[0]
                    stages[int(m.group(1))] = (m.group(2), int(m.group(3)), reason)
    steps = sum(s[1] for s in stages.values())
    # A case run on one thread records its own processor seconds, which a
    # shared or paused machine does not inflate; else its wall seconds.
    cpu = "cpu_seconds" in values
    return {
        "steps": steps,
        "seconds": float(values["cpu_seconds" if cpu else "wall_seconds"]),
        "cpu": cpu,
        "stages": list(stages.values()),
    }


def processor_seconds(granasym, scene):
    """User + system seconds of `granasym dem run SCENE` into a temporary folder."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory(prefix="plan_vs_actual_") as folder:
        subprocess.run([granasym, "dem", "run", scene, "--out", os.path.join(folder, "r.h5"),
                        "--quiet"], check=True, stdout=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def ratio(planned, actual):
    return planned / actual if actual > 0 else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("study")
    parser.add_argument("programme")
    parser.add_argument("--scale", default="small")
    parser.add_argument("--granasym", default=os.environ.get("GRANASYM", "granasym"))
    parser.add_argument("--jobs", type=int, default=0)
    parser.add_argument("--cpu-seconds", type=float, default=0.0)
    parser.add_argument("--rerun", action="store_true",
                        help="run each case again and compare its processor seconds")
    parser.add_argument("--stages", action="store_true", help="each stage's steps and stop")
    args = parser.parse_args()
    cases = planned_cases(args.granasym, args.programme, args.scale, args.jobs)
    width = max(len(k) for k in cases)
    kind = "cpu s" if args.rerun else "s"
    print(f"{'case':<{width}}  {'plan steps':>11}  {'steps':>9}  {'ratio':>5}  "
          f"{'plan s':>7}  {kind:>7}  {'ratio':>5}  stops")
    # Per group: planned steps, actual steps, planned seconds, actual
    # seconds, cases, and the planned steps and seconds at the low end.
    groups = {name: [0.0] * 4 + [0] + [0.0] * 2 for name in ("all", "predicted", "at most")}
    missing = 0
    wall_only = 0  # cases compared by their wall seconds (no cpu_seconds)
    for case_id, plan in cases.items():
        actual = actual_case(os.path.join(args.study, "cases", case_id))
        if actual is None or actual["steps"] == 0:
            missing += 1
            continue
        if args.rerun:
            scene = os.path.join(args.study, "cases", case_id, "scene.toml")
            actual["seconds"] = processor_seconds(args.granasym, scene)
            actual["cpu"] = True
        wall_only += 0 if actual["cpu"] else 1
        for name in ("all", "at most" if plan["bound"] else "predicted"):
            g = groups[name]
            g[0] += plan["steps"]
            g[1] += actual["steps"]
            g[2] += plan["seconds"]
            g[3] += actual["seconds"]
            g[4] += 1
            g[5] += plan["earliest_steps"]
            g[6] += plan["earliest_seconds"]
        bound = "<=" if plan["bound"] else "  "
        stops = ", ".join(sorted({s[2] for s in actual["stages"]}))
        print(f"{case_id:<{width}}  {bound}{plan['steps']:9.3g}  {actual['steps']:9d}  "
              f"{ratio(plan['steps'], actual['steps']):5.2f}  {plan['seconds']:7.1f}  "
              f"{actual['seconds']:7.1f}{'' if actual['cpu'] else 'w'} "
              f"{ratio(plan['seconds'], actual['seconds']):5.2f}  {stops}"
              + (f"  (low end: {plan['earliest_steps']:.3g} steps, "
                 f"{ratio(plan['earliest_seconds'], actual['seconds']):.2f} of the seconds)"
                 if plan["bound"] else ""))
        if args.stages:
            for name, steps, reason in actual["stages"]:
                print(f"    {name}: {steps} steps, {reason}")
    print(f"\n{len(cases) - missing} cases compared ({missing} planned cases not finished in "
          "the folder); actual seconds: each case's processor seconds, or its wall seconds "
          f"where it has none (marked w: {wall_only} cases); planned / actual:")
    for name, g in groups.items():
        if g[4] == 0:
            continue
        print(f"  {name:>9} ({g[4]:3d} cases): steps {g[0]:.3g} / {g[1]:.3g} = "
              f"{ratio(g[0], g[1]):.2f}; case seconds {g[2]:.0f} / {g[3]:.0f} = "
              f"{ratio(g[2], g[3]):.2f}")
        if g[5] != g[0] or g[6] != g[2]:
            print(f"  {'':>9}  at the low end (each stage that may liquefy liquefying as early "
                  f"as the model allows): steps {g[5]:.3g} / {g[1]:.3g} = "
                  f"{ratio(g[5], g[1]):.2f}; case seconds {g[6]:.0f} / {g[3]:.0f} = "
                  f"{ratio(g[6], g[3]):.2f}")
    if args.cpu_seconds > 0:
        total = groups["all"][2]
        print(f"processor seconds of the run: {args.cpu_seconds:.0f}; planned case seconds / "
              f"them = {ratio(total, args.cpu_seconds):.2f}")


if __name__ == "__main__":
    main()
