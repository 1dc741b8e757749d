"""FE impact study plots (fe_stage study impact).

    scripts/plot.py fe_impact OUT.png CASE_DIR
        F(t), δ(t), F(δ) with the quasi-static curve of the same mesh (force_penetration.csv)
        overlaid, and the energy balance (impact_history.csv). δ in µm, t in µs, F in N.
    scripts/plot.py fe_impact OUT.png --sweep impact_sweep.csv
        the quantities that change across the sweep (peak force, impulse, mean force, δ_max,
        contact time, restitution, the dynamic gap at the peak) against the impact velocity,
        one line per journal mass (against the mass when there is one velocity); those that do
        not change are written once in the title. Beside OUT: fig5a.png (the paper's Fig. 5a,
        every case's F(δ) over the quasi-static curve) and fig5b.png (peak force against v
        beside the quasi-static force at the peak's δ, and the gap).
"""
import json
import os

import matplotlib.pyplot as plt

from plotting._common import read_table
from plotting._impact_sweep import (case_folders, constant_value, groups, read_sweep,
                                    split_quantities)


def plot_case(out, folder):
    _, _, h = read_table(os.path.join(folder, "impact_history.csv"))
    _, _, q = read_table(os.path.join(folder, "force_penetration.csv"))
    t_us = [x * 1e6 for x in h["time"]]
    d_um = [x * 1e6 for x in h["delta"]]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    ax = axes[0][0]
    ax.plot(t_us, h["force"], "o-", ms=2)
    ax.set_xlabel("t [µs]")
    ax.set_ylabel("contact force F [N]")
    ax.set_title("F(t)")
    ax = axes[0][1]
    ax.plot(t_us, d_um, "o-", ms=2)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("t [µs]")
    ax.set_ylabel("δ [µm] (journal beyond first touch)")
    ax.set_title("δ(t)")
    ax = axes[1][0]
    ax.plot(d_um, h["force"], "o-", ms=2, label="impact (HHT-α)")
    ax.plot([x * 1e6 for x in q["delta"]], q["force"], "k--", label="quasi-static, same mesh")
    ax.set_xlabel("δ [µm]")
    ax.set_ylabel("F [N]")
    ax.set_title("F(δ): loading and unloading against the quasi-static curve")
    ax.legend(fontsize=8)
    ax = axes[1][1]
    t0 = h["kinetic_journal"][0]
    for key, lab in [("kinetic_journal", "kinetic, journal"), ("kinetic_bearing", "kinetic, bearing"),
                     ("strain_bearing", "strain, bearing"), ("strain_journal", "strain, journal"),
                     ("numerical_dissipation", "HHT numerical dissipation")]:
        ax.plot(t_us, [x / t0 for x in h[key]], label=lab)
    ax.plot(t_us, [-x / t0 for x in h["work_contact"]], label="contact work lost")
    total = [(a + b + c + c2 + d - w) / t0 for a, b, c, c2, d, w in
             zip(h["kinetic_journal"], h["kinetic_bearing"], h["strain_bearing"],
                 h["strain_journal"], h["numerical_dissipation"], h["work_contact"])]
    ax.plot(t_us, total, "k:", label="sum (= 1)")
    ax.set_xlabel("t [µs]")
    ax.set_ylabel("energy / initial kinetic energy [1]")
    ax.set_title("energy balance")
    ax.legend(fontsize=7)
    for a in axes.flat:
        a.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def _mass_label(m):
    return f"m = {m:.4g} kg"


