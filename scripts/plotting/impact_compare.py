"""The FE impact sweep against the MBD contact laws (impact_compare's outputs).

    scripts/plot.py impact_compare OUT.png DIR

Peak force, δ_max, contact duration and restitution against the impact velocity, FE and each
damping model (c_e of the comparison); and the c_e that reproduces the FE restitution, per model
against v (restitution_fit.csv).
"""
import os

import matplotlib.pyplot as plt

from plotting._common import read_table

MODELS = ["none", "lankarani_nikravesh", "hunt_crossley", "flores", "gonthier"]
COLOURS = dict(zip(MODELS, ["C0", "C1", "C2", "C3", "C4"]))  # one colour per model everywhere


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 1
    out, folder = argv
    _, _, t = read_table(os.path.join(folder, "impact_comparison.csv"))
    _, _, f = read_table(os.path.join(folder, "restitution_fit.csv"))
    v = t["v_in"]
    fig, axes = plt.subplots(2, 3, figsize=(15, 8))
    panels = [("peak_force", 1.0, "peak force [N]"), ("delta_max", 1e6, "δ_max [µm]"),
              ("contact_duration", 1e6, "contact duration [µs]"),
              ("restitution", 1.0, "restitution v_out/v_in [1]")]
    for ax, (key, scale, label) in zip(axes.flat, panels):
        ax.plot(v, [x * scale for x in t["fe_" + key]], "ko-", lw=2, label="FE (HHT-α)")
        for m in MODELS:
            if f"{m}_{key}" in t:
                ax.plot(v, [x * scale for x in t[f"{m}_{key}"]], "o--", ms=3, color=COLOURS[m],
                        label=f"MBD law, {m.replace('_', ' ')}")
        ax.set_xlabel("impact velocity [m/s]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0][0].legend(fontsize=7)
    ax = axes[1][1]
    for m in MODELS[1:]:
        key = "c_e_" + m
        if key in f:
            pts = [(a, b) for a, b in zip(v, f[key]) if b > 0]
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=COLOURS[m],
                        label=m.replace("_", " "))
    ax.set_xlabel("impact velocity [m/s]")
    ax.set_ylabel("c_e that returns the FE restitution [1]")
    ax.set_title("fitted restitution coefficient")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    ax = axes[1][2]
    for m in MODELS:
        key = f"{m}_peak_force_error"
        if key in t:
            ax.plot(v, [100 * x for x in t[key]], "o--", ms=3, color=COLOURS[m],
                    label=m.replace("_", " "))
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("impact velocity [m/s]")
    ax.set_ylabel("MBD peak force − FE [% of FE]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    return 0
