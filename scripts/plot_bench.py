#!/usr/bin/env python3
"""Charts from the benchmark-suite CSV (doc/benchmarks.md).

Reads doc/bench_suite.csv (written by `fpm run --profile release fastcontact-bench-suite`)
and writes into doc/:

* bench_accuracy_<family>.png  — error against CPU time (set-up + solve), one line per solver
  and options, one point per grid (grid sizes written next to the first line's points);
  families: hertz, rough (case 3 and case 1: contact-area error; rough_p: case 3 pressure
  difference), cattaneo (case 5), mindlin (Cattaneo–Mindlin), mp1;
* bench_cost.png — solve time against unknowns on log–log axes, one panel per family, with
  the least-squares exponent t ~ n^e of each line in the legend (also printed to stdout);
* bench_exponents.csv — the fitted exponents (family, solver, options, exponent, grids).

Usage (from the repository root):

    python3 -m venv .venv-plots && .venv-plots/bin/pip install -r scripts/requirements-plots.txt
    .venv-plots/bin/python scripts/plot_bench.py [CSV] [--out DIR]

With no venv at hand, `python3 scripts/plot_bench.py --setup` creates .venv-plots, installs
the requirements and re-runs itself inside it.
"""
import csv
import math
import os
import subprocess
import sys
from collections import defaultdict

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VENV = os.path.join(ROOT, ".venv-plots")

# (family key, title, case names in the CSV, error label[, CSV column of the error; default
# `error`, taken as an absolute value])
FAMILIES = [
    ("hertz", "Hertz Test I", ["hertz_test1"],
     "RMS error of p vs analytic Hertz [N/mm²]"),
    ("rough", "Rough punch, case 3 (δ = 0.25, ≈28 % contact)", ["rough_case3"],
     "|contact area − ref| / ref (finest-grid BCCG)", "area_error_rel"),
    ("rough1", "Rough punch, case 1 (δ = −0.11, ≈5 % contact)", ["rough_case1"],
     "|contact area − ref| / ref (finest-grid BCCG)", "area_error_rel"),
    ("rough_p", "Rough punch, case 3: pressure difference", ["rough_case3"],
     "‖p − p_ref‖/‖p_ref‖ (block-averaged finest BCCG)"),
    ("cattaneo", "Cattaneo case 5 (60 % slip)", ["cattaneo_case5"],
     "‖p_t − p_t,ref‖/‖p_t,ref‖ (block-averaged finest TangCG)"),
    ("mindlin", "Cattaneo–Mindlin, Fx = 0.875 μ Fn", ["cattaneo_mindlin"],
     "RMS of |p_t| − Cattaneo–Mindlin [N/mm²]"),
    ("mp1", "MP1 (2D strip, no slip)", ["mp1"],
     "‖p − p_ref‖/‖p_ref‖ (block-averaged finest MG)"),
]

COST_FAMILIES = [
    ("Hertz Test I", ["hertz_test1"]),
    ("Rough punch (cases 1–3, mean)", ["rough_case1", "rough_case2", "rough_case3"]),
    ("Cattaneo cases 1–7 (mean)", ["cattaneo_case%d" % c for c in range(1, 8)]),
    ("MP1 strip", ["mp1"]),
]


def ensure_venv():
    """Create .venv-plots with the requirements and re-run this script inside it."""
    py = os.path.join(VENV, "bin", "python")
    if not os.path.exists(py):
        subprocess.check_call([sys.executable, "-m", "venv", VENV])
        # keep the venv out of git without touching the shared .gitignore
        with open(os.path.join(VENV, ".gitignore"), "w") as f:
            f.write("*\n")
        subprocess.check_call([py, "-m", "pip", "install", "-q", "-r",
                               os.path.join(ROOT, "scripts", "requirements-plots.txt")])
    args = [a for a in sys.argv[1:] if a != "--setup"]
    os.execv(py, [py, os.path.abspath(__file__)] + args)


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("error", "fn_error_rel", "area_error_rel", "setup_seconds", "solve_seconds", "total_seconds",
                  "work_units", "peak_rss_mb"):
            r[k] = float(r[k])
        # process CPU time when the CSV has it (robust when other jobs share the cores)
        for k in ("setup", "solve", "total"):
            if r.get(k + "_cpu_seconds"):
                r[k + "_seconds"] = float(r[k + "_cpu_seconds"])
        for k in ("nx", "ny", "unknowns", "iterations"):
            r[k] = int(r[k])
    return rows


