#!/usr/bin/env python3
"""Charts of rolling contact (doc/rolling.md): creep-force curves written by the driver
(NAME_creep.csv of a `&tangential sweep` case) and FASTSIM's error against the full theory
(doc/bench_rolling_fastsim.csv of `fastcontact-bench-rolling --fastsim`).

    python3 -m venv .venv-plots && .venv-plots/bin/pip install -r scripts/requirements-plots.txt
    .venv-plots/bin/python scripts/plot_creep.py --curves out/curves/*_creep.csv --out doc/rolling_curves.png
    .venv-plots/bin/python scripts/plot_creep.py --fastsim doc/bench_rolling_fastsim.csv --out doc/rolling_fastsim.png

Curves: one column per swept quantity (xi, eta, phi), one line per file (label: file stem);
top row Fx/(mu Fn) and Fy/(mu Fn) against the swept value, bottom row the frictional
dissipation per mm rolled over mu Fn (Tgamma / (mu Fn), the `dissipation` column) when the
files have it.  FASTSIM: |F_fastsim - F_full|/(mu Fn)
against the normalised creepage, one panel per direction, one line per a/b.
"""
import argparse
import csv
import os
import sys


def read(path):
    with open(path) as f:
        return [{k.strip(): v.strip() for k, v in row.items()} for row in csv.DictReader(f)]


def swept(rows):
    """Name of the swept column: the one of xi, eta, phi equal to 'value' and varying."""
    for name in ('xi', 'eta', 'phi', 'fx', 'fy'):
        vals = [float(r[name]) for r in rows if name in r]
        if vals and len(set(vals)) > 1 and all(abs(float(r[name]) - float(r['value'])) < 1e-12 for r in rows):
            return name
    return 'value'


def plot_curves(paths, out, plt):
    groups = {}
    for p in paths:
        rows = read(p)
        groups.setdefault(swept(rows), []).append((os.path.basename(p).replace('_creep.csv', ''), rows))
    tgamma = all('dissipation' in rows[0] for sets in groups.values() for _, rows in sets if rows)
    nrow = 2 if tgamma else 1
    fig, axes = plt.subplots(nrow, len(groups), figsize=(5 * len(groups), 4 * nrow), squeeze=False)
    units = {'xi': 'creepage xi [-]', 'eta': 'creepage eta [-]', 'phi': 'spin phi [1/mm]'}
    for col, (name, sets) in enumerate(sorted(groups.items())):
        ax = axes[0][col]
        for label, rows in sets:
            x = [float(r['value']) for r in rows]
            ax.plot(x, [float(r['fx_mufn']) for r in rows], 'o-', ms=3, label=label + ': Fx/(mu Fn)')
            ax.plot(x, [float(r['fy_mufn']) for r in rows], 's--', ms=3, label=label + ': Fy/(mu Fn)')
        ax.set_xlabel(units.get(name, name))
        ax.set_ylabel('creep force / (mu Fn)')
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        if tgamma:
            ax = axes[1][col]
            for label, rows in sets:
                x = [float(r['value']) for r in rows]
                # mu Fn from a point with a non-zero force: |F| / |F / (mu Fn)|
                mufn = next((abs(float(r['fx'])) / abs(float(r['fx_mufn'])) for r in rows
                             if float(r['fx_mufn']) != 0), None) or \
                    next((abs(float(r['fy'])) / abs(float(r['fy_mufn'])) for r in rows if float(r['fy_mufn']) != 0), 1.0)
                ax.plot(x, [float(r['dissipation']) / mufn for r in rows], 'o-', ms=3, label=label)
            ax.set_xlabel(units.get(name, name))
            ax.set_ylabel('dissipation per mm rolled / (mu Fn)  [T gamma / (mu Fn)]')
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def plot_fastsim(path, out, plt):
    rows = read(path)
    dirs = ['xi', 'eta', 'phi']
    fig, axes = plt.subplots(1, 3, figsize=(15, 4), squeeze=False)
    for ax, d in zip(axes[0], dirs):
        ratios = sorted({r['a_over_b'] for r in rows if r['direction'] == d}, key=float)
        for ab in ratios:
            sel = [r for r in rows if r['direction'] == d and r['a_over_b'] == ab]
            ax.plot([float(r['creepage_star']) for r in sel], [float(r['error_mufn']) for r in sel], 'o-', ms=3,
                    label='a/b = ' + ab)
        ax.set_xlabel('normalised creepage %s* = G ab C / (3 mu Fn) * %s' % (d, d))
        ax.set_ylabel('|F_fastsim - F_full| / (mu Fn)')
        ax.set_title('FASTSIM error, creepage ' + d)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--curves', nargs='*', default=[], help='NAME_creep.csv files of the driver')
    ap.add_argument('--fastsim', help='doc/bench_rolling_fastsim.csv')
    ap.add_argument('--out', required=True, help='PNG file to write')
    a = ap.parse_args()
    try:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit('matplotlib missing: pip install -r scripts/requirements-plots.txt (in a venv)')
    if a.fastsim:
        plot_fastsim(a.fastsim, a.out, plt)
    elif a.curves:
        plot_curves(a.curves, a.out, plt)
    else:
        sys.exit('give --curves FILES or --fastsim FILE')


if __name__ == '__main__':
    main()
