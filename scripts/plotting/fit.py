"""Plot of a fitted law: data and fit (F against delta, in mm and N), and the residuals.

    plot.py fit LAW.json --output LAW.png
"""
import argparse
import json
import os
import re

import matplotlib.pyplot as plt


def main(argv):
    p = argparse.ArgumentParser(prog="plot.py fit")
    p.add_argument("law")
    p.add_argument("--output", required=True)
    a = p.parse_args(argv)
    with open(a.law) as f:
        law = json.load(f)
    K, n = law["law"]["K"], law["law"]["n"]
    d = law["diagnostics"]
    if d is None:
        raise SystemExit(f"{a.law}: no diagnostics (not a fitted law); nothing to plot")
    delta = d["delta"]
    force = d["force"]
    top = max(delta)
    xs = [top * i / 200 for i in range(201)]
    K_mm = law["mm_N"]["K"]

    fig, (ax, ar) = plt.subplots(2, 1, figsize=(7, 7), sharex=True,
                                 gridspec_kw={"height_ratios": [3, 1.3]})
    ax.plot([x * 1e3 for x in delta], force, "o", label="data")
    ax.plot([x * 1e3 for x in xs], [K * x ** n for x in xs], "-",
            label=f"fit F = {K_mm:.6g}·δ^{n:.4f}  (δ in mm, F in N)")
    ax.set_ylabel("contact force F [N]")
    # run_pipeline's law sits in fit/<sweep>/<p>=<v>(.partial)/law.json: name the case
    from plotting.fe import folder_label
    name = folder_label(os.path.dirname(os.path.abspath(a.law)))
    # fit_stage plots its law before putting it in place: LAW.tmp.<pid>.json is LAW.json
    base = re.sub(r"\.tmp\.[0-9]+\.json$", ".json", os.path.basename(a.law))
    if base != "law.json" or "=" not in os.path.basename(os.path.dirname(a.law)):
        name = base
    ax.set_title(f"{name}:  R² = {d['r_squared']:.6f},  "
                 f"n = {n:.4f} ± {d['n_std_error']:.2g}")
    ax.grid(True, alpha=0.3)
    ax.legend()
    ar.axhline(0.0, color="k", lw=0.8)
    ar.plot([x * 1e3 for x in delta], d["residual"], "o-")
    ar.set_xlabel("penetration δ [mm]")
    ar.set_ylabel("residual F − F_fit [N]")
    ar.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    return 0
