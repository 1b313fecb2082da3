#!/usr/bin/env python3
"""Seeded, time-bounded check that the cases of a batch do not influence each other.

The driver keeps operators, coefficient sets and FFT plans from case to case and reuses
them while grid and material match.  Each case must still give exactly what it gives when
solved alone.  This script writes random multi-case namelists (normal, normal+tangential,
tangential, steady rolling with and without creep-force sweeps, transient rolling,
periodic cells with and without friction, and with `--ic-tool` influence-coefficient files (analytic
half-space bodies written by `fastcontact-ic --analytic`, body 1 or both bodies); different grids,
materials, loads, solvers, preconditioner forms and thread counts, small grids), runs each file whole, then every case of it alone with
`--case NAME` (which reads the cases before it only for what they pass on and builds its
operators afresh), then in two round-robin parts (`--part 1/2`, `--part 2/2`) into one
directory, and compares the outputs:

* the JSON summary, without the times and the `operator_built` flags;
* the element table, the creep-force table and the transient steps table, without their
  `seconds` column.

They must agree to the last digit (the same arithmetic in the same order).  A last run with
`--resume` on the whole run's directory must skip every case that has a summary and
rewrite none.  A difference
prints the seed, the file and the first differing keys; the exit status is 1 when any case
differed.

Usage:  scripts/fuzz_isolation.py --driver PATH [--ic-tool PATH] [--seed N] [--budget SECONDS] [--keep DIR]

Standard library only.  The seed defaults to FUZZ_SEED or the clock; `--seed N` repeats a
run exactly.
"""
import argparse
import csv
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

HEAD = [
    "&material g1 = 200.0, g2 = 200.0, nu1 = 0.42, nu2 = 0.42 /",
    "&grid nx = 20, ny = 16, xmin = -1.3, xmax = 1.3, ymin = -1.3, ymax = 1.3 /",
    "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /",
    "&normal fn = 9.1954 /",
    "&tangential mu = 0.4, xi = 0.002, eta = 0.001, phi = 0.003 /",
]


def periodic_case(rnd, i):
    """A periodic wavy cell (normal, or with a tangential force): its own material, grid, geometry, loads."""
    n = rnd.choice([16, 24, 32])
    prob = rnd.choice(['normal', 'normal+tangential'])
    nu = rnd.choice([0.0, 0.3])
    g2, nu2 = rnd.choice([(200.0, nu), (800.0, 0.28)])   # identical bodies (K = 0) or not
    return [f"&case name = 'c{i}', problem = '{prob}' /",
            f"&material g1 = 200.0, g2 = {g2}, nu1 = {nu}, nu2 = {nu2} /",
            f"&grid nx = {n}, ny = {n}, xmin = 0.0, xmax = 1.0, ymin = 0.0, ymax = 1.0, periodic = .true. /",
            f"&geometry kind = 'wavy', amplitude = 0.001, wavelength_x = 1.0, wavelength_y = {rnd.choice([0.0, 1.0])} /",
            f"&normal fn = {rnd.choice([0.5, 5.0])} /",
            f"&tangential sweep = '', mu = 0.3, fx = {rnd.choice([0.03, 0.1])}, fy = {rnd.choice([0.0, -0.05])} /",
            f"&solver normal = '{rnd.choice(['bccg', 'norm'])}', tangential = 'tangcg' /"]


# coefficient files (--ic-tool): grid -> {body: path}, written once per run
IC_GRIDS = [(20, 16), (24, 20)]
IC_BODIES = [(200.0, 0.42), (82000.0, 0.28)]


def ic_case(rnd, i, files):
    """A case whose body 1 (and maybe body 2) comes from a coefficient file on its grid."""
    nx, ny = rnd.choice(IC_GRIDS)
    b1, b2 = rnd.choice(IC_BODIES), rnd.choice(IC_BODIES)
    f2 = files[(nx, ny)][b2] if rnd.random() < 0.5 else ''
    prob = rnd.choice(['normal', 'normal+tangential', 'rolling'])
    return [f"&case name = 'c{i}', problem = '{prob}' /",
            f"&material g1 = {b1[0]}, g2 = {b2[0]}, nu1 = {b1[1]}, nu2 = {b2[1]}, "
            f"ic_file = '{files[(nx, ny)][b1]}', ic_file2 = '{f2}' /",
            f"&grid nx = {nx}, ny = {ny}, xmin = -1.3, xmax = 1.3, ymin = -1.3, ymax = 1.3, periodic = .false. /",
            "&geometry kind = 'quadratic', rx = 50.0, ry = 50.0 /",
            f"&solver normal = '{rnd.choice(['bccg', 'norm'])}' /",
            "&tangential sweep = '' /"]


