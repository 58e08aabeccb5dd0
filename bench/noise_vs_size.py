#!/usr/bin/env python3
"""Noise of the asymptotic states' psi_sigma and ln(1+e) against the sample size.

Issue 34 §3. Reads study folders of studies/programmes/noise.toml (one per
scale, each with replicates) and prints one CSV table (stdout, or --out):

  (a) row-to-row noise: the standard deviation of the residuals of psi_sigma
      and of ln p about a straight line in accumulated strain over the
      detector's window (the last `window_strain` of the stage, or for an
      extension state that held before the end of its path the window that
      ended at the strain the stage record names), per replicate; the median
      over the replicates. Every case of noise.toml is a strain path at
      constant psi_epsilon and ||D||, so ln(1+e) is imposed (exactly linear
      in the accumulated strain: its residuals are rounding noise, column
      a_lnv_imposed); its noise shows in ln p. a_lnv_equiv converts it to the
      scatter of ln(1+e) at a given p, |d ln(1+e)/d ln p| * (a) ln p, with
      the detector's slope of each replicate (not for isochoric states,
      where p moves at constant e). a2_* are the same about a quadratic: where
      they are much below (a) the window holds a curved trend (a drifting
      state, or the NCL's changing slope), not noise.
  (b) replicate-to-replicate spread: the standard deviation (ddof = 1) over
      the replicates of the state's psi_sigma, ln(1+e) and ln p in
      asymptotic_states.csv (detected and drifting states).
  (c) the ensemble-mean path: each replicate's series resampled on the
      common accumulated-strain axis of its case (all replicates follow the
      same prescribed strain path from the same initial porosity), averaged,
      and (a) computed for the mean path over the window that ends where the
      earliest replicate's window ends (median window length); c_over_a is
      (c) / ((a) / sqrt(R)): 1 where the replicates' noise is independent.

Below the states, rows `exponent` give k of a fit noise ∝ N^-k (least
squares in log-log over the scales) for every numeric column and kind, and
`exponent_all` one k per column with a separate intercept per kind.

  python3 bench/noise_vs_size.py noise-tiny noise-small noise-medium [--out table.csv]
"""
import argparse
import csv
import math
import os
import re
import sys

import h5py
import numpy as np

USABLE = ("detected", "drifting")
NOISE_COLUMNS = [
    "a_psi_deg", "a_lnp", "a_lnv_equiv", "a2_psi_deg", "a2_lnp", "b_psi_deg", "b_lnv", "b_lnp", "c_psi_deg", "c_lnp",
]


def residual_sd(x, y, degree=1):
    """Standard deviation of y about its least-squares polynomial in x (ddof = degree + 1)."""
    if len(x) < degree + 3:
        return math.nan
    coeffs = np.polyfit(x, y, degree)
    r = y - np.polyval(coeffs, x)
    return float(np.sqrt(np.sum(r * r) / (len(x) - degree - 1)))


class Case:
    """One replicate's case: its series on the case's accumulated strain."""

    def __init__(self, path):
        with h5py.File(path, "r") as f:
            s = f["series"]
            t = s["time_s"][:]
            rate = s["stretching_rate_per_s"][:]
            self.strain = np.concatenate(([0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))))
            self.psi = s["psi_sigma_deg"][:]
            self.lnp = np.log(np.maximum(s["p_kpa"][:], 1e-300))
            self.lnv = s["ln_1_plus_e"][:]
            self.stages = {}
            for key in f["stages"]:
                a = f["stages"][key].attrs
                name = a["name"]
                name = name.decode() if isinstance(name, bytes) else str(name)
                first, last = int(a["first_row"]), int(a["last_row"])
                start = self.strain[first - 1] if first > 0 else 0.0
                stop = str(a.get("stop_reason", ""))
                self.stages[name] = (first, last, start, stop)

    def window_end(self, stage, held_before_end):
        """Case strain at which the detector's window ends."""
        first, last, start, stop = self.stages[stage]
        if held_before_end:
            m = re.search(r"up to stage strain ([0-9.eE+-]+)", stop)
            if m:
                return start + float(m.group(1))
        return self.strain[last]

    def rows(self, stage, lo, hi):
        first, last, _, _ = self.stages[stage]
        idx = np.arange(first, last + 1)
        s = self.strain[idx]
        keep = (s >= lo - 1e-9) & (s <= hi + 1e-9)
        return idx[keep]