def plot_sweep(out, table):
    """The quantities that change across the sweep against v (one line per journal mass; against
    the mass when v is one), those that do not written once in the title; and beside OUT the
    paper's Fig. 5a and 5b (fig5a.png, fig5b.png in OUT's folder)."""
    s = read_sweep(table)
    varying, constant = split_quantities(s)
    by_mass = groups(s)
    one_v = constant_value(s["v_in_m_per_s"]) is not None
    n = max(1, len(varying))
    cols = min(3, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5 * cols, 3.8 * rows + 0.6), squeeze=False)
    for ax, (key, scale, label, _) in zip(axes.flat, varying):
        if one_v:
            order = sorted(range(len(s[key])), key=lambda i: s["journal_mass_kg"][i])
            ax.plot([s["journal_mass_kg"][i] for i in order], [s[key][i] * scale for i in order],
                    "o-")
            ax.set_xscale("log")
            ax.set_xlabel("journal mass [kg]")
        else:
            for m, idx in by_mass.items():
                ax.plot([s["v_in_m_per_s"][i] for i in idx], [s[key][i] * scale for i in idx],
                        "o-", label=_mass_label(m))
            ax.set_xlabel("impact velocity [m/s]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    for ax in list(axes.flat)[len(varying):]:
        ax.axis("off")
    if varying and not one_v and len(by_mass) > 1:
        axes.flat[0].legend(fontsize=7)
    same = "; ".join(f"{label} {fmt.format(c * scale)}" for (key, scale, label, fmt), c in constant)
    fig.suptitle("FE impact sweep" + (f" — the same in every case: {same}" if same else ""),
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    folder = os.path.dirname(os.path.abspath(out))
    plot_fig5a(os.path.join(folder, "fig5a.png"), table)
    plot_fig5b(os.path.join(folder, "fig5b.png"), s)


def plot_fig5a(out, table):
    """The paper's Fig. 5a: every case's F(δ) through the impact over the quasi-static curve of
    the same mesh (the one reaching furthest), one plot; log–log, as δ spans decades."""
    folders = case_folders(table)
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    reach, curve = -1.0, None
    for k, f in enumerate(folders):
        h_path = os.path.join(f, "impact_history.csv")
        if not os.path.exists(h_path):
            continue
        _, _, h = read_table(h_path)
        pts = [(d * 1e6, F) for d, F in zip(h["delta"], h["force"]) if d > 0 and F > 0]
        man = os.path.join(f, "manifest.json")
        label = os.path.basename(f)
        if os.path.exists(man):
            with open(man) as fh:
                imp = json.load(fh).get("extra", {}).get("impact", {})
            v, m = imp.get("velocity_in", {}).get("value"), imp.get("journal_mass", {}).get("value")
            if v is not None and m is not None:
                label = f"v = {v:.3g} m/s, m = {m:.4g} kg"
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", lw=1.2, color=f"C{k % 10}",
                    label=label)
        q_path = os.path.join(f, "force_penetration.csv")
        if os.path.exists(q_path):
            _, _, q = read_table(q_path)
            if q["delta"] and max(q["delta"]) > reach:
                reach, curve = max(q["delta"]), q
    if curve is not None:
        pts = [(d * 1e6, F) for d, F in zip(curve["delta"], curve["force"]) if d > 0 and F > 0]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "k--", lw=2,
                label="quasi-static, same journal and mesh")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("δ [µm] (journal beyond first touch)")
    ax.set_ylabel("contact force F [N]")
    ax.set_title("Fig. 5a: F(δ) of every impact over the quasi-static curve")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_fig5b(out, s):
    """The paper's Fig. 5b as we read it (its caption is not in our copy: the text says it shows
    how the starting velocity changes the contact force): the peak force against v, one line
    per journal mass, with the quasi-static force at the peak's δ (dashed, same colour); and
    the dynamic gap between them against v."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.8))
    for k, (m, idx) in enumerate(groups(s).items()):
        v = [s["v_in_m_per_s"][i] for i in idx]
        a1.plot(v, [s["peak_force_N"][i] for i in idx], "o-", color=f"C{k}",
                label=_mass_label(m) + ", impact peak")
        a1.plot(v, [s["quasi_static_force_at_peak_delta_N"][i] for i in idx], "s--",
                color=f"C{k}", ms=4, label=_mass_label(m) + ", quasi-static at the peak's δ")
        a2.plot(v, [100 * s["dynamic_gap"][i] for i in idx], "o-", color=f"C{k}",
                label=_mass_label(m))
    a1.set_yscale("log")
    a1.set_xlabel("impact velocity [m/s]")
    a1.set_ylabel("contact force [N]")
    a1.set_title("Fig. 5b: peak force against the impact velocity")
    a2.axhline(0.0, color="k", lw=0.5)
    a2.set_xlabel("impact velocity [m/s]")
    a2.set_ylabel("dynamic gap at the peak [%]")
    a2.set_title("peak / quasi-static at the same δ − 1")
    for a in (a1, a2):
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main(argv):
    if len(argv) == 3 and argv[1] == "--sweep":
        plot_sweep(argv[0], argv[2])
        return 0
    if len(argv) != 2:
        print(__doc__)
        return 1
    plot_case(argv[0], argv[1])
    return 0
