"""FE rolling study plots (fe_stage study rolling; the paper's §3.4, Figs. 10–12).

    scripts/plot.py fe_rolling OUT.png CASE_DIR [ROLLING_JSON]
        ROLLING_JSON: the manifest's "rolling" block as text (fe_stage passes it; without it
        the slip stages are read from CASE_DIR/manifest.json). From CASE_DIR/rolling_history.csv and CASE_DIR/rolling_strain_profile.csv:
        the spin rates φ̇ (bearing) and γ̇ (journal) against time, exact and by the paper's
        Eqs. 7–8 (Fig. 10); the slip speed at the contact with the slip stages; the contact
        forces; the energy balance (drive and push work against stored elastic energy,
        plastic and friction dissipation, the journal's kinetic energy); and the radial and
        tangential strain profiles across the contact zone at the end (Fig. 12).

The principal strains in the bore and the journal at the end (Fig. 11) come from the case's VTU
fields: scripts/plot.py rolling_strains CASE_DIR --output OUT.png (plotting/rolling_strains.py);
the report draws it in its rolling section.
"""
import json
import os

import matplotlib.pyplot as plt

from plotting._common import read_table


# the slip stages of fe_stage's manifest (rolling.slip_stages) marked in the slip-speed panel
SLIP_STAGES = [("end_of_slip", "end of gross slip"), ("settled", "settled")]


def stage_markers(stages, t_span_ms):
    """The slip stages to mark, as [(t [ms], label)] in time order: stages at the same time (within
    1 % of the plotted span t_span_ms [ms]) share one marker whose label names them all, with
    the time, e.g. "end of gross slip = settled, 40 ms"; none when the stages were not found."""
    if not stages or not stages.get("found"):
        return []
    tol = 0.01 * abs(t_span_ms[1] - t_span_ms[0])
    groups = []  # [[t [ms], [labels]]]
    for key, label in SLIP_STAGES:
        value = (stages.get(key) or {}).get("value")
        if value is None:
            continue
        t = value * 1e3
        for g in groups:
            if abs(g[0] - t) <= tol:
                g[1].append(label)
                break
        else:
            groups.append([t, [label]])
    return [(t, f"{' = '.join(labels)}, {t:.3g} ms") for t, labels in sorted(groups)]


def main(argv):
    if len(argv) not in (2, 3):
        print(__doc__)
        return 1
    out, folder = argv[:2]
    _, _, h = read_table(os.path.join(folder, "rolling_history.csv"))
    profile_path = os.path.join(folder, "rolling_strain_profile.csv")
    p = read_table(profile_path)[2] if os.path.exists(profile_path) else None
    # the slip stages, as fe_stage puts them in the manifest's "rolling" block: given as a
    # JSON argument (the plot runs before the manifest is written), or read from a manifest
    # already there (re-plotting a finished run; the block is under "extra")
    stages = None
    if len(argv) == 3:
        stages = json.loads(argv[2]).get("slip_stages")
    else:
        manifest_path = os.path.join(folder, "manifest.json")
        if os.path.exists(manifest_path):
            with open(manifest_path) as f:
                manifest = json.load(f)
            stages = ((manifest.get("extra") or {}).get("rolling") or {}).get("slip_stages")
    t_ms = [x * 1e3 for x in h["time"]]

    fig, axes = plt.subplots(2, 3, figsize=(15, 8))
    ax = axes[0][0]
    ax.plot(t_ms, h["phi_rate"], "C0-", label="φ̇ bearing (driven)")
    ax.plot(t_ms, h["phi_rate_paper"], "C0--", label="φ̇ by Eqs. 4–5, 7")
    ax.plot(t_ms, h["gamma_rate"], "C1-", label="γ̇ journal (torque balance)")
    ax.plot(t_ms, h["gamma_rate_paper"], "C1--", label="γ̇ by Eqs. 6, 7")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("spin rate [rad/s]")
    ax.set_title("spin rates (paper Fig. 10)")
    ax.legend(fontsize=7)

    ax = axes[0][1]
    ax.plot(t_ms, h["slip_speed"], "o-", ms=2)
    ax.axhline(0.0, color="k", lw=0.5)
    t_span = (t_ms[0], t_ms[-1]) if t_ms else (0.0, 1.0)
    markers = stage_markers(stages, t_span)
    if markers:  # room above the curve for the labels' rows
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi + (0.06 + 0.07 * len(markers)) * (hi - lo))
    for i, (t, label) in enumerate(markers):
        ax.axvline(t, color="C3", ls=":", lw=1)
        # in axes fraction upwards, one line lower per marker so that near ones do not overlap;
        # to the left of a line in the right half of the panel, so that it stays inside
        right = t > 0.5 * (t_span[0] + t_span[1])
        ax.text(t, 0.98 - 0.06 * i, f"{label} " if right else f" {label}", fontsize=7,
                va="top", ha="right" if right else "left", color="C3",
                transform=ax.get_xaxis_transform(),
                bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=1))
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("slip speed ω_B r_B − γ̇ r_J [m/s]")
    ax.set_title("relative speed at the contact (slip stages)")

    ax = axes[0][2]
    ax.plot(t_ms, h["force_normal"], label="normal (along +y, on the journal)")
    ax.plot(t_ms, h["force_tangential"], label="tangential (along +x)")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("contact force [N]")
    ax.set_title("contact force, full body")
    ax.legend(fontsize=7)

    ax = axes[1][0]
    for key, lab in [("work_drive", "work of the drive (bearing torque)"),
                     ("work_push", "work of the push (journal axis)"),
                     ("elastic_energy", "stored elastic energy"),
                     ("plastic_dissipation", "plastic dissipation"),
                     ("friction_dissipation", "friction dissipation"),
                     ("kinetic_energy", "journal kinetic energy"),
                     ("energy_balance_error", "balance error"),
                     ("work_frame", "contact work on the bearing, in its frame"),
                     ("frame_balance_error", "the bearing's balance error, in its frame")]:
        if key in h:  # (older outputs lack the frame's columns)
            ax.plot(t_ms, h[key], label=lab, ls=":" if key.endswith("error") else "-")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("energy [J]")
    ax.set_title("energy balance")
    ax.legend(fontsize=7)

    ax = axes[1][1]
    ax.plot(t_ms, h["max_plastic_strain"], label="largest equivalent plastic strain")
    ax.plot(t_ms, h["max_strain"], label="largest principal strain")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("strain [1]")
    ax.set_title("plastic and total strain")
    ax.legend(fontsize=7)

    ax = axes[1][2]
    if p:
        # body 0 the bore (solid), body 1 a deformable journal's surface (dashed); older runs
        # have no body column: all the bore's
        bodies = p.get("body") or [0.0] * len(p["arc"])
        for body, style, where in [(0, "-", "bore"), (1, "--", "journal")]:
            rows = [i for i, b in enumerate(bodies) if int(b) == body]
            if not rows:
                continue
            arc_mm = [p["arc"][i] * 1e3 for i in rows]
            for col, colour, lab in [("strain_radial", "C0", "radial"),
                                     ("strain_tangential", "C1", "tangential"),
                                     ("plastic_strain", "k", "equivalent plastic")]:
                ax.plot(arc_mm, [p[col][i] for i in rows], colour + style,
                        label=f"{where}: {lab}")
        ax.legend(fontsize=7)
    ax.set_xlabel("arc along the surface from the contact point [mm]")
    ax.set_ylabel("strain at the contact surface [1]")
    ax.set_title("strains across the contact, at the end (Fig. 12)")
    for a in axes.flat:
        a.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    return 0
