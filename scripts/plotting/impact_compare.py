"""The FE impact sweep against the MBD contact laws (impact_compare's outputs).

    scripts/plot.py impact_compare OUT.png DIR

Peak force, δ_max, contact duration and restitution against the impact velocity (one panel row
per quantity, one marker per journal mass), FE and each damping model (c_e of the comparison);
the c_e that reproduces the FE restitution per model, with its error bar from the Δt and mesh
levels where impact_compare had them (restitution_fit.csv); and each model's peak-force error.
"""
import os

import matplotlib.pyplot as plt

from plotting._common import read_table

MODELS = ["none", "lankarani_nikravesh", "hunt_crossley", "flores", "gonthier"]
COLOURS = dict(zip(MODELS, ["C0", "C1", "C2", "C3", "C4"]))  # one colour per model everywhere
MARKERS = "os^vD<>"


def _by_mass(t):
    """{mass: [row indices sorted by v]} (one journal mass: one group)."""
    groups = {}
    for i, m in enumerate(t.get("journal_mass", [0.0] * len(t["v_in"]))):
        key = next((k for k in groups if abs(k - m) <= 1e-9 * max(m, 1e-30)), m)
        groups.setdefault(key, []).append(i)
    for k in groups:
        groups[k].sort(key=lambda i: t["v_in"][i])
    return dict(sorted(groups.items()))


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 1
    out, folder = argv
    _, _, t = read_table(os.path.join(folder, "impact_comparison.csv"))
    _, _, f = read_table(os.path.join(folder, "restitution_fit.csv"))
    groups = _by_mass(t)
    several = len(groups) > 1
    fig, axes = plt.subplots(2, 3, figsize=(15, 8))
    panels = [("peak_force", 1.0, "peak force [N]"), ("delta_max", 1e6, "δ_max [µm]"),
              ("contact_duration", 1e6, "contact duration [µs]"),
              ("restitution", 1.0, "restitution v_out/v_in [1]")]
    for ax, (key, scale, label) in zip(axes.flat, panels):
        for g, (m, idx) in enumerate(groups.items()):
            mk = MARKERS[g % len(MARKERS)]
            v = [t["v_in"][i] for i in idx]
            tag = f", m = {m:.4g} kg" if several else ""
            ax.plot(v, [t["fe_" + key][i] * scale for i in idx], "k-", marker=mk, lw=2,
                    label="FE (HHT-α)" + tag)
            for mod in MODELS:
                if f"{mod}_{key}" in t:
                    ax.plot(v, [t[f"{mod}_{key}"][i] * scale for i in idx], "--", marker=mk,
                            ms=3, color=COLOURS[mod],
                            label=f"MBD law, {mod.replace('_', ' ')}" if g == 0 else None)
        if key in ("peak_force", "delta_max") and several:
            ax.set_yscale("log")
        ax.set_xlabel("impact velocity [m/s]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0][0].legend(fontsize=6)
    ax = axes[1][1]
    for mod in MODELS[1:]:
        key = "c_e_" + mod
        if key not in f:
            continue
        for g, (m, idx) in enumerate(groups.items()):
            pts = [(f["v_in"][i], f[key][i], f.get(key + "_error_bar", [0.0] * len(f[key]))[i])
                   for i in idx if f[key][i] > 0]
            if pts:
                ax.errorbar([p[0] for p in pts], [p[1] for p in pts],
                            yerr=[max(p[2], 0.0) for p in pts], fmt="-",
                            marker=MARKERS[g % len(MARKERS)], color=COLOURS[mod], capsize=3,
                            label=mod.replace("_", " ") if g == 0 else None)
    ax.set_xlabel("impact velocity [m/s]")
    ax.set_ylabel("c_e that returns the FE restitution [1]")
    ax.set_title("fitted restitution coefficient (bars: spread over Δt and mesh levels)",
                 fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    ax = axes[1][2]
    for mod in MODELS:
        key = f"{mod}_peak_force_error"
        if key in t:
            for g, (m, idx) in enumerate(groups.items()):
                ax.plot([t["v_in"][i] for i in idx], [100 * t[key][i] for i in idx], "--",
                        marker=MARKERS[g % len(MARKERS)], ms=3, color=COLOURS[mod],
                        label=mod.replace("_", " ") if g == 0 else None)
    if "given_law_peak_force_error" in t:
        for g, (m, idx) in enumerate(groups.items()):
            ax.plot([t["v_in"][i] for i in idx],
                    [100 * t["given_law_peak_force_error"][i] for i in idx], ":",
                    marker=MARKERS[g % len(MARKERS)], color="grey",
                    label="the given law file, none" if g == 0 else None)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("impact velocity [m/s]")
    ax.set_ylabel("MBD peak force − FE [% of FE]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    return 0
