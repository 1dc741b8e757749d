#!/usr/bin/python3
"""The plot helpers of issue 15 item 8: FE legends never show run_pipeline's temporary folder
name, a log axis over one decade carries several readable tick labels, and the report's overlay
of all MBD runs (item 3) gives each run one colour in every panel — also in the journal orbit,
which the ideal joint (no clearance joint) does not have. The rolling plot's slip stages at the
same time share one marker and one label (they printed on top of each other), apart each their own.

    plot_helpers_test.py
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plotting._report_common import readable_log_axis  # noqa: E402
from plotting import _report_mbd  # noqa: E402
from plotting.fe import folder_label  # noqa: E402
from plotting.fe_rolling import stage_markers  # noqa: E402


class FakeRun:
    """What overlay_figures reads of a run: name, data columns, the joint's columns."""

    def __init__(self, name, joint):
        self.name = name
        t = [0.0, 0.005, 0.01, 0.02]
        self.data = {"t": t, "slider_velocity": [0, -1, -2, -2.5], "slider_position": [0.45, 0.44, 0.43, 0.4],
                     "slider_acceleration": [0, 1, 2, 3], "E_total": [2.5, 2.499, 2.498, 2.497]}
        if joint:
            self.data.update({"j_ecc_1": [0, 1e-4, 2e-4, 3e-4], "j_ecc_2": [0, -1e-4, -2e-4, -3e-4]})
        self.joint = {"name": "j"} if joint else None

    def joint_col(self, suffix):
        return self.data.get("j_" + suffix) if self.joint else None


def overlay_colours():
    """{panel title: {run name: colour}} of the figures overlay_figures draws."""
    import matplotlib.colors as mcolors
    figures = []
    real = _report_mbd.figure_html
    _report_mbd.figure_html = lambda fig, caption: figures.append(fig) or ""
    try:
        _report_mbd.overlay_figures([FakeRun("fe_law", True), FakeRun("ideal", False),
                                     FakeRun("johnson", True)])
    finally:
        _report_mbd.figure_html = real
    out = {}
    for fig in figures:
        for ax in fig.axes:
            out[ax.get_title()] = {l.get_label(): mcolors.to_hex(l.get_color()) for l in ax.lines}
        plt.close(fig)
    return out


def check(cond, what):
    if not cond:
        print("FAIL:", what)
        return 1
    return 0


def main():
    bad = 0
    bad += check(folder_label("out/fe/thickness/t_B=0.004.partial") == "t_B = 4 mm",
                 folder_label("out/fe/thickness/t_B=0.004.partial"))
    bad += check(folder_label("out/fe/misalignment/theta=2.5/") == "θ = 2.5°",
                 folder_label("out/fe/misalignment/theta=2.5/"))
    bad += check(folder_label("/x/my_case.partial") == "my_case", folder_label("/x/my_case.partial"))
    # δ from 0.005 to 0.05 mm: one decade. Matplotlib's default labels one tick there.
    fig, ax = plt.subplots()
    ax.loglog([0.005, 0.05], [1600, 20000])
    readable_log_axis(ax.xaxis)
    fig.canvas.draw()
    labels = [t.get_text() for t in ax.get_xticklabels()
              if t.get_text() and 0.005 <= t.get_position()[0] <= 0.05]
    bad += check(len(labels) >= 3, f"x tick labels in the data range: {labels}")
    bad += check(all("10^" not in l and "$" not in l for l in labels), f"plain numbers: {labels}")
    plt.close(fig)

    # slip stages as in fe_stage's manifest (rolling.slip_stages), times in s; the plot in ms
    def stages(end, settled):
        return {"found": True, "end_of_slip": {"value": end, "unit": "s"},
                "settled": {"value": settled, "unit": "s"}}
    same = stage_markers(stages(0.04, 0.04), (0.0, 40.0))
    bad += check(same == [(40.0, "end of gross slip = settled, 40 ms")], f"stages at one time: {same}")
    apart = stage_markers(stages(0.0125, 0.03), (0.0, 40.0))
    bad += check(apart == [(12.5, "end of gross slip, 12.5 ms"), (30.0, "settled, 30 ms")],
                 f"stages apart: {apart}")
    bad += check(stage_markers({"found": False}, (0.0, 40.0)) == [] and stage_markers(None, (0, 1)) == [],
                 "no markers when the stages were not found")

    panels = overlay_colours()
    reference = panels.get("Fig. 14: slider velocity", {})
    bad += check(set(reference) == {"fe_law", "ideal", "johnson"}, f"velocity panel: {reference}")
    for title, colours in panels.items():
        for name, c in colours.items():
            bad += check(reference.get(name) == c,
                         f"panel '{title}': {name} drawn in {c}, in the velocity panel in {reference.get(name)}")
    orbit = panels.get("journal centre in the bearing", {})
    bad += check(set(orbit) == {"fe_law", "johnson"}, f"orbit panel: the runs with a joint: {orbit}")
    print("ok" if not bad else f"{bad} failures")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
