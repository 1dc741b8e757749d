"""FE stage plots: force–penetration curves (linear and log–log, δ in mm, F in N).

    scripts/plot.py fe OUT.png DIR_OR_CSV[=LABEL] [...] [--paper]

Each argument is an fe_stage output folder (its force_penetration.csv) or a CSV file, optionally
with a legend label after '='. --paper adds the paper's t_B = 4 mm law F = 338240·δ^1.0114 (mm, N).
"""
import os
import re

import matplotlib.pyplot as plt

from plotting import _paper
from plotting._common import read_table
from plotting._report_common import readable_log_axis

# run_pipeline runs a stage in "<folder>.partial" and renames it when the stage succeeds; the
# plot is drawn before the rename, so the folder name is read without that suffix.
PARTIAL_SUFFIX = ".partial"


def folder_label(path):
    """'t_B = 4 mm' for run_pipeline's folder 't_B=0.004' (t_B in m), 'θ = 2.5°' for
    'theta=2.5' (θ in degrees, as pipeline.yaml gives it); other names as they are."""
    name = os.path.basename(os.path.normpath(path))
    if name.endswith(PARTIAL_SUFFIX):
        name = name[:-len(PARTIAL_SUFFIX)]
    m = re.fullmatch(r"(t_B|theta)=([-+0-9.eE]+)", name)
    if m:
        v = float(m.group(2))
        return f"t_B = {v * 1e3:.4g} mm" if m.group(1) == "t_B" else f"θ = {v:.5g}°"
    return name


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 1
    out = argv[0]
    paper = "--paper" in argv
    sources = [a for a in argv[1:] if a != "--paper"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    for src in sources:
        # An existing path is taken whole (run_pipeline's folders are named "t_B=0.004");
        # otherwise the text after the last '=' is the legend label.
        path, label = (src, "") if os.path.exists(src) else src.rpartition("=")[::2]
        csv_path = os.path.join(path, "force_penetration.csv") if os.path.isdir(path) else path
        _, _, d = read_table(csv_path)
        delta_mm = [x * 1e3 for x in d["delta"]]
        label = label or folder_label(path)
        ax1.plot(delta_mm, d["force"], "o-", ms=3, label=label)
        pts = [(x, f) for x, f in zip(delta_mm, d["force"]) if x > 0 and f > 0]
        ax2.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, label=label)
    if paper:
        # The paper's law over its own δ range (ten points up to DELTA_MAX), from _paper.py so
        # that this plot and the report draw the same curve.
        deltas = [_paper.DELTA_MAX * i / 10 for i in range(1, 11)]
        xs = [x * 1e3 for x in deltas]
        ys = [_paper.tb4_force(x) for x in deltas]
        paper_label = (f"paper t_B = {_paper.TB4_T_B * 1e3:g} mm: "
                       f"{_paper.TB4_K_MM:g}·δ^{_paper.TB4_N:g}")
        for ax in (ax1, ax2):
            ax.plot(xs, ys, "k--", label=paper_label)
    for ax in (ax1, ax2):
        ax.set_xlabel("δ [mm]")
        ax.set_ylabel("F [N]")
        ax.grid(True, which="both", alpha=0.3)
    readable_log_axis(ax2.xaxis)
    readable_log_axis(ax2.yaxis)
    ax1.legend(fontsize=8)
    ax1.set_title("force–penetration")
    ax2.set_title("log–log")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    return 0