def read_states(folder):
    with open(os.path.join(folder, "asymptotic_states.csv"), newline="") as f:
        return list(csv.DictReader(f))


def state_label(row):
    return row["case_name"] + "@" + row["stage"]


def analyse(folder, ncl_stages):
    states = read_states(folder)
    replicates = sorted({int(r["replicate"]) for r in states})
    count, scale_name = None, ""
    summary = os.path.join(folder, "study.toml")
    if os.path.exists(summary):
        text = open(summary).read()
        m = re.search(r"^\s*count\s*=\s*(\d+)", text, re.M)
        if m:
            count = int(m.group(1))
        m = re.search(r"^\s*scale\s*=\s*\"?(\w+)", text, re.M)
        scale_name = m.group(1) if m else ""
    if count is None:  # the sample's packing
        with h5py.File(os.path.join(folder, "cases", "r%d" % replicates[0], "ncl", "result.h5"), "r") as f:
            count = int(f["summary"].attrs["particles"])
    groups = {}
    for r in states:
        if r["kind"] not in ("ncl", "csl", "compression", "extension"):
            continue
        if r["kind"] == "ncl" and r["stage"] not in ncl_stages:
            continue
        groups.setdefault(state_label(r), []).append(r)
    out = []
    for label, rows in sorted(groups.items(), key=lambda kv: (kv[1][0]["kind"], kv[0])):
        kind = rows[0]["kind"]
        statuses = [r["status"] for r in rows]
        usable = [r for r in rows if r["status"] in USABLE]
        res = {
            "folder": os.path.basename(os.path.normpath(folder)), "scale": scale_name, "N": count,
            "replicates": len(replicates), "kind": kind, "state": label,
            "detected": sum(s == "detected" for s in statuses),
            "drifting": sum(s == "drifting" for s in statuses),
            "other": ";".join(sorted({s for s in statuses if s not in USABLE})),
        }
        a_psi, a_lnp, a_equiv, a_lnv, a2_psi, a2_lnp, n_rows = [], [], [], [], [], [], []
        ends, widths, cases = [], [], []
        for r in usable:
            path = os.path.join(folder, "cases", "r" + r["replicate"], r["case_name"], "result.h5")
            case = Case(path)
            stage = r["stage"]
            w = float(r["window_strain"])
            end = case.window_end(stage, r["held_before_end"] in ("1", "true"))
            idx = case.rows(stage, end - w, end)
            x = case.strain[idx]
            a_psi.append(residual_sd(x, case.psi[idx]))
            a_lnp.append(residual_sd(x, case.lnp[idx]))
            a_lnv.append(residual_sd(x, case.lnv[idx]))
            a2_psi.append(residual_sd(x, case.psi[idx], 2))
            a2_lnp.append(residual_sd(x, case.lnp[idx], 2))
            n_rows.append(len(idx))
            if kind != "csl":
                a_equiv.append(abs(float(r["dln1pe_dlnp"])) * a_lnp[-1])
            ends.append(end)
            widths.append(w)
            cases.append((case, stage))
        med = lambda v: float(np.nanmedian(v)) if len(v) and not all(map(math.isnan, v)) else math.nan
        res["rows_in_window"] = int(np.median(n_rows)) if n_rows else 0
        res["a_psi_deg"] = med(a_psi)
        res["a_lnp"] = med(a_lnp)
        res["a_lnv_equiv"] = med(a_equiv)
        res["a_lnv_imposed"] = med(a_lnv)
        res["a2_psi_deg"] = med(a2_psi)
        res["a2_lnp"] = med(a2_lnp)
        sd = lambda v: float(np.std(v, ddof=1)) if len(v) > 1 else math.nan
        res["b_psi_deg"] = sd([float(r["psi_sigma_deg"]) for r in usable])
        res["b_lnv"] = sd([float(r["ln_1_plus_e"]) for r in usable])
        res["b_lnp"] = sd([math.log(float(r["p_kpa"])) for r in usable])
        res["c_psi_deg"] = res["c_lnp"] = res["c_over_a_psi"] = res["c_over_a_lnp"] = math.nan
        if len(cases) > 1:
            end, w = min(ends), float(np.median(widths))
            first_case, first_stage = cases[0]
            grid = first_case.strain[first_case.rows(first_stage, end - w, end)]
            if len(grid) < 4:
                grid = np.linspace(end - w, end, max(4, int(round(w / 0.002)) + 1))
            psi = np.mean([np.interp(grid, c.strain, c.psi) for c, _ in cases], axis=0)
            lnp = np.mean([np.interp(grid, c.strain, c.lnp) for c, _ in cases], axis=0)
            res["c_psi_deg"] = residual_sd(grid, psi)
            res["c_lnp"] = residual_sd(grid, lnp)
            root = math.sqrt(len(cases))
            res["c_over_a_psi"] = res["c_psi_deg"] / (res["a_psi_deg"] / root)
            res["c_over_a_lnp"] = res["c_lnp"] / (res["a_lnp"] / root)
        out.append(res)
    return out


