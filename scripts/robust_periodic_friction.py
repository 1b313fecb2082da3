#!/usr/bin/env python3
"""Random frictional cases on periodic cells and how many converge.

Writes one namelist of N seeded random cases -- a 2D or 1D wavy cell or a rough cell
(punch_rough covering the cell), nu in {0, 0.3, 0.45} (identical bodies; with --dissimilar body 2
is four times stiffer with nu2 = 0.28, so K != 0 and the Panagiotopoulos rounds run), 16^2 ... 64^2
elements, mean pressures from a few per cent of the cell in contact to full contact, a
prescribed tangential force of 5 ... 97 % of mu Fn in a random direction (70 %) or a rigid
shift (30 %) -- runs the built driver on it once and reports the cases that did not converge,
how many were in contact everywhere (the singular configuration, doc/parallel.md) and the
largest iteration counts.  doc/parallel.md ("Friction on a periodic cell") quotes its results.

Usage:  scripts/robust_periodic_friction.py --driver PATH [--seed N] [--n 120] [--dissimilar] [--keep DIR]

Standard library only.  Exit status 0 when every case converged, else 1.
"""
import argparse
import glob
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile


def cases(seed, n, dissimilar=False):
    rnd = random.Random(seed)
    lines = []
    for k in range(n):
        nu = rnd.choice([0.0, 0.3, 0.45])
        m = rnd.choice([16, 32, 48, 64])
        fn = rnd.choice([0.02, 0.1, 0.5, 1.0, 3.0, 6.0])
        mu = rnd.choice([0.2, 0.5])
        lines += [f"&case name = 'r{k}', problem = 'normal+tangential' /",
                  f"&material g1 = 200.0, g2 = {800.0 if dissimilar else 200.0}, nu1 = {nu}, "
                  f"nu2 = {0.28 if dissimilar else nu} /",
                  f"&grid nx = {m}, ny = {m}, xmin = 0.0, xmax = 1.0, ymin = 0.0, ymax = 1.0, periodic = .true. /"]
        if rnd.random() < 0.5:
            lines.append(f"&geometry kind = 'wavy', amplitude = 0.001, wavelength_x = {rnd.choice([1.0, 0.5])}, "
                         f"wavelength_y = {rnd.choice([0.0, 1.0, 0.5])} /")
        else:
            lines.append(f"&geometry kind = 'punch_rough', diameter = 10.0, sigma = 0.001, seed = {rnd.randint(1, 99)} /")
        lines.append(f"&normal fn = {fn} /")
        if rnd.random() < 0.7:
            frac, ang = rnd.choice([0.05, 0.3, 0.6, 0.9, 0.97]), rnd.uniform(0, 2 * math.pi)
            lines.append(f"&tangential mu = {mu}, fx = {frac * mu * fn * math.cos(ang):.6g}, "
                         f"fy = {frac * mu * fn * math.sin(ang):.6g} /")
        else:
            lines.append(f"&tangential mu = {mu}, xi = {rnd.choice([-1e-4, -1e-5, 3e-5])}, eta = {rnd.choice([0.0, 2e-5])} /")
        lines.append("&output table = .false. /")
    return '\n'.join(lines) + '\n'


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--driver', required=True)
    ap.add_argument('--seed', type=int, default=5)
    ap.add_argument('--n', type=int, default=120)
    ap.add_argument('--dissimilar', action='store_true', help='body 2: G = 800, nu = 0.28 (K != 0)')
    ap.add_argument('--keep', help='copy the namelist and outputs here')
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix='fc_periodic_friction_')
    nml = os.path.join(work, 'cases.nml')
    with open(nml, 'w') as f:
        f.write(cases(a.seed, a.n, a.dissimilar))
    subprocess.run([a.driver, nml, '--out', os.path.join(work, 'out')], stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL, env=dict(os.environ, OMP_NUM_THREADS='1'))
    rows = []
    for p in glob.glob(os.path.join(work, 'out', '*.json')):
        with open(p) as f:
            j = json.load(f)
        rows.append((j['iterations_tangential'], j['outer_iterations_tangential'], j['name'], j['status'],
                     j['ncon'] == j['nx'] * j['ny'], j['message']))
    bad = [r for r in rows if r[3] != 'converged']
    print(f'seed {a.seed}: {len(rows)} of {a.n} cases solved, {len(rows) - len(bad)} converged, '
          f'{sum(r[4] for r in rows)} in contact everywhere')
    for r in sorted(rows, reverse=True)[:3]:
        print(f'  {r[2]}: {r[0]} TangCG iterations, {r[1]} force-loop steps, full contact {r[4]}, {r[3]}')
    for r in bad:
        print(f'  NOT CONVERGED {r[2]}: {r[3]} {r[5]}')
    if a.keep:
        shutil.copytree(work, a.keep, dirs_exist_ok=True)
    shutil.rmtree(work, ignore_errors=True)
    return 1 if bad or len(rows) < a.n else 0


if __name__ == '__main__':
    sys.exit(main())
