#!/usr/bin/env python3
"""Charts of the numerical influence-coefficient benchmark (doc/numerical_ic.md).

Reads doc/bench_fem_ic_coef.csv and doc/bench_fem_ic_contact.csv (written by
`fastcontact-bench-fem-ic coef ...` and `... contact ...`) and writes
doc/fem_ic_coef.png (eq. 5.12 error at the origin against L/h_c, per mesh and order) and
doc/fem_ic_cost.png (relative errors in Fz and Fx against cost = CalculiX CPU + solve CPU).

    python3 -m venv .venv-plots && .venv-plots/bin/pip install -r scripts/requirements-plots.txt
    .venv-plots/bin/python scripts/plot_fem_ic.py
"""
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC = os.path.join(ROOT, "doc")


NAMES = {"hex": "Mesh1 nested boxes", "tensor": "tensor hexahedra", "prism": "Mesh2 extruded prisms",
         "tprism": "tensor prisms"}


def rows(name):
    path = os.path.join(DOC, name)
    return list(csv.DictReader(open(path, newline=""))) if os.path.exists(path) else []


def coef_chart():
    data = rows("bench_fem_ic_coef.csv")
    if not data:
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    groups = {}
    for r in data:
        groups.setdefault((r["mesh"], r["order"], r["integration"], r["stretch"]), []).append(r)
    for (mesh, order, integ, f), rs in sorted(groups.items()):
        rs.sort(key=lambda r: float(r["l_over_hc"]))
        kind = "quadratic" if order == "2" else "linear"
        if order == "2" and mesh in ("hex", "tensor"):
            kind += " (C3D20R)" if integ == "reduced" else " (C3D20)"
        ax.loglog([float(r["l_over_hc"]) for r in rs], [max(float(r["err_origin"]), 1e-5) for r in rs],
                  {"hex": "o-", "tensor": "s--", "prism": "v-", "tprism": "^:"}[mesh],
                  label=f"{NAMES[mesh]}, {kind}, f = {float(f):g}")
    ax.axhline(0.01, ls="--", c="k", lw=0.8, label="target eq. 5.12")
    ax.set_xlabel("L / h_c")
    ax.set_ylabel("|A0 - F0| / |A0|")
    ax.set_title("A^zz at the origin, 10x10 grid (thesis §5.3)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(DOC, "fem_ic_coef.png"), dpi=120)


def cost_chart():
    data = rows("bench_fem_ic_contact.csv")
    if not data:
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 6.5), sharex=True)
    for ax, key, title, target in [(axes[0], "fz_err", "Fz (vs Hertz 9.1954 N)", 1e-3),
                                   (axes[1], "fx_err", "Fx (vs 3.2216 N)", 3e-4)]:
        ax.axhline(target, ls="--", c="k", lw=0.8)
        for r in data:
            cost = float(r["ccx_cpu_s"]) + float(r["solve_s"])
            err = abs(float(r[key]))
            ref = abs(float(r[key + "_halfspace"]))
            mk = {"hex": "o", "tensor": "s", "prism": "v", "tprism": "^"}[r["mesh"]]
            integ = "R" if r["integration"] == "reduced" else ""
            ax.loglog(cost, max(err, 1e-7), mk,
                      label=f"{r['grid']}² {NAMES[r['mesh']]} {integ} f={r['stretch']} L={float(r['L_mm']):g}")
            ax.annotate(f"{r['grid']}²", (cost, max(err, 1e-7)), fontsize=7)
            ax.loglog(cost, max(ref, 1e-7), "x", c="gray")
        ax.set_xlabel("cost: CalculiX CPU + solve CPU [s]")
        ax.set_ylabel("relative error")
        ax.set_title(title + "\nx: half-space kernels, same grid; dashed: 160² target", fontsize=9)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=6)
    fig.tight_layout(rect=(0, 0.22, 1, 1))
    fig.savefig(os.path.join(DOC, "fem_ic_cost.png"), dpi=120)


if __name__ == "__main__":
    coef_chart()
    cost_chart()
