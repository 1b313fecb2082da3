#!/usr/bin/env python3
"""Pictures of one fastcontact case: pressure, tangential traction vectors, slip, and the
adhesion / slip / exterior map, from the driver's element table.

Usage:  python3 scripts/plot_case.py OUT/CASE [--out FILE.png] [--arrows N]

OUT/CASE is the path without extension: OUT/CASE.npy (`&output table_format = 'npy'` or
'both') is read if it exists, else OUT/CASE.csv; OUT/CASE.json gives nx, ny and the title.
Writes OUT/CASE.png (or FILE.png): four panels with x to the right and y up, element
centres as pixel centres.  --arrows N: at most N arrows per direction (default 24).
Normal problems (px = py = 0) get the pressure and the contact map only.

Needs numpy and matplotlib (scripts/requirements-plots.txt); not a dependency of the package.
"""
import argparse
import json
import os
import sys


def load_table(stem):
    import numpy as np
    if os.path.exists(stem + ".npy"):
        t = np.load(stem + ".npy")
        cols = {k: t[k] for k in ("ix", "iy", "x", "y", "pn", "px", "py", "sx", "sy", "gap")}
        cols["status"] = np.array([s.decode() for s in t["status"]])
        return cols
    names = ["ix", "iy", "x", "y", "status", "pn", "px", "py", "sx", "sy", "gap"]
    raw = np.genfromtxt(stem + ".csv", delimiter=",", skip_header=1, dtype=None, encoding="ascii",
                        names=names)
    cols = {k: np.asarray(raw[k], dtype=float) for k in names if k != "status"}
    cols["status"] = np.asarray(raw["status"], dtype=str)
    return cols


def grid_of(cols, key, nx, ny):
    """Column `key` as an (ny, nx) image, rows y increasing."""
    import numpy as np
    img = np.full((ny, nx), np.nan)
    img[cols["iy"].astype(int) - 1, cols["ix"].astype(int) - 1] = cols[key]
    return img


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("stem", help="OUT/CASE (without extension)")
    ap.add_argument("--out", help="output picture (default OUT/CASE.png)")
    ap.add_argument("--arrows", type=int, default=24)
    args = ap.parse_args()
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    stem = args.stem[:-4] if args.stem.endswith((".csv", ".npy")) else args.stem
    with open(stem + ".json") as f:
        js = json.load(f)
    nx, ny = int(js["nx"]), int(js["ny"])
    cols = load_table(stem)
    x = np.unique(cols["x"]); y = np.unique(cols["y"])
    dx = (x[1] - x[0]) if nx > 1 else js.get("dx", 1.0)
    dy = (y[1] - y[0]) if ny > 1 else js.get("dy", 1.0)
    extent = [x[0] - dx / 2, x[-1] + dx / 2, y[0] - dy / 2, y[-1] + dy / 2]
    pn = grid_of(cols, "pn", nx, ny)
    px = grid_of(cols, "px", nx, ny); py = grid_of(cols, "py", nx, ny)
    sx = grid_of(cols, "sx", nx, ny); sy = grid_of(cols, "sy", nx, ny)
    state = np.zeros((ny, nx))
    code = {"E": 0, "A": 1, "S": 2}
    state[cols["iy"].astype(int) - 1, cols["ix"].astype(int) - 1] = [code.get(s, 0) for s in cols["status"]]
    tangential = bool(np.any(px != 0) or np.any(py != 0))

    npanel = 4 if tangential else 2
    fig, axes = plt.subplots(1, npanel, figsize=(4.6 * npanel, 4.4), constrained_layout=True)
    title = "%s — %s" % (js.get("name", ""), js.get("title", ""))
    fig.suptitle(title + "   (Fn = %.6g N%s)" % (js.get("fn", float("nan")),
                 ", Fx = %.4g N, Fy = %.4g N" % (js["fx"], js["fy"]) if tangential else ""))

    ax = axes[0]
    im = ax.imshow(np.where(pn > 0, pn, np.nan), origin="lower", extent=extent, cmap="viridis", aspect="equal")
    fig.colorbar(im, ax=ax, shrink=0.8, label="pressure pn [N/mm²]")
    ax.set_title("pressure")

    k = 1
    if tangential:
        ax = axes[k]; k += 1
        mag = np.hypot(px, py)
        im = ax.imshow(np.where(pn > 0, mag, np.nan), origin="lower", extent=extent, cmap="magma", aspect="equal")
        fig.colorbar(im, ax=ax, shrink=0.8, label="|p_t| [N/mm²]")
        stepx = max(1, nx // args.arrows); stepy = max(1, ny // args.arrows)
        X, Y = np.meshgrid(x, y)
        sel = (slice(stepy // 2, None, stepy), slice(stepx // 2, None, stepx))
        mask = pn[sel] > 0
        ax.quiver(X[sel][mask], Y[sel][mask], px[sel][mask], py[sel][mask], color="white", pivot="middle",
                  scale_units="xy", angles="xy")
        ax.set_title("tangential traction (arrows)")

        ax = axes[k]; k += 1
        smag = np.hypot(sx, sy)
        im = ax.imshow(np.where(state == 2, smag, np.nan), origin="lower", extent=extent, cmap="plasma",
                       aspect="equal")
        # steady rolling: slip velocity over rolling velocity (dimensionless); shift
        # problems and transient steps: the slip of the step [mm]
        rolling = js.get("problem", "") == "rolling"
        fig.colorbar(im, ax=ax, shrink=0.8, label="|s| [-] (slip / rolling velocity)" if rolling else "|s| [mm]")
        ax.set_title("slip (slip area)")

    ax = axes[k]
    cmap = ListedColormap(["#f0f0f0", "#2b7bba", "#e8702a"])
    ax.imshow(state, origin="lower", extent=extent, cmap=cmap, vmin=-0.5, vmax=2.5, aspect="equal",
              interpolation="nearest")
    from matplotlib.patches import Patch
    labels = ["exterior", "adhesion", "slip"] if tangential else ["exterior", "contact", ""]
    handles = [Patch(color=cmap(i), label=labels[i]) for i in range(3) if labels[i]]
    ax.legend(handles=handles, loc="upper right", fontsize=8)
    ax.set_title("adhesion / slip / exterior" if tangential else "contact area")
    for a in axes:
        a.set_xlabel("x [mm]"); a.set_ylabel("y [mm]")
    out = args.out or stem + ".png"
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    sys.exit(main())