def exponent(ns, values):
    pts = [(math.log(n), math.log(v)) for n, v in zip(ns, values) if v > 0 and math.isfinite(v)]
    if len(pts) < 2 or len({p[0] for p in pts}) < 2:
        return math.nan
    x, y = np.array(pts).T
    return float(-np.polyfit(x, y, 1)[0])


def pooled_exponent(series):
    """k of log v = c_kind - k log N, one intercept per kind (least squares)."""
    xs, ys, kinds = [], [], []
    for kind, (ns, values) in series.items():
        for n, v in zip(ns, values):
            if v > 0 and math.isfinite(v):
                xs.append(math.log(n)), ys.append(math.log(v)), kinds.append(kind)
    names = sorted(set(kinds))
    if len(xs) < len(names) + 1:
        return math.nan
    A = np.zeros((len(xs), len(names) + 1))
    for i, (x, k) in enumerate(zip(xs, kinds)):
        A[i, 0] = x
        A[i, 1 + names.index(k)] = 1.0
    coeffs = np.linalg.lstsq(A, np.array(ys), rcond=None)[0]
    return float(-coeffs[0])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folders", nargs="+", help="study folders of noise.toml, one per scale")
    parser.add_argument("--ncl-stages", default="p100,p1000", help="NCL stages whose end states count")
    parser.add_argument("--out", help="write the CSV here as well as to stdout")
    args = parser.parse_args()
    rows = []
    for folder in args.folders:
        rows.extend(analyse(folder, set(args.ncl_stages.split(","))))
    columns = ["folder", "scale", "N", "replicates", "kind", "state", "detected", "drifting", "other",
               "rows_in_window", "a_psi_deg", "a_lnp", "a_lnv_equiv", "a_lnv_imposed", "a2_psi_deg", "a2_lnp", "b_psi_deg",
               "b_lnv", "b_lnp", "c_psi_deg", "c_lnp", "c_over_a_psi", "c_over_a_lnp"]
    by_state = {}
    for r in rows:
        by_state.setdefault(r["state"], []).append(r)
    for state, rs in by_state.items():
        rs.sort(key=lambda r: r["N"])
        e = {c: "" for c in columns}
        e.update(folder="exponent", kind=rs[0]["kind"], state=state, N="", replicates="")
        for c in NOISE_COLUMNS:
            e[c] = exponent([r["N"] for r in rs], [r[c] for r in rs])
        rows.append(e)
    e = {c: "" for c in columns}
    e.update(folder="exponent_all", state="all states")
    for c in NOISE_COLUMNS:
        e[c] = pooled_exponent({s: ([r["N"] for r in rs], [r[c] for r in rs]) for s, rs in by_state.items()})
    rows.append(e)

    def fmt(v):
        if isinstance(v, float):
            return "" if math.isnan(v) else "%.4g" % v
        return str(v)

    streams = [sys.stdout]
    if args.out:
        streams.append(open(args.out, "w", newline=""))
    for stream in streams:
        w = csv.writer(stream, lineterminator="\n")
        w.writerow(columns)
        for r in rows:
            w.writerow([fmt(r.get(c, "")) for c in columns])
    if args.out:
        streams[1].close()


if __name__ == "__main__":
    main()
