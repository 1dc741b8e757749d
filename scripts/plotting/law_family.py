"""Plot of a law family: each member's data and fit, and F_ref and n against the parameter.

    plot.py law_family FAMILY.json --output FAMILY.png
"""
import argparse
import json
import math

import matplotlib.pyplot as plt


def main(argv):
    p = argparse.ArgumentParser(prog="plot.py law_family")
    p.add_argument("family")
    p.add_argument("--output", required=True)
    a = p.parse_args(argv)
    with open(a.family) as f:
        fam = json.load(f)
    name, unit = fam["parameter"]["name"], fam["parameter"]["unit"]
    scale, shown_unit = (180 / math.pi, "°") if unit == "rad" else (1e3, "mm") if unit == "m" else (1, unit)
    dref = fam["delta_ref"]
    fig, (ax, ab) = plt.subplots(1, 2, figsize=(11, 4.5))
    values, fref, ns, nerr = [], [], [], []
    for m in fam["members"]:
        law = m["law"]
        K, n = law["law"]["K"], law["law"]["n"]
        v = m["value"] * scale
        values.append(v)
        fref.append(K * dref ** n)
        ns.append(n)
        d = law["diagnostics"]
        nerr.append(d["n_std_error"] if d else 0.0)
        top = law["valid_range"]["delta_max"]
        xs = [top * i / 100 for i in range(101)]
        line, = ax.plot([x * 1e3 for x in xs], [K * x ** n for x in xs], "-",
                        label=f"{name} = {v:.4g} {shown_unit}")
        if d:
            ax.plot([x * 1e3 for x in d["delta"]], d["force"], "o", color=line.get_color(), ms=3)
    ax.set_xlabel("penetration δ [mm]")
    ax.set_ylabel("contact force F [N]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ab.plot(values, fref, "o-", color="C0")
    ab.set_xlabel(f"{name} [{shown_unit}]")
    ab.set_ylabel(f"F(δ_ref = {dref * 1e3:.3g} mm) [N]", color="C0")
    ab2 = ab.twinx()
    ab2.errorbar(values, ns, yerr=[1.96 * e for e in nerr], fmt="s--", color="C3", capsize=3)
    ab2.set_ylabel("exponent n (±1.96 s.e.)", color="C3")
    ab.grid(True, alpha=0.3)
    fig.suptitle(f"law family over {name}: {fam['interpolation']}")
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    return 0
