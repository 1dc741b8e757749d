#!/usr/bin/python3
"""Each mesh's error of F(delta_max) in one or more adaptive sequences (fe_stage's
adaptive_cycles.csv), against the sequence's extrapolated value — the preset figures of an FE
sweep whose presets are the first meshes of one adaptive sequence (pipeline.yaml fe_sweeps
misalignment presets: fast = mesh 2, standard = mesh 3, accurate = mesh 4; issue 31 item 5).

    bench/adaptive_reference.py RUN_DIR [RUN_DIR ...] [--presets fast=2 standard=3 accurate=4]

The reference is the tail beyond the last mesh as fe_stage estimates it (docs/fe.md "The error
estimate"): F_inf = F_k - (F_{k-2} - F_k) / ((N_k/N_{k-2})^q - 1), with q the Richardson rate
through the last three meshes, and also with q bounded by 2/3 (Q2 in 3D, the energy norm's
rate on optimal meshes): the two give an interval, and each mesh's error is stated against
both ends (the larger is the figure to quote). A sequence whose last two changes differ in sign
gives no extrapolation: then the last mesh is the reference, its own error taken as its last
change, and each mesh's error is given from |F_k - F_last| (a lower bound) to that plus the
last change.
"""
import argparse
import csv
import math
import os


def read_sequence(run_dir):
    with open(os.path.join(run_dir, "adaptive_cycles.csv")) as f:
        rows = [r for r in csv.reader(l for l in f if not l.startswith("#"))]
    head, rows = rows[0], rows[1:]
    N = [float(r[head.index("n_dofs")]) for r in rows]
    F = [float(r[head.index("force_at_delta_max")]) for r in rows]
    t = [float(r[head.index("wall_time")]) for r in rows]
    return N, F, t


def three_mesh_rate(N, F, i, j, k):
    """q of F = F_inf + C N^-q through meshes i, j, k (by bisection in [1e-3, 10])."""
    d1, d2 = F[j] - F[i], F[k] - F[j]
    def g(q):
        return (N[i] ** -q - N[j] ** -q) / (N[j] ** -q - N[k] ** -q) - d1 / d2
    lo, hi = 1e-3, 10.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if (g(lo) > 0) == (g(mid) > 0):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def references(N, F, q_bound=2.0 / 3.0):
    """(F_inf with the fitted rate, F_inf with the rate bounded, q fitted) or None."""
    if len(F) < 3:
        return None
    d1, d2 = F[-2] - F[-3], F[-1] - F[-2]
    if d1 == 0 or d2 == 0 or (d1 > 0) != (d2 > 0) or abs(d2) >= abs(d1):
        return None
    # F_k = F_inf + C N^-q through the last three meshes
    q = three_mesh_rate(N, F, -3, -2, -1)
    def tail(qq):
        return (F[-3] - F[-1]) / ((N[-1] / N[-3]) ** qq - 1.0)
    return F[-1] - tail(q), F[-1] - tail(min(q, q_bound)), q


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--presets", nargs="*", default=["fast=2", "standard=3", "accurate=4"])
    a = ap.parse_args()
    presets = [(p.split("=")[0], int(p.split("=")[1])) for p in a.presets]
    for run in a.runs:
        N, F, t = read_sequence(run)
        ref = references(N, F)
        print(f"{run}: F = {', '.join(f'{x:.2f}' for x in F)} N on "
              f"{', '.join(f'{n / 1e3:.1f}k' for n in N)} DoFs")
        if ref is None:
            # No extrapolation: the last mesh is the reference and its own error is taken as its
            # last change (what fe_stage reports, not extrapolated); each mesh's error is stated
            # against the last mesh alone (a lower bound) and with that change added.
            own = abs(F[-1] - F[-2]) / abs(F[-1])
            print(f"  no extrapolation (the last changes turn or grow): against the last mesh, "
                  f"whose own error is taken as its last change, {100 * own:.3g} %")
            for name, k in presets:
                if k < len(F):
                    e = 100 * abs(F[k] - F[-1]) / abs(F[-1])
                    print(f"  {name} (mesh {k}, {N[k] / 1e3:.1f}k DoFs): {F[k]:.2f} N, error "
                          f"{e:.3g} … {e + 100 * own:.3g} %")
            continue
        else:
            print(f"  F_inf = {ref[0]:.2f} N (fitted q = {ref[2]:.3g}) … {ref[1]:.2f} N (q <= 2/3)")
            refs = ref[:2]
        for name, k in presets:
            if k < len(F):
                e = [100 * abs(F[k] - r) / abs(r) for r in refs]
                print(f"  {name} (mesh {k}, {N[k] / 1e3:.1f}k DoFs): {F[k]:.2f} N, error "
                      f"{min(e):.3g} … {max(e):.3g} %")


if __name__ == "__main__":
    main()
