"""FE impact study plots (fe_stage study impact).

    scripts/plot.py fe_impact OUT.png CASE_DIR
        F(t), δ(t), F(δ) with the quasi-static curve of the same mesh (force_penetration.csv)
        overlaid, and the energy balance (impact_history.csv). δ in µm, t in µs, F in N.
    scripts/plot.py fe_impact OUT.png --sweep impact_sweep.csv
        the sweep table against the impact velocity: peak force, δ_max, contact duration,
        restitution, and the dynamic peak's excess over the quasi-static force at the same δ.
"""
import os

import matplotlib.pyplot as plt

from plotting._common import read_table


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


def plot_sweep(out, table):
    _, _, s = read_table(table)
    v = s["v_in_m_per_s"]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    rows = [(axes[0][0], "peak_force_N", 1.0, "peak force [N]"),
            (axes[0][1], "delta_max_m", 1e6, "δ_max [µm]"),
            (axes[1][0], "contact_duration_s", 1e6, "contact duration [µs]"),
            (axes[1][1], "restitution", 1.0, "restitution v_out/v_in [1]")]
    for ax, key, scale, lab in rows:
        ax.plot(v, [x * scale for x in s[key]], "o-")
        ax.set_xlabel("impact velocity [m/s]")
        ax.set_ylabel(lab)
        ax.grid(True, alpha=0.3)
    ax = axes[0][0]
    ax.plot(v, s["quasi_static_force_at_peak_delta_N"], "k--",
            label="quasi-static force at the same δ")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main(argv):
    if len(argv) == 3 and argv[1] == "--sweep":
        plot_sweep(argv[0], argv[2])
        return 0
    if len(argv) != 2:
        print(__doc__)
        return 1
    plot_case(argv[0], argv[1])
    return 0
