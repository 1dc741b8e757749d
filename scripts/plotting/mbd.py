"""Plots of an mbd_stage run (SPEC §4 outputs), and a comparison of several runs.

    plot.py mbd DIR                          -> DIR/plots/*.png
    plot.py mbd --compare OUT.png DIR1 DIR2 ...   -> one figure overlaying the runs (Figs. 14–16)
    plot.py mbd --bench BENCH_DIR            -> BENCH_DIR/mbd_tolerance.png from mbd_benchmark

DIR holds timeseries.csv and summary.json written by mbd_stage.
"""
import json
import os
import sys

import matplotlib.pyplot as plt

from plotting._common import read_table
from plotting._report_common import readable_log_axis


def _load(d):
    cols, units, data = read_table(os.path.join(d, "timeseries.csv"))
    with open(os.path.join(d, "summary.json")) as f:
        summary = json.load(f)
    return cols, units, data, summary


def _clearance_prefixes(summary):
    return [c["name"] + "_" for c in summary.get("clearance_joints", [])]


def _save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_run(d):
    cols, units, data, summary = _load(d)
    out = os.path.join(d, "plots")
    os.makedirs(out, exist_ok=True)
    t = data["t"]
    name = summary.get("scene", os.path.basename(d))
    if "slider_velocity" in data:
        fig, ax = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
        ax[0].plot(t, data["slider_velocity"], lw=0.8)
        ax[0].set_ylabel("slider velocity [m/s]")
        ax[1].plot(t, data["slider_acceleration"], lw=0.6)
        ax[1].set_ylabel("slider acceleration [m/s²]")
        ax[1].set_xlabel("t [s]")
        ax[0].set_title(name)
        _save(fig, os.path.join(out, "slider_motion.png"))
        fig, ax = plt.subplots(figsize=(6, 5))
        ax.plot(data["slider_position"], data["slider_velocity"], lw=0.6)
        ax.set_xlabel("slider position [m]")
        ax.set_ylabel("slider velocity [m/s]")
        ax.set_title("phase portrait — " + name)
        _save(fig, os.path.join(out, "phase_portrait.png"))
    for cj, pre in zip(summary.get("clearance_joints", []), _clearance_prefixes(summary)):
        c_r = cj["geometry"]["c_r"]
        fig, ax = plt.subplots(figsize=(5.5, 5.5))
        import math
        th = [2 * math.pi * i / 360 for i in range(361)]
        ax.plot([1e3 * c_r * math.cos(a) for a in th], [1e3 * c_r * math.sin(a) for a in th], "k--", lw=0.8,
                label="clearance circle c_r")
        ax.plot([1e3 * x for x in data[pre + "ecc_1"]], [1e3 * y for y in data[pre + "ecc_2"]], lw=0.6,
                label="journal centre")
        ax.set_aspect("equal")
        ax.set_xlabel("eccentricity along h1 [mm]")
        ax.set_ylabel("eccentricity along h2 [mm]")
        ax.set_title("journal orbit — " + cj["name"])
        ax.legend(loc="upper right", fontsize=8)
        _save(fig, os.path.join(out, cj["name"] + "_orbit.png"))
        fig, ax = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
        ax[0].plot(t, [1e6 * v for v in data[pre + "radial_delta"]], lw=0.6)
        ax[0].axhline(0.0, color="k", lw=0.5)
        ax[0].set_ylabel("δ radial [µm]")
        ax[0].set_ylim(bottom=-0.1 * 1e6 * c_r)
        ax[1].plot(t, data[pre + "radial_F_n"], lw=0.6, label="F_n")
        ax[1].plot(t, data[pre + "radial_F_t"], lw=0.6, label="F_t (friction)")
        ax[1].set_ylabel("force [N]")
        ax[1].legend(fontsize=8)
        ax[2].plot(t, data[pre + "axial_pos_F_n"], lw=0.6, label="axial +")
        ax[2].plot(t, data[pre + "axial_neg_F_n"], lw=0.6, label="axial −")
        ax[2].set_ylabel("axial force [N]")
        ax[2].set_xlabel("t [s]")
        ax[2].legend(fontsize=8)
        ax[0].set_title("contact — " + cj["name"])
        _save(fig, os.path.join(out, cj["name"] + "_contact.png"))
    fig, ax = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for c in ("E_kin", "E_pot", "E_el", "E_total", "W_friction", "W_damping", "W_drivers"):
        if any(abs(v) > 0 for v in data[c]):
            ax[0].plot(t, data[c], lw=0.8, label=c)
    ax[0].set_ylabel("energy, work [J]")
    ax[0].legend(fontsize=8, ncol=2)
    ax[0].set_title("energy — " + name)
    ax[1].plot(t, data["energy_error"], lw=0.8)
    ax[1].set_ylabel("E − W − E(0) [J]")
    ax[1].set_xlabel("t [s]")
    _save(fig, os.path.join(out, "energy.png"))
    reac = [c[:-3] for c in cols if c.endswith("_Fx")]
    if reac:
        fig, ax = plt.subplots(len(reac), 1, figsize=(8, 3 * len(reac)), sharex=True, squeeze=False)
        for i, j in enumerate(reac):
            for a in ("Fx", "Fy", "Fz"):
                ax[i][0].plot(t, data[j + "_" + a], lw=0.6, label=a)
            ax[i][0].set_ylabel(j + " [N]")
            ax[i][0].legend(fontsize=8)
        ax[-1][0].set_xlabel("t [s]")
        ax[0][0].set_title("ground joint reactions (force on the moving body)")
        _save(fig, os.path.join(out, "ground_reactions.png"))
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.semilogy(t, [max(v, 1e-18) for v in data["phi_max"]], lw=0.8, label="max |Φ|")
    ax.semilogy(t, [max(v, 1e-18) for v in data["euler_norm_error"]], lw=0.8, label="max |‖e‖ − 1|")
    ax.set_xlabel("t [s]")
    ax.legend(fontsize=8)
    ax.set_title("constraint drift — " + name)
    _save(fig, os.path.join(out, "constraint_drift.png"))
    return 0


