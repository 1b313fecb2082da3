#!/usr/bin/env python3
"""Random creep-force sweeps (steady rolling with warm starts) and how many points converge.

Writes one namelist of N seeded random sweeps -- swept value 'xi', 'eta', 'phi' (creepages)
or 'fx', 'fy' (prescribed creep forces), up, down or through zero, 20 points each, fixed
creepages beside the swept one, a sphere or an ellipse (ry 12.5 ... 100 mm) on 30x25 ...
60x50 grids -- runs the built driver on it once, and counts per sweep whether every point
converged (the driver goes on past a point that does not, from the last converged one, and
writes every point's status).  doc/rolling.md ("Warm starts") quotes its results.

Usage:  scripts/sweep_robustness.py --driver PATH [--seed N] [--n 40] [--kind creepage|force]
            [--keep DIR]

Standard library only.  Exit status 0 when every sweep converged at every point, else 1.
"""
import argparse
import csv
import glob
import os
import random
import shutil
import subprocess
import sys
import tempfile


def sweeps(seed, n, kind):
    rnd = random.Random(seed)
    out = []
    for k in range(n):
        if kind == 'force':
            sw = rnd.choice(['fx', 'fy'])
            top = rnd.choice([1.0, 2.5, 3.5])          # N; mu*Fn = 3.68 N
            fixed = f"fx = 0.0, fy = 0.0, phi = {rnd.choice([0, 0.005, -0.01, 0.03])}"
        else:
            sw = rnd.choice(['xi', 'eta', 'phi'])
            top = rnd.choice([0.01, 0.04, 0.1]) if sw == 'phi' else rnd.choice([0.003, 0.006, 0.012, 0.03])
            fixed = (f"xi = {rnd.choice([0, 0.001, 0.003, -0.002])}, eta = {rnd.choice([0, 0.002, -0.001])}, "
                     f"phi = {rnd.choice([0, 0.005, -0.01, 0.03])}")
        r = rnd.random()
        a, b = (0, top) if r < 0.35 else ((top, 0) if r < 0.7 else (-top, top))
        ry = rnd.choice([50, 25, 12.5, 100])
        nx, ny = rnd.choice([(30, 25), (48, 40), (60, 50)])
        out.append(f"&case name = 's{k}', problem = 'rolling' /\n"
                   "&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /\n"
                   f"&grid nx = {nx}, ny = {ny}, xmin = -0.9, xmax = 0.9, ymin = -0.9, ymax = 0.9 /\n"
                   f"&geometry kind = 'quadratic', rx = 50.0, ry = {ry} /\n"
                   "&normal fn = 9.1954 /\n"
                   f"&tangential mu = 0.4, {fixed}, sweep = '{sw}', sweep_from = {a}, sweep_to = {b}, "
                   "sweep_n = 20 /\n")
    return ''.join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--driver', required=True)
    ap.add_argument('--seed', type=int, default=7)
    ap.add_argument('--n', type=int, default=40)
    ap.add_argument('--kind', choices=['creepage', 'force'], default='creepage')
    ap.add_argument('--keep', default='')
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix='fc_sweeps_')
    nml = os.path.join(work, 'sweeps.nml')
    with open(nml, 'w') as f:
        f.write(sweeps(args.seed, args.n, args.kind))
    env = dict(os.environ, OMP_NUM_THREADS='1')
    subprocess.run([args.driver, nml, '--out', os.path.join(work, 'out')], env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    failed, points, iterations, bad_points = [], 0, 0, 0
    for k in range(args.n):
        path = os.path.join(work, 'out', f's{k}_creep.csv')
        rows = list(csv.DictReader(open(path))) if os.path.exists(path) else []
        points += len(rows)
        iterations += sum(int(float(r['iterations'])) for r in rows)
        bad = [r for r in rows if r['status'] != 'converged']
        bad_points += len(bad)
        if len(rows) < 20 or bad:
            first = bad[0] if bad else {}
            failed.append(f"s{k}: {len(rows)} points, {len(bad)} not converged, the first at "
                          f"{first.get('value', '-')} ({first.get('status', 'no output')})")
    print(f"seed {args.seed}, {args.n} {args.kind} sweeps: {args.n - len(failed)} complete, "
          f"{len(failed)} with points not converged; {points} points ({bad_points} not converged), "
          f"{iterations} Krylov iterations")
    for line in failed:
        print('  ' + line)
    if args.keep:
        shutil.copytree(work, args.keep, dirs_exist_ok=True)
    shutil.rmtree(work, ignore_errors=True)
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
