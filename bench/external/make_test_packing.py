#!/usr/bin/env python3
"""Random non-overlapping periodic sphere packing for the external comparison.

Standard library only. Writes the plain-text packing format used by
compare.sh:

    N Lx Ly Lz            (metres)
    x y z r               (metres, one line per sphere, 0 <= x < Lx, ...)

Radii are uniform in [rmin, rmax] (default 0.1 - 0.5 mm) or drawn from a
grain-size table (--gsd CSV with columns diameter_mm, percent_passing_by_mass,
lines starting with '#' ignored).  The cubic cell is sized so that the solid
fraction equals --phi.  Spheres are first placed by random sequential
addition; any sphere that cannot be placed without overlap after a few
attempts is placed anyway, and the overlaps are then removed by iterative
pairwise push-apart (a crude but robust relaxation that converges for solid
fractions comfortably below jamming, i.e. phi <~ 0.62 for these size ratios).
"""

import argparse
import bisect
import math
import random
import sys


def read_gsd(path):
    pts = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            cols = line.split(",")
            try:
                d = float(cols[0]) * 1e-3
                p = float(cols[1]) / 100.0
            except ValueError:
                continue  # header row
            pts.append((d, p))
    pts.sort()
    if len(pts) < 2:
        sys.exit("gsd table needs at least two rows")
    return pts


def sample_gsd(pts, n, rng):
    """Diameters with the given *mass* distribution: draw d from the mass CDF
    (piecewise linear) and accept with probability (dmin/d)^3, which turns a
    mass-weighted sample into a number-weighted one."""
    ds = [d for d, _ in pts]
    ps = [p for _, p in pts]
    dmin = ds[0]
    out = []
    while len(out) < n:
        u = rng.random() * ps[-1]
        k = bisect.bisect_left(ps, u)
        k = min(max(k, 1), len(ps) - 1)
        p0, p1 = ps[k - 1], ps[k]
        d0, d1 = ds[k - 1], ds[k]
        d = d0 if p1 <= p0 else d0 + (u - p0) / (p1 - p0) * (d1 - d0)
        if rng.random() < (dmin / d) ** 3:
            out.append(0.5 * d)
    return out


class Grid:
    def __init__(self, box, cell):
        self.box = box
        self.n = max(1, int(box / cell))
        self.h = box / self.n
        self.cells = {}

    def key(self, p):
        n = self.n
        return (int(p[0] / self.h) % n, int(p[1] / self.h) % n, int(p[2] / self.h) % n)

    def add(self, idx, p):
        self.cells.setdefault(self.key(p), []).append(idx)

    def near(self, p):
        n = self.n
        cx, cy, cz = self.key(p)
        rng = (-1, 0, 1) if n >= 3 else tuple(range(n))
        seen = set()
        for dx in rng:
            for dy in rng:
                for dz in rng:
                    k = ((cx + dx) % n, (cy + dy) % n, (cz + dz) % n)
                    if k in seen:
                        continue
                    seen.add(k)
                    for j in self.cells.get(k, ()):
                        yield j


def min_image(d, box):
    return d - box * round(d / box)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-n", "--number", type=int, default=2000, help="number of spheres")
    ap.add_argument("--rmin", type=float, default=0.1e-3, help="min radius [m]")
    ap.add_argument("--rmax", type=float, default=0.5e-3, help="max radius [m]")
    ap.add_argument("--gsd", help="grain-size CSV (diameter_mm, percent passing by mass)")
    ap.add_argument("--phi", type=float, default=0.55, help="solid fraction of the cell")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--max-iter", type=int, default=2000)
    ap.add_argument("-v", "--verbose", action="store_true")
    ap.add_argument("-o", "--out", default="packing.txt")
    a = ap.parse_args()

    rng = random.Random(a.seed)
    if a.gsd:
        radii = sample_gsd(read_gsd(a.gsd), a.number, rng)
    else:
        radii = [rng.uniform(a.rmin, a.rmax) for _ in range(a.number)]
    radii.sort(reverse=True)
    vs = sum(4.0 / 3.0 * math.pi * r ** 3 for r in radii)
    box = (vs / a.phi) ** (1.0 / 3.0)
    rmax = max(radii)
    n = len(radii)

    # 1) random sequential addition, largest first
    pos = [None] * n
    grid = Grid(box, 2.0 * rmax)
    forced = 0
    for i, ri in enumerate(radii):
        for attempt in range(30):
            p = (rng.random() * box, rng.random() * box, rng.random() * box)
            ok = True
            for j in grid.near(p):
                q = pos[j]
                dx = min_image(p[0] - q[0], box)
                dy = min_image(p[1] - q[1], box)
                dz = min_image(p[2] - q[2], box)
                s = ri + radii[j]
                if dx * dx + dy * dy + dz * dz < s * s:
                    ok = False
                    break
            if ok:
                break
        else:
            forced += 1
        pos[i] = p
        grid.add(i, p)
    pos = [list(p) for p in pos]

    # 2) remove the remaining overlaps by pairwise push-apart
    it = 0
    worst = 0.0
    while True:
        grid = Grid(box, 2.0 * rmax)
        for i in range(n):
            grid.add(i, pos[i])
        disp = [[0.0, 0.0, 0.0] for _ in range(n)]
        worst = 0.0
        for i in range(n):
            p = pos[i]
            ri = radii[i]
            for j in grid.near(p):
                if j <= i:
                    continue
                q = pos[j]
                dx = min_image(q[0] - p[0], box)
                dy = min_image(q[1] - p[1], box)
                dz = min_image(q[2] - p[2], box)
                s = ri + radii[j]
                d2 = dx * dx + dy * dy + dz * dz
                if d2 >= s * s:
                    continue
                d = math.sqrt(d2)
                if d < 1e-12 * s:
                    dx, dy, dz, d = rng.random(), rng.random(), rng.random(), 1.0
                    d = math.sqrt(dx * dx + dy * dy + dz * dz)
                ov = s - d
                worst = max(worst, ov)
                # push to a small positive gap, shared by volume
                wi = radii[j] ** 3 / (ri ** 3 + radii[j] ** 3)
                f = (1.05 * ov + 1e-6 * s) / d
                di, dj = disp[i], disp[j]
                di[0] -= f * wi * dx; di[1] -= f * wi * dy; di[2] -= f * wi * dz
                dj[0] += f * (1 - wi) * dx; dj[1] += f * (1 - wi) * dy; dj[2] += f * (1 - wi) * dz
        if worst <= 0.0:
            break
        it += 1
        if a.verbose and it % 20 == 0:
            print("relax iter %d: max overlap %.3e m" % (it, worst), file=sys.stderr)
        if it > a.max_iter:
            sys.exit("could not remove overlaps (max %.3e m); lower --phi" % worst)
        for i in range(n):
            p, d = pos[i], disp[i]
            for k in range(3):
                p[k] = (p[k] + d[k]) % box

    with open(a.out, "w") as f:
        f.write("%d %.12e %.12e %.12e\n" % (n, box, box, box))
        for p, r in zip(pos, radii):
            x, y, z = (c % box for c in p)
            # guard against c % box == box after rounding
            x, y, z = (c if c < box else 0.0 for c in (x, y, z))
            f.write("%.12e %.12e %.12e %.12e\n" % (x, y, z, r))
    print("wrote %s: N=%d L=%.6e m phi=%.4f e=%.4f (RSA forced %d, %d relax iters)"
          % (a.out, n, box, vs / box ** 3, box ** 3 / vs - 1, forced, it))


if __name__ == "__main__":
    main()
