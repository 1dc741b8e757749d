#!/usr/bin/python3
"""The plot helpers of issue 15 item 8: FE legends never show run_pipeline's temporary folder
name, and a log axis over one decade carries several readable tick labels.

    plot_helpers_test.py
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plotting._report_common import readable_log_axis  # noqa: E402
from plotting.fe import folder_label  # noqa: E402


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
    print("ok" if not bad else f"{bad} failures")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
