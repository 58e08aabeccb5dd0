#!/usr/bin/env python3
"""Write a LAMMPS data file and input script for the external comparison.

Standard library only.  Reads the plain-text packing (first line
"N Lx Ly Lz", then "x y z r" per sphere, metres) and writes into --dir:

    data.lmp   atom_style sphere data file (units si), diameter and density
               per atom, initial velocity = affine field L (x - box centre)
    in.lmp     input script: gran/hooke/history, nve/sphere, fix deform with
               a constant true strain rate on x, y, z ("trate", which matches
               the exponential cell update H <- H + dt L H of granasym and
               Yade), remap v, pair-virial pressure, e = V/V_solid - 1
    notes.txt  the approximations made (printed as well)

The input prints a machine-readable line at the end:
    RESULT code=lammps N=... steps=... p_kpa=... e=...
(the loop time is read from LAMMPS's own "Loop time of ..." line).

Approximations with respect to the granasym / Yade model:
  * LAMMPS's Hookean granular pair style takes one k_n for all pairs.  We use
    k_n = 2E r r/(r + r) = E * r_mean for the mean radius of the packing
    (the per-pair value 2E r_i r_j/(r_i + r_j) is not expressible there);
    k_t = 0.3 k_n.
  * LAMMPS has no Cundall local (non-viscous) damping.  The viscous pair
    damping gamma_n = gamma_t is set by --gamma (default 0: undamped), so
    the stress response differs; e is set purely by the imposed cell strain.
"""

import argparse
import math
import os
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--packing", required=True)
    ap.add_argument("--dir", required=True, help="output directory")
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--rate", type=float, default=-167.0 / math.sqrt(3.0),
                    help="velocity gradient component L_xx [1/s] (also y, z without --rate-yz)")
    ap.add_argument("--rate-yz", type=float, default=None,
                    help="velocity gradient components L_yy = L_zz [1/s] (default: --rate)")
    ap.add_argument("--dt", type=float, default=1.2e-7)
    ap.add_argument("--young", type=float, default=500e6)
    ap.add_argument("--kt-ratio", type=float, default=0.3)
    ap.add_argument("--friction-angle", type=float, default=0.5)
    ap.add_argument("--density", type=float, default=2650.0)
    ap.add_argument("--gamma", type=float, default=0.0,
                    help="gamma_n = gamma_t viscous damping of gran/hooke/history [1/s]")
    ap.add_argument("--skin-frac", type=float, default=0.1,
                    help="neighbour skin as a fraction of the mean diameter")
    ap.add_argument("--thermo", type=int, default=0,
                    help="thermo output interval (default: steps/4)")
    a = ap.parse_args()
    rate_yz = a.rate if a.rate_yz is None else a.rate_yz

    with open(a.packing) as f:
        head = f.readline().split()
        n = int(head[0])
        lx, ly, lz = (float(v) for v in head[1:4])
        sph = []
        for line in f:
            c = line.split()
            if len(c) >= 4:
                sph.append(tuple(float(v) for v in c[:4]))
    if len(sph) != n:
        sys.exit("packing: header says %d spheres, found %d" % (n, len(sph)))

    r_mean = sum(s[3] for s in sph) / n
    v_solid = sum(4.0 / 3.0 * math.pi * s[3] ** 3 for s in sph)
    kn = 2.0 * a.young * r_mean * r_mean / (2.0 * r_mean)
    kt = a.kt_ratio * kn
    mu = math.tan(a.friction_angle)
    skin = a.skin_frac * 2.0 * r_mean
    thermo = a.thermo if a.thermo > 0 else max(1, a.steps // 4)

    os.makedirs(a.dir, exist_ok=True)
    with open(os.path.join(a.dir, "data.lmp"), "w") as f:
        f.write("granasym external comparison packing (units si)\n\n")
        f.write("%d atoms\n1 atom types\n\n" % n)
        f.write("0.0 %.12e xlo xhi\n0.0 %.12e ylo yhi\n0.0 %.12e zlo zhi\n\n" % (lx, ly, lz))
        f.write("Atoms # sphere\n\n")
        for i, (x, y, z, r) in enumerate(sph, 1):
            f.write("%d 1 %.12e %.6f %.12e %.12e %.12e\n" % (i, 2.0 * r, a.density, x, y, z))
        # affine initial velocity about the box centre (fix deform keeps the
        # centre fixed); with "remap v" LAMMPS then carries this field
        f.write("\nVelocities\n\n")
        for i, (x, y, z, r) in enumerate(sph, 1):
            f.write("%d %.12e %.12e %.12e 0 0 0\n" % (
                i, a.rate * (x - 0.5 * lx), rate_yz * (y - 0.5 * ly), rate_yz * (z - 0.5 * lz)))

    notes = [
        "LAMMPS approximation: constant k_n = E*r_mean = %.6e N/m for every pair "
        "(r_mean = %.6e m); granasym/Yade use 2E r_i r_j/(r_i+r_j) per pair." % (kn, r_mean),
        "LAMMPS approximation: k_t = %.3g k_n = %.6e N/m, mu = tan(%.3g) = %.6f."
        % (a.kt_ratio, kt, a.friction_angle, mu),
        "LAMMPS has no Cundall local damping; gamma_n = gamma_t = %g 1/s instead, "
        "so p differs from granasym/Yade (compare time per particle-step)." % a.gamma,
        "Loading: fix deform trate %.6g on x, %.6g on y and z (true strain rate, matches "
        "H <- H + dt L H), remap v, initial velocity = affine field." % (a.rate, rate_yz),
    ]
    with open(os.path.join(a.dir, "notes.txt"), "w") as f:
        f.write("\n".join(notes) + "\n")

    inp = """# generated by bench/external/lammps_input.py
units           si
atom_style      sphere
dimension       3
boundary        p p p
comm_modify     vel yes
read_data       data.lmp

pair_style      gran/hooke/history {kn:.10e} {kt:.10e} {g:.10e} {g:.10e} {mu:.10f} 1
pair_coeff      * *

neighbor        {skin:.10e} bin
neigh_modify    delay 0 every 1 check yes

timestep        {dt:.10e}
fix             integ all nve/sphere
fix             load all deform 1 x trate {rate:.10e} y trate {rate_yz:.10e} z trate {rate_yz:.10e} remap v

# pressure from the pair virial only (LAMMPS: positive = compression)
compute         pvir all pressure NULL virial
variable        p_kpa equal c_pvir/1000.0
variable        e equal vol/{vs:.12e}-1.0
thermo_style    custom step time v_p_kpa v_e vol ke
thermo_modify   norm no
thermo          {thermo}

run             {steps}
print           "RESULT code=lammps N={n} steps={steps} p_kpa=${{p_kpa}} e=${{e}}"
""".format(kn=kn, kt=kt, g=a.gamma, mu=mu, skin=skin, dt=a.dt, rate=a.rate, rate_yz=rate_yz,
           vs=v_solid, thermo=thermo, steps=a.steps, n=n)
    with open(os.path.join(a.dir, "in.lmp"), "w") as f:
        f.write(inp)
    for line in notes:
        print(line)


if __name__ == "__main__":
    main()
