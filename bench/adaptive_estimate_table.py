#!/usr/bin/python3
"""fe_stage's own estimate of the error of F(delta_max) on an adaptive sequence's last mesh,
before and after issue 32 item 3's second change, against the references of every recorded
sequence (tests/data/fe/adaptive_sequences.txt, each block naming its docs section). Not a test:
the test is AdaptiveEstimate.BracketsTheReferenceOnTheMeasuredSequences in fe_logic_test, which
prints the "after" column from the C++ code itself (this script's copy of it agrees to the
printed digits).

    bench/adaptive_estimate_table.py [--data tests/data/fe/adaptive_sequences.txt] [--references]

For every prefix of 2 ... `checked` meshes of each sequence: the error against the reference
interval (the near end, or 0 inside it, to the far end), the estimate before (the rate fitted
by least squares over the last up to four changes, bounded by p/d = 2/3, main at 82b8d4b) and
after (the rate p/d whatever the fit), each with the ratio estimate / far-end error, and a
summary (median and extremes of the ratios). `--references` prints the extrapolations the
intervals are built from: fe_stage's estimate before this change over the whole sequence,
the three-mesh Richardson value through the last three meshes (bench/adaptive_reference.py)
and through every other mesh (0-2-4, 1-3-5).
"""
import argparse
import math
import os
import statistics

from adaptive_reference import three_mesh_rate  # (bench/ is this script's own folder)
from adaptive_sequences import read_sequences

P_OVER_D = 2.0 / 3.0  # Q2 elements in 3D: fe_stage's default
FIT_CHANGES = 4  # adaptive_fit_changes


def fitted_rate(N, F, first, k):
    """q of log|F_{j-1} - F_j| = log C + log(N_{j-1}^-q - N_j^-q) by least squares over the
    changes of meshes first..k, as fe_stage fits it (scan, then golden sections); None where
    the best scan point is the lowest (no positive rate)."""
    def misfit(q):
        g = [math.log(abs(F[j - 1] - F[j])) + q * math.log(N[j - 1])
             - math.log1p(-(N[j - 1] / N[j]) ** q) for j in range(first + 1, k + 1)]
        m = sum(g) / len(g)
        return sum((v - m) ** 2 for v in g)
    lo, hi, n = 1e-3, 20.0, 400
    point = lambda i: lo * (hi / lo) ** (i / n)
    best = min(range(n + 1), key=lambda i: (misfit(point(i)), i))
    if best == 0:
        return None
    a, b = point(max(best - 1, 0)), point(min(best + 1, n))
    g = 0.5 * (math.sqrt(5.0) - 1.0)
    for _ in range(200):
        if b - a <= 1e-12:
            break
        c, d = b - g * (b - a), a + g * (b - a)
        if misfit(c) < misfit(d):
            b = d
        else:
            a = c
    return 0.5 * (a + b)


def estimate(N, F, after):
    """(relative error, 'extrapolated' | 'last change', rate fitted or None). 'last change': the
    change in the last cycle, not extrapolated and no bound either way (fe_stage's method
    "change in the last cycle (not extrapolated; not a bound)")."""
    k = len(F) - 1
    last = (abs(F[k] - F[k - 1]) / abs(F[k]), "last change", None)
    if len(F) < 3:
        return last
    first = k - min(k, FIT_CHANGES)
    for j in range(first + 1, k + 1):
        if not N[j] > N[j - 1] or not (F[j - 1] - F[j]) * (F[k - 1] - F[k]) > 0:
            return last
    q_fit = fitted_rate(N, F, first, k)
    if q_fit is None:
        return last
    q = P_OVER_D if after else min(q_fit, P_OVER_D)
    tail = (F[k - 2] - F[k]) / ((N[k] / N[k - 2]) ** q - 1.0)
    return abs(tail) / abs(F[k] - tail), "extrapolated", q_fit


def richardson3(N, F, i, j, k):
    """F_inf and q through meshes i, j, k (q: bench/adaptive_reference.py's three_mesh_rate)."""
    q = three_mesh_rate(N, F, i, j, k)
    return F[k] - (F[i] - F[k]) / ((N[k] / N[i]) ** q - 1.0), q


def references(seqs):
    for s in seqs:
        N, F = s["N"], s["F"]
        e, how, _ = estimate(N, F, after=False)
        line = f"{s['name']}: "
        if how == "extrapolated":
            line += f"estimate before, all meshes {F[-1] / (1 + e if F[-1] < F[-2] else 1 - e):.1f} N"
        else:
            line += "estimate before: the last change (not extrapolated)"
        line += "; last three {:.1f} N (q = {:.3g})".format(*richardson3(N, F, len(F) - 3, len(F) - 2, len(F) - 1))
        for i in (0, 1):
            if i + 4 < len(F):
                line += "; {}-{}-{} {:.1f} N (q = {:.3g})".format(i, i + 2, i + 4, *richardson3(N, F, i, i + 2, i + 4))
        print(line + f"; the data file's interval {s['reference'][0]:.1f}-{s['reference'][1]:.1f} N")


def table(seqs):
    print("| sequence | meshes | DoFs | error against the reference | before | after | before / error | after / error |")
    print("|---|---|---|---|---|---|---|---|")
    ratios = {"before": [], "after": []}
    for s in seqs:
        lo, hi = s["reference"]
        # a sequence the test does not check (its reference is doubtful) is listed, every
        # prefix, but left out of the summary
        checked = s["checked"] > 0
        for m in range(2, (s["checked"] if checked else len(s["F"])) + 1):
            N, F = s["N"][:m], s["F"][:m]
            near = 0.0 if lo <= F[-1] <= hi else min(abs(F[-1] - lo) / lo, abs(F[-1] - hi) / hi)
            far = max(abs(F[-1] - lo) / lo, abs(F[-1] - hi) / hi)
            cells, r = [], []
            for which in ("before", "after"):
                e, how, q_fit = estimate(N, F, after=(which == "after"))
                r.append(e / far)
                if checked:
                    ratios[which].append((e / far, how, m))
                mark = "≈ " if how == "last change" else ""
                cells.append(f"{mark}{100 * e:.2f} %" + (f" (q fitted {q_fit:.2f})" if q_fit is not None and which == "before" else ""))
            print(f"| {s['name']}{'' if checked else ' (not checked)'} | {m} | {N[-1]:,.0f} "
                  f"| {100 * near:.2f}–{100 * far:.2f} % | {cells[0]} | {cells[1]} | {r[0]:.2f} | {r[1]:.2f} |")
    print()
    for which, rs in ratios.items():
        x = sorted(r for r, how, m in rs if how == "extrapolated")
        lc = sorted(r for r, how, m in rs if how == "last change")
        print(f"{which}: extrapolated {len(x)}: estimate / far-end error median {statistics.median(x):.2f}, "
              f"lowest {x[0]:.2f}, highest {x[-1]:.2f}; last change (not extrapolated, no bound) {len(lc)}: "
              f"median {statistics.median(lc):.2f}, lowest {lc[0]:.2f}, highest {lc[-1]:.2f}, "
              f"above the far-end error on {sum(r > 1 for r in lc)}, below on {sum(r < 1 for r in lc)}")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", default=os.path.join(here, "..", "tests", "data", "fe", "adaptive_sequences.txt"))
    ap.add_argument("--references", action="store_true")
    a = ap.parse_args()
    seqs = list(read_sequences(a.data).values())  # in the file's order
    if a.references:
        references(seqs)
    else:
        table(seqs)


if __name__ == "__main__":
    main()
