#!/usr/bin/env python3
"""Periodic half-space: fastcontact (&grid periodic = .true.) against tamaas' periodic
Polonsky-Keer solvers (normal: PolonskyKeerRey; with Coulomb friction: PolonskyKeerTan) and
against Johnson's wavy-surface solution (doc/parallel.md).

    python3 -m venv /tmp/tv && /tmp/tv/bin/pip install tamaas numpy
    /tmp/tv/bin/python scripts/peers_periodic.py [--fastcontact PATH] [--out doc/peers_periodic.csv]
        [--friction-out doc/peers_periodic_friction.csv]

Cases (same heights, same mean pressure, same combined modulus E* = G/(1-nu)):
  wavy_partial  1D wavy surface, amplitude A, one wavelength per cell, mean pressure 0.45 p*
                (Johnson: pmax = 2 sqrt(pbar p*), contact fraction 2a/lambda with
                sin^2(pi a/lambda) = pbar/p*)
  rough_cell    random-phase rough cell (numpy seed 16), power-law spectrum, 128^2, mean
                pressure giving ~10 % contact
  wavy2d_friction  2D wavy cell A cos(2 pi x/L) cos(2 pi y/L) under a mean pressure and a
                mean tangential traction with Coulomb friction, 32^2 ... 256^2 (friction_case)
Discretisations differ: fastcontact uses piecewise-constant pressure elements (influence
coefficients of the element), tamaas point collocation with the continuous kernel 2/(E*|q|);
the differences below are therefore discretisation differences, not solver errors.
Python drives the comparison only; both solvers do their own work.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import tamaas as tm

G, NU = 82000.0, 0.28          # both bodies; Kalker's combined G, nu equal these
ESTAR = G / (1 - NU)           # combined plane-strain modulus E* [N/mm^2]


def run_fastcontact(exe, h0, lx, ly, fn, workdir, name, g=G, nu=NU, tangential=None, tol='1.0e-8'):
    """Solve the periodic cell with the driver; h0[iy, ix] (x fastest in the table).  With
    `tangential` (the &tangential group's keys) a normal+tangential case.  Returns the
    pressure p[iy, ix], the JSON summary and the element table."""
    ny, nx = h0.shape
    table = os.path.join(workdir, name + '.txt')
    np.savetxt(table, h0.reshape(-1, 8) if h0.size % 8 == 0 else h0.reshape(-1, 1), fmt='%.17e')
    nml = os.path.join(workdir, name + '.nml')
    problem = 'normal+tangential' if tangential else 'normal'
    with open(nml, 'w') as f:
        f.write(f"&case name = '{name}', problem = '{problem}' /\n")
        f.write(f"&material g1 = {g}, g2 = {g}, nu1 = {nu}, nu2 = {nu} /\n")
        f.write(f"&grid nx = {nx}, ny = {ny}, xmin = 0.0, xmax = {lx}, ymin = 0.0, ymax = {ly}, periodic = .true. /\n")
        f.write(f"&geometry kind = 'table', file = '{table}' /\n")
        f.write(f"&normal fn = {fn} /\n&solver tol = {tol} /\n")
        if tangential:
            f.write(f"&tangential {tangential} /\n")
    out = os.path.join(workdir, 'out')
    subprocess.run([exe, nml, '--out', out], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, name + '.json')) as f:
        js = json.load(f)
    data = np.genfromtxt(os.path.join(out, name + '.csv'), delimiter=',', names=True)
    p = np.zeros((ny, nx))
    p[data['iy'].astype(int) - 1, data['ix'].astype(int) - 1] = data['pn']
    return p, js, data


def run_tamaas(surface, lx, ly, pbar):
    """tamaas: rigid flat on an elastic half-space with heights `surface`[iy, ix]."""
    ny, nx = surface.shape
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [ly, lx], [ny, nx])
    model.E = ESTAR          # nu = 0: tamaas' E* = E/(1 - nu^2) = E
    model.nu = 0.0
    solver = tm.PolonskyKeerRey(model, np.ascontiguousarray(surface), 1e-12)
    solver.max_iter = 10000
    solver.solve(pbar)
    return np.array(model.traction).reshape(ny, nx)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--fastcontact', default=None, help='path of the fastcontact driver')
    ap.add_argument('--out', default='doc/peers_periodic.csv')
    ap.add_argument('--friction-out', default='doc/peers_periodic_friction.csv')
    args = ap.parse_args()
    exe = args.fastcontact
    if exe is None:
        exe = subprocess.run(['fpm', 'run', '--profile', 'release', 'fastcontact', '--runner', 'echo'],
                             check=True, capture_output=True, text=True).stdout.strip().splitlines()[-1]
    rows = []
    with tempfile.TemporaryDirectory() as work:
        # ---- wavy surface, partial contact (Johnson)
        lam, amp, nx, ny = 2.0, 2.0e-4, 128, 4
        dx = lam / nx
        x = (np.arange(nx) + 0.5) * dx
        z = amp * np.cos(2 * np.pi * x / lam)                 # heights, peak at x = 0
        pstar = np.pi * ESTAR * amp / lam
        pbar = 0.45 * pstar
        ly = ny * dx
        h0 = np.tile(z.max() - z, (ny, 1))
        pf, _, _ = run_fastcontact(exe, h0, lam, ly, pbar * lam * ly, work, 'wavy_partial')
        pt = run_tamaas(np.tile(z, (ny, 1)), lam, ly, pbar)
        a = lam / np.pi * np.arcsin(np.sqrt(pbar / pstar))
        for name, p in (('fastcontact', pf), ('tamaas', pt)):
            rows.append(dict(case='wavy_partial', code=name, n=f'{nx}x{ny}', pmax=p.max(),
                             pmax_rel_err=p.max() / (2 * np.sqrt(pbar * pstar)) - 1,
                             contact_fraction=(p > 0).mean(), contact_fraction_analytic=2 * a / lam,
                             mean_pressure=p.mean(), rel_l2_vs_other=np.nan))
        # ---- rough periodic cell
        n, lx = 128, 1.0
        rng = np.random.default_rng(16)
        qx = np.fft.fftfreq(n, d=lx / n)
        q = np.hypot(*np.meshgrid(qx, qx))
        spec = np.where((q >= 2) & (q <= 32), q ** (-1.8), 0.0)      # power law, cut-offs 2 and 32 /mm
        z = np.real(np.fft.ifft2(np.sqrt(spec) * np.exp(2j * np.pi * rng.random((n, n)))))
        z *= 1.0e-3 / z.std()                                        # rms 1 um
        pbar = 150.0                                                 # [N/mm^2]: about 5 % contact
        pf, _, _ = run_fastcontact(exe, z.max() - z, lx, lx, pbar * lx * lx, work, 'rough_cell')
        pt = run_tamaas(z, lx, lx, pbar)
        diff = np.linalg.norm(pf - pt) / np.linalg.norm(pt)
        for name, p, other in (('fastcontact', pf, pt), ('tamaas', pt, pf)):
            rows.append(dict(case='rough_cell', code=name, n=f'{n}x{n}', pmax=p.max(), pmax_rel_err=np.nan,
                             contact_fraction=(p > 0).mean(), contact_fraction_analytic=np.nan,
                             mean_pressure=p.mean(), rel_l2_vs_other=diff))
        friction = [friction_case(exe, work, n) for n in (32, 64, 128, 256)]
    keys = list(rows[0].keys())
    with open(args.out, 'w') as f:
        f.write(','.join(keys) + '\n')
        for r in rows:
            f.write(','.join(f'{r[k]:.6g}' if isinstance(r[k], float) else str(r[k]) for k in keys) + '\n')
    print(open(args.out).read())
    keys = list(friction[0].keys())
    with open(args.friction_out, 'w') as f:
        f.write(','.join(keys) + '\n')
        for r in friction:
            f.write(','.join(f'{r[k]:.6g}' if isinstance(r[k], float) else str(r[k]) for k in keys) + '\n')
    print(open(args.friction_out).read())


def friction_case(exe, work, n):
    """Friction on a periodic cell: the 2D wavy surface z = A cos(2πx/L) cos(2πy/L) under a mean
    pressure and a mean tangential traction (qx, qy), Coulomb friction.  tamaas'
    PolonskyKeerTan solves an elastic half-space (E, ν = 0.5: no normal-tangential coupling)
    against the rigid surface; fastcontact two identical bodies (K = 0) with ν = 0.4999 and
    G = E*(1 − ν), which give the same normal kernel and, to 4e−4, the same tangential ones
    (Cerruti: the x²/r³ and xy/r³ terms scale with ν/(1 − ν)).  tamaas' traction component 0
    lies along its first array axis, our y."""
    L, amp, estar, mu, pbar, qx, qy = 1.0, 1.0e-3, 1000.0, 0.3, 0.3, 0.05, 0.02
    x = (np.arange(n) + 0.5) * L / n
    X, Y = np.meshgrid(x, x)                                  # [iy, ix]
    z = amp * np.cos(2 * np.pi * X / L) * np.cos(2 * np.pi * Y / L)
    model = tm.ModelFactory.createModel(tm.model_type.surface_2d, [L, L], [n, n])
    model.E = estar * (1 - 0.5 ** 2)
    model.nu = 0.5
    solver = tm.PolonskyKeerTan(model, np.ascontiguousarray(z), 1e-12, mu)
    solver.max_iter = 3000
    solver.dump_freq = 10 ** 9
    solver.solve([qy, qx, pbar])
    tt = np.array(model.traction)
    tx, ty, tp = tt[..., 1], tt[..., 0], tt[..., 2]
    nu = 0.4999
    p, _, d = run_fastcontact(exe, z.max() - z, L, L, pbar * L * L, work, f'friction_{n}', g=estar * (1 - nu), nu=nu,
                              tangential=f'mu = {mu}, fx = {qx * L * L}, fy = {qy * L * L}', tol='1.0e-9')
    iy, ix = d['iy'].astype(int) - 1, d['ix'].astype(int) - 1
    fx, fy = np.zeros((n, n)), np.zeros((n, n))
    fx[iy, ix] = d['px']; fy[iy, ix] = d['py']
    stick_f = (p > 0) & (np.hypot(fx, fy) < mu * p * (1 - 1e-6))
    stick_t = (tp > 0) & (np.hypot(tx, ty) < mu * tp * (1 - 1e-6))
    slip = (p > 0) & ~stick_f & (tp > 0) & ~stick_t
    dang = np.angle(np.exp(1j * (np.arctan2(fy, fx) - np.arctan2(ty, tx))))[slip]
    return dict(case='wavy2d_friction', n=f'{n}x{n}', pressure_rel_l2=np.linalg.norm(p - tp) / np.linalg.norm(tp),
                qx_rel_l2=np.linalg.norm(fx - tx) / np.linalg.norm(tx), qy_rel_l2=np.linalg.norm(fy - ty) / np.linalg.norm(ty),
                contact_fastcontact=int((p > 0).sum()), contact_tamaas=int((tp > 0).sum()),
                stick_fastcontact=int(stick_f.sum()), stick_tamaas=int(stick_t.sum()),
                slip_angle_diff_max=float(np.abs(dang).max()) if dang.size else 0.0)


if __name__ == '__main__':
    sys.exit(main())