def case_groups(rnd, i, periodic_before, files=None, ic_before=False):
    """The groups of case i: a problem and a random subset of changes to inherit from;
    whether it is periodic and whether it reads coefficient files."""
    if files and rnd.random() < 0.15:
        return ic_case(rnd, i, files), False, True
    if rnd.random() < 0.1:
        g, per = periodic_case(rnd, i), True
        if ic_before:
            g.insert(1, "&material ic_file = '', ic_file2 = '' /")
        return g, per, False
    prob = rnd.choice(['normal', 'normal+tangential', 'tangential', 'rolling', 'rolling', 'transient_rolling'])
    g = [f"&case name = 'c{i}', problem = '{prob}' /"]
    if ic_before:   # back to the half-space kernels
        g.append("&material ic_file = '', ic_file2 = '' /")
    if periodic_before:   # back to the quadratic scene of the head, on the half-space
        g += [HEAD[1].replace(' /', ', periodic = .false. /')] + HEAD[2:4]
    if rnd.random() < 0.25:   # identical bodies (K = 0): often the same G with another ν
        gg, nu = rnd.choice([200.0, 82000.0]), rnd.choice([0.28, 0.42, 0.3])
        g.append(f"&material g1 = {gg}, g2 = {gg}, nu1 = {nu}, nu2 = {nu} /")
    elif rnd.random() < 0.35:
        g.append(f"&material g1 = {rnd.choice([200.0, 82000.0, 1e30])}, g2 = {rnd.choice([200.0, 82000.0])}, "
                 f"nu1 = {rnd.choice([0.28, 0.42, 0.0])}, nu2 = {rnd.choice([0.28, 0.42])} /")
    if rnd.random() < 0.5:
        g.append(f"&grid nx = {rnd.choice([12, 16, 20, 24, 30])}, ny = {rnd.choice([12, 16, 20, 24])}, "
                 "xmin = -1.3, xmax = 1.3, ymin = -1.3, ymax = 1.3 /")
    if rnd.random() < 0.3:
        g.append(f"&geometry kind = 'quadratic', rx = {rnd.choice([50.0, 30.0])}, ry = {rnd.choice([50.0, 80.0])} /")
    if rnd.random() < 0.4:
        g.append(rnd.choice(["&normal fn = 9.1954 /", "&normal approach = 0.02 /", "&normal fn = 5.0 /"]))
    if rnd.random() < 0.6:
        if rnd.random() < 0.7 or prob == 'transient_rolling':
            g.append(f"&tangential mu = {rnd.choice([0.3, 0.4])}, xi = {rnd.choice([0.0, 0.001, 0.0021, -0.003])}, "
                     f"eta = {rnd.choice([0.0, 0.001])}, phi = {rnd.choice([0.0, 0.003, -0.01])} /")
        else:
            g.append(f"&tangential mu = 0.4, fx = {rnd.choice([-1.0, 0.5])}, fy = {rnd.choice([0.0, 0.5])} /")
    s = []
    if rnd.random() < 0.3:
        s.append(f"normal = '{rnd.choice(['bccg', 'norm'])}'")
    if rnd.random() < 0.3:
        s.append(f"rolling = '{rnd.choice(['gmres', 'gmres', 'march'])}'")
    if rnd.random() < 0.3:
        s.append(f"tol = {rnd.choice([1e-5, 1e-6, 1e-4])}")
    if rnd.random() < 0.2:
        s.append(f"threads = {rnd.choice([1, 2])}")
    if rnd.random() < 0.2:
        s.append(f"model = '{rnd.choice(['auto', 'full'])}'")
    if rnd.random() < 0.2:
        s.append(f"fft_preconditioner = '{rnd.choice(['circulant', 'toeplitz'])}'")
    if rnd.random() < 0.2:
        s.append(f"rolling_start = '{rnd.choice(['fastsim', 'adhesion'])}'")
    if s:
        g.append('&solver ' + ', '.join(s) + ' /')
    if prob == 'transient_rolling':
        g.append(f"&tangential xi = 0.002, nsteps = {rnd.choice([10, 30])} /")
    if prob == 'rolling' and rnd.random() < 0.3:
        g.append(rnd.choice([
            "&tangential xi = 0.001, sweep = 'xi', sweep_from = 0.0, sweep_to = 0.004, sweep_n = 5 /",
            "&tangential xi = 0.001, sweep = 'phi', sweep_from = -0.01, sweep_to = 0.01, sweep_n = 4 /",
            "&tangential fx = -0.5, sweep = 'fx', sweep_from = -0.5, sweep_to = 0.5, sweep_n = 4 /"]))
    else:
        g.append("&tangential sweep = '' /")
    return g, False, False


def summary(path):
    """The JSON summary without times and operator-reuse flags."""
    def clean(x):
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items() if 'seconds' not in k and not k.startswith('operator_built')}
        if isinstance(x, list):
            return [clean(v) for v in x]
        return x
    with open(path) as f:
        return clean(json.load(f))


