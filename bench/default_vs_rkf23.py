#!/usr/bin/env python3
"""RKF23's time over the default integrator's at the default's error, per path.

    bench/default_vs_rkf23.py RESULTS.csv DEFAULT_TOLERANCE

RESULTS.csv is written by constitutive_work_precision --csv (one model, or
filter first); the default is the arkode_erk_order5 row at DEFAULT_TOLERANCE,
and RKF23's time is interpolated log-log along its curve to that row's error.
Prints a Markdown table row per path and the geometric mean and minimum.
"""
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
deftol = float(sys.argv[2])
paths = []
for r in rows:
    if r['path'] not in paths: paths.append(r['path'])
out = []
for p in paths:
    d = [r for r in rows if r['path']==p and r['integrator']=='arkode_erk_order5' and abs(float(r['tolerance'])/deftol-1)<1e-6 and r['status']=='ok']
    k = sorted([(float(r['error']), float(r['median_time_s'])) for r in rows if r['path']==p and r['integrator']=='rkf23' and r['status']=='ok' and float(r['error'])>0])
    if not d: print(p, 'no default row', [r['status'] for r in rows if r['path']==p and r['integrator']=='arkode_erk_order5']); continue
    e, t = float(d[0]['error']), float(d[0]['median_time_s'])
    # interpolate rkf23 time at error e (log-log), k sorted by error
    tr = None
    for (e1,t1),(e2,t2) in zip(k, k[1:]):
        if e1 <= e <= e2:
            w = (math.log(e)-math.log(e1))/(math.log(e2)-math.log(e1)) if e2>e1 else 0
            tr = math.exp(math.log(t1)+w*(math.log(t2)-math.log(t1)))
    if tr is None:
        print(f"| {p} | {e:.1e} | {t*1e6:.0f} | beyond RKF23's range (finest {k[0][0]:.1e} at {k[0][1]*1e6:.0f} µs) | ≥ {k[0][1]/t:.2f} |" if e < k[0][0] else f"| {p} | {e:.1e} | {t*1e6:.0f} | ? | ? |")
        out.append(k[0][1]/t if e<k[0][0] else float('nan'))
    else:
        print(f"| {p} | {e:.1e} | {t*1e6:.0f} | {tr*1e6:.0f} | {tr/t:.2f} |"); out.append(tr/t)
g=[x for x in out if x==x]
print('geomean', math.exp(sum(map(math.log,g))/len(g)), 'min', min(g))
