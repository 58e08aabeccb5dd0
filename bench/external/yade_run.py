# Yade script for the granasym external comparison.
#
# Run non-interactively (Debian 12 yade 2023.02a):
#     yade -j THREADS -n -x yade_run.py PACKING STEPS [RATE] [SKIN_FRAC] [DAMPING] [RATE_YZ]
# (-n: no GUI, -x: exit when the script ends, -j: OpenMP threads).
#
# Builds a periodic cell from the plain-text packing ("N Lx Ly Lz", then
# "x y z r" per sphere, metres), FrictMat spheres (E = 500 MPa, k_s/k_n = 0.3,
# friction angle 0.5 rad, 2650 kg/m^3), the linear Cundall-Strack law, local
# damping 0.5 (DAMPING, for checks only), dt = 1.2e-7 s, and a constant diagonal velocity gradient
# diag(RATE, RATE_YZ, RATE_YZ) (default -167/sqrt(3) 1/s, RATE_YZ = RATE).  Times O.run(STEPS, True)
# and prints, as its last line,
#     RESULT code=yade N=... steps=... threads=... wall_s=... p_kpa=... e=...
# with p compression positive (Yade's stress is tension positive) and
# e = cell volume / total sphere volume - 1.
#
# The collider's verletDist (the enlargement of each bounding box) is half
# the pair skin SKIN_FRAC * mean diameter, so that two boxes start to overlap
# at the same gap at which a Verlet list with that skin would list the pair.

import math
import os
import sys
import time

args = [a for a in sys.argv[1:]]
if len(args) < 2:
    print("usage: yade -n -x yade_run.py PACKING STEPS [RATE] [SKIN_FRAC] [DAMPING] [RATE_YZ]")
    sys.exit(2)
packing = args[0]
steps = int(args[1])
rate = float(args[2]) if len(args) > 2 else -167.0 / math.sqrt(3.0)
skin_frac = float(args[3]) if len(args) > 3 else 0.1
damping = float(args[4]) if len(args) > 4 else 0.5  # other values: checks only
rate_yz = float(args[5]) if len(args) > 5 else rate  # L_yy = L_zz (default: isotropic)

with open(packing) as f:
    head = f.readline().split()
    n = int(head[0])
    lx, ly, lz = (float(v) for v in head[1:4])
    sph = []
    for line in f:
        c = line.split()
        if len(c) >= 4:
            sph.append(tuple(float(v) for v in c[:4]))
if len(sph) != n:
    print("packing: header says %d spheres, found %d" % (n, len(sph)))
    sys.exit(1)

r_mean = sum(s[3] for s in sph) / n
v_solid = sum(4.0 / 3.0 * math.pi * s[3] ** 3 for s in sph)

O.reset()
O.periodic = True
O.cell.hSize = Matrix3(lx, 0, 0, 0, ly, 0, 0, 0, lz)
mat = O.materials.append(FrictMat(young=500e6, poisson=0.3, frictionAngle=0.5,
                                  density=2650.0))
O.bodies.append([sphere(Vector3(x, y, z), r, material=mat) for (x, y, z, r) in sph])

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()], verletDist=0.5 * skin_frac * 2.0 * r_mean),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom()],
        [Ip2_FrictMat_FrictMat_FrictPhys()],
        [Law2_ScGeom_FrictPhys_CundallStrack()],
    ),
    NewtonIntegrator(damping=damping, gravity=Vector3(0, 0, 0)),
]
O.dt = 1.2e-7
O.cell.velGrad = Matrix3(rate, 0, 0, 0, rate_yz, 0, 0, 0, rate_yz)

t0 = time.time()
O.run(steps, True)
wall = time.time() - t0

s = utils.getStress()
p_kpa = -(s[0, 0] + s[1, 1] + s[2, 2]) / 3.0 / 1000.0
e = O.cell.volume / v_solid - 1.0
threads = os.environ.get("OMP_NUM_THREADS", "?")
print("RESULT code=yade N=%d steps=%d threads=%s wall_s=%.6f p_kpa=%.9g e=%.9g contacts=%d"
      % (n, O.iter, threads, wall, p_kpa, e, sum(1 for i in O.interactions if i.isReal)))