def label_of(r):
    opts = r["options"].replace(";tol=1e-6", "").replace(";tol=1e-5", "").replace(";tol=1e-8", "")
    opts = opts.replace("tol=1e-6", "").replace("tol=1e-5", "").replace("tol=1e-8", "")
    opts = opts.replace("smoother=", "").replace("precondition", "prec").replace("no_prec", "no-prec")
    opts = opts.replace("force;", "").replace(";force", "").replace("force", "")
    s = r["solver"]
    opts = opts.strip(";").replace(";", " ")
    return s + (" " + opts if opts else "")


def fit_exponent(ns, ts):
    pts = [(math.log(n), math.log(t)) for n, t in zip(ns, ts) if n > 0 and t > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
    return sxy / sxx if sxx > 0 else float("nan")


def main():
    if "--setup" in sys.argv:
        ensure_venv()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    out = os.path.join(ROOT, "doc")
    if "--out" in sys.argv:
        out = sys.argv[sys.argv.index("--out") + 1]
        args = [a for a in args if a != out]
    path = args[0] if args else os.path.join(ROOT, "doc", "bench_suite.csv")
    rows = read_rows(path)
    os.makedirs(out, exist_ok=True)
    floor = 1e-4  # seconds: timer floor for log axes

    markers = "osD^v<>ph*"
    written = []
    for fam in FAMILIES:
        key, title, cases, ylabel = fam[:4]
        column = fam[4] if len(fam) > 4 else "error"
        sel = [r for r in rows if r["case"] in cases]
        if not sel:
            continue
        lines = defaultdict(list)
        for r in sel:
            lines[label_of(r)].append(r)
        fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=100)
        for i, (lab, rs) in enumerate(sorted(lines.items())):
            rs.sort(key=lambda r: r["unknowns"])
            t = [max(r["total_seconds"], floor) for r in rs]
            e = [max(abs(r[column]), 1e-12) for r in rs]
            ax.loglog(t, e, marker=markers[i % len(markers)], label=lab)
            for r, ti, ei in zip(rs, t, e):
                if r["status"] != "converged":
                    ax.plot([ti], [ei], "x", color="red", markersize=10)
            # grid size next to the last point
            if i == 0:
                for r, ti, ei in zip(rs, t, e):
                    ax.annotate("%dx%d" % (r["nx"], r["ny"]), (ti, ei), fontsize=7,
                                textcoords="offset points", xytext=(3, 3))
        ax.set_xlabel("CPU time, set-up + solve [s] (process CPU time, 1 thread)")
        ax.set_ylabel(ylabel, fontsize=9)
        ax.set_title("%s\naccuracy against time (a point per grid)" % title, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fn = os.path.join(out, "bench_accuracy_%s.png" % key)
        fig.savefig(fn)
        plt.close(fig)
        written.append(fn)

    fams = [(t, c) for t, c in COST_FAMILIES if any(r["case"] in c for r in rows)]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5), dpi=100)
    exps = []
    print("fitted exponents: solve_seconds ~ unknowns^e (least squares over the grids)")
    for ax, (title, cases) in zip(axes.flat, fams):
        groups = defaultdict(lambda: defaultdict(list))
        for r in rows:
            if r["case"] in cases and r["status"] == "converged":
                groups[label_of(r)][r["unknowns"]].append(r["solve_seconds"])
        for i, (lab, byn) in enumerate(sorted(groups.items())):
            ns = sorted(byn)
            ts = [max(sum(byn[n]) / len(byn[n]), floor) for n in ns]
            # fit only above the timer floor and from the 2nd grid on when there are >= 4
            use = [(n, t) for n, t in zip(ns, ts) if t > 2 * floor]
            if len(use) >= 4:
                use = use[1:]
            e = fit_exponent([u[0] for u in use], [u[1] for u in use])
            exps.append((title, lab, e, len(use)))
            print("  %-32s %-28s e = %5.2f  (%d grids)" % (title, lab, e, len(use)))
            ax.loglog(ns, ts, marker=markers[i % len(markers)],
                      label="%s  (e = %.2f)" % (lab, e) if e == e else lab)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("unknowns")
        ax.set_ylabel("solve CPU time [s]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(fams):]:
        ax.axis("off")
    fig.suptitle("Cost against unknowns (log–log), fitted t ~ n^e", fontsize=11)
    fig.tight_layout()
    fn = os.path.join(out, "bench_cost.png")
    fig.savefig(fn)
    plt.close(fig)
    written.append(fn)
    with open(os.path.join(out, "bench_exponents.csv"), "w") as f:
        f.write("family,solver,exponent,grids\n")
        for title, lab, e, m in exps:
            f.write('"%s","%s",%.3f,%d\n' % (title, lab, e, m))
    written.append(os.path.join(out, "bench_exponents.csv"))
    for w in written:
        print("wrote", os.path.relpath(w, ROOT))


if __name__ == "__main__":
    main()