def table(path):
    """A CSV table without its `seconds` column."""
    with open(path, newline='') as f:
        rows = list(csv.reader(f))
    if not rows:
        return rows
    drop = {i for i, h in enumerate(rows[0]) if h == 'seconds'}
    return [[v for i, v in enumerate(r) if i not in drop] for r in rows]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--driver', required=True)
    ap.add_argument('--seed', type=int, default=int(os.environ.get('FUZZ_SEED', time.time_ns() % 2**31)))
    ap.add_argument('--budget', type=float, default=60.0, help='seconds for new files (default 60)')
    ap.add_argument('--timeout', type=float, default=300.0, help='seconds per driver run')
    ap.add_argument('--keep', help='keep the files of differing batches in this directory')
    ap.add_argument('--ic-tool', help='fastcontact-ic: also cases with coefficient files (analytic bodies)')
    a = ap.parse_args()
    print(f'isolation fuzz seed: {a.seed} (repeat: scripts/fuzz_isolation.py --driver D --seed {a.seed})', flush=True)
    rnd = random.Random(a.seed)
    env = dict(os.environ, OMP_WAIT_POLICY='passive')
    t_end = time.time() + a.budget
    nfiles = ncases = bad = 0
    files, icdir = None, None
    if a.ic_tool:
        icdir = tempfile.mkdtemp(prefix='fc_isolation_ic_')
        files = {}
        for nx, ny in IC_GRIDS:
            files[(nx, ny)] = {}
            for g, nu in IC_BODIES:
                model = os.path.join(icdir, f'm{nx}x{ny}_{int(g)}.nml')
                path = os.path.join(icdir, f'b{nx}x{ny}_{int(g)}.fcic')
                with open(model, 'w') as f:
                    f.write(f"&material g1 = {g}, nu1 = {nu} /\n"
                            f"&grid nx = {nx}, ny = {ny}, xmin = -1.3, xmax = 1.3, ymin = -1.3, ymax = 1.3 /\n")
                subprocess.run([a.ic_tool, model, '--out', path, '--analytic'], check=True, capture_output=True)
                files[(nx, ny)][(g, nu)] = path
    while time.time() < t_end:
        work = tempfile.mkdtemp(prefix='fc_isolation_')
        lines, periodic, ic = [], False, False
        for i in range(rnd.randint(2, 6)):
            g, periodic, ic = case_groups(rnd, i, periodic, files, ic)
            lines += (g[:1] + HEAD + g[1:]) if i == 0 else g
        nml = os.path.join(work, 'cases.nml')
        with open(nml, 'w') as f:
            f.write('\n'.join(lines) + '\n')
        subprocess.run([a.driver, nml, '--out', os.path.join(work, 'all')], capture_output=True, env=env,
                       timeout=a.timeout)
        alld = os.path.join(work, 'all')
        names = sorted(x[:-5] for x in os.listdir(alld) if x.endswith('.json')) if os.path.isdir(alld) else []
        differs = []
        for n in names:
            oned = os.path.join(work, 'one_' + n)
            subprocess.run([a.driver, nml, '--out', oned, '--case', n], capture_output=True, env=env,
                           timeout=a.timeout)
            if not os.path.exists(os.path.join(oned, n + '.json')):
                differs.append(f'{n}: no summary when solved alone')
                continue
            s_all, s_one = summary(os.path.join(alld, n + '.json')), summary(os.path.join(oned, n + '.json'))
            if s_all != s_one:
                keys = [k for k in s_all if s_all.get(k) != s_one.get(k)]
                differs.append(f'{n}: summary keys {keys[:6]}')
            for suffix in ('.csv', '_creep.csv', '_steps.csv'):
                p = os.path.join(alld, n + suffix)
                if os.path.exists(p):
                    q = os.path.join(oned, n + suffix)
                    if not os.path.exists(q) or table(p) != table(q):
                        differs.append(f'{n}: {n}{suffix}')
        # the file in two round-robin parts into one directory: every case as in the whole run
        partd = os.path.join(work, 'parts')
        for part in ('1/2', '2/2'):
            subprocess.run([a.driver, nml, '--out', partd, '--part', part], capture_output=True, env=env,
                           timeout=a.timeout)
        for n in names:
            p, q = os.path.join(alld, n + '.json'), os.path.join(partd, n + '.json')
            if not os.path.exists(q) or summary(p) != summary(q):
                differs.append(f'{n}: --part differs')
        # --resume on the whole run's directory: every case with a summary skipped, none rewritten
        before = {n: open(os.path.join(alld, n + '.json')).read() for n in names}
        r = subprocess.run([a.driver, nml, '--out', alld, '--resume'], capture_output=True, env=env,
                           timeout=a.timeout, text=True, errors='replace')
        if f'({len(names)} of them done in an earlier run: skipped)' not in r.stdout:
            differs.append(f'--resume: not all {len(names)} cases skipped')
        if any(open(os.path.join(alld, n + '.json')).read() != before[n] for n in names):
            differs.append('--resume rewrote a summary')
        nfiles += 1
        ncases += len(names)
        if differs:
            bad += 1
            print(f'DIFFERS (seed {a.seed}, file {nfiles}): ' + '; '.join(differs))
            print('--- namelist ---\n' + '\n'.join(lines) + '\n---')
            if a.keep:
                shutil.copytree(work, os.path.join(a.keep, f'file{nfiles}'), dirs_exist_ok=True)
        shutil.rmtree(work, ignore_errors=True)
    if icdir:
        shutil.rmtree(icdir, ignore_errors=True)
    print(f'isolation fuzz: {nfiles} files, {ncases} cases solved whole and alone, {bad} files differing')
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