def compare(out_png, dirs):
    fig, ax = plt.subplots(2, 2, figsize=(13, 9))
    for d in dirs:
        cols, units, data, summary = _load(d)
        label = summary.get("scene", os.path.basename(d)).replace("slider_crank_", "")
        t = data["t"]
        ax[0][0].plot(t, data["slider_velocity"], lw=0.8, label=label)
        ax[0][1].plot(t, data["slider_acceleration"], lw=0.6, label=label)
        ax[1][0].plot(data["slider_position"], data["slider_velocity"], lw=0.6, label=label)
        pres = _clearance_prefixes(summary)
        if pres:
            ax[1][1].plot([1e3 * x for x in data[pres[0] + "ecc_1"]],
                          [1e3 * y for y in data[pres[0] + "ecc_2"]], lw=0.6, label=label)
    ax[0][0].set_xlabel("t [s]")
    ax[0][0].set_ylabel("slider velocity [m/s]")
    ax[0][1].set_xlabel("t [s]")
    ax[0][1].set_ylabel("slider acceleration [m/s²]")
    ax[1][0].set_xlabel("slider position [m]")
    ax[1][0].set_ylabel("slider velocity [m/s]")
    ax[1][1].set_xlabel("eccentricity h1 [mm]")
    ax[1][1].set_ylabel("eccentricity h2 [mm]")
    ax[1][1].set_aspect("equal", adjustable="datalim")
    for a in ax.flat:
        a.legend(fontsize=7)
    fig.suptitle("contact-force models compared (paper's slider–crank, §4)")
    os.makedirs(os.path.dirname(os.path.abspath(out_png)), exist_ok=True)
    _save(fig, out_png)
    return 0


def bench(d):
    cols, units, data = read_table(os.path.join(d, "mbd_tolerance.csv"))
    names = {0: "DP5", 1: "Verner 6(5)", 2: "Fehlberg 8(7)", 3: "CVODE BDF"}
    scenes = {0: "FE law with damping", 1: "energy check"}
    fig, ax = plt.subplots(2, 2, figsize=(12, 8.5))
    for row, sname in scenes.items():
        for m, label in names.items():
            idx = [i for i, v in enumerate(data["method"])
                   if int(v) == m and int(data["scene"][i]) == row]
            if not idx:
                continue
            w = [data["wall_time"][i] for i in idx]
            e1 = [max(data["first_peak_rel_error"][i], 1e-10) for i in idx]
            e2 = [max(data["v_error_20ms"][i], 1e-9) for i in idx]
            ax[row][0].loglog(w, e1, "o-", label=label)
            ax[row][1].loglog(w, e2, "o-", label=label)
            for i, x, y in zip(idx, w, e2):
                ax[row][1].annotate("%.0e" % data["rtol"][i], (x, y), fontsize=6)
        ax[row][1].axhline(1e-4, color="k", lw=0.6, ls="--")
        ax[row][1].axvline(0.2, color="k", lw=0.6, ls=":")
        ax[row][0].set_ylabel("first-impact peak force, rel. error (%s)" % sname, fontsize=8)
        ax[row][1].set_ylabel("slider velocity error, t ≤ 0.02 s [m/s] (%s)" % sname, fontsize=8)
    for a in ax.flat:
        a.set_xlabel("wall time [s] (0.1 s scene, in-process)")
        a.legend(fontsize=7)
        a.grid(True, which="both", lw=0.3)
        readable_log_axis(a.xaxis)
    fig.suptitle("MBD: wall time against error, reference DP5 rtol 1e-12 (dashed: 1e-4 m/s target)")
    _save(fig, os.path.join(d, "mbd_tolerance.png"))
    return 0


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv else 1
    if argv[0] == "--bench":
        return bench(argv[1])
    if argv[0] == "--compare":
        if len(argv) < 3:
            print("mbd --compare OUT.png DIR1 [DIR2 ...]", file=sys.stderr)
            return 1
        return compare(argv[1], argv[2:])
    return plot_run(argv[0])
