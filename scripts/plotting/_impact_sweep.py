"""The FE impact sweep's numbers (fe_stage study impact, issue 31 item 3), shared by its plots
(fe_impact.py) and the report's impact section (_report_impact.py): the case folders, the
quantities per case, which of them change across the sweep (the others are stated once, not
plotted), and the paper's two claims (§3.2) set beside ours.

A sweep runs every pair of `sweep.velocity` × `sweep.journal_mass` (either alone is a line);
impact_sweep.csv has one row per case, in the order of the case folders that the sweep's
manifest lists.
"""
import json
import os

from plotting._common import read_table

# (column, scale to the shown unit, label with unit, format) of what a case reports
QUANTITIES = [
    ("peak_force_N", 1.0, "peak force [N]", "{:.4g}"),
    ("impulse_Ns", 1e3, "impulse [mN s]", "{:.4g}"),
    ("mean_force_N", 1.0, "mean force over the contact [N]", "{:.4g}"),
    ("delta_max_m", 1e6, "δ_max [µm]", "{:.4g}"),
    ("contact_duration_s", 1e6, "contact time [µs]", "{:.4g}"),
    ("restitution", 1.0, "restitution v_out/v_in [1]", "{:.4f}"),
    ("dynamic_gap", 100.0, "dynamic gap at the peak [%]", "{:+.2f}"),
]

# relative spread below which a quantity is the same in every case (the linear model's
# round-off is ~1e-10; a physical trend over the sweep is far above 1e-4)
CONSTANT_SPREAD = 1e-4


def case_folders(sweep_csv):
    """The case folders of a sweep, in the table's row order: those its manifest lists; else
    every sub-folder with an impact_history.csv, sorted (a sweep still being written)."""
    top = os.path.dirname(os.path.abspath(sweep_csv))
    man = os.path.join(top, "manifest.json")
    folders = []
    if os.path.exists(man):
        with open(man) as f:
            for o in json.load(f).get("outputs", []):
                p = o.get("path", "")
                if os.path.basename(p) == "manifest.json" and os.path.dirname(p):
                    folders.append(os.path.join(top, os.path.basename(os.path.dirname(p))))
    if not folders:
        folders = sorted(os.path.join(top, d) for d in os.listdir(top)
                         if os.path.exists(os.path.join(top, d, "impact_history.csv")))
    return folders


def read_sweep(sweep_csv):
    """The table as a dict of lists, with the quantities an older table lacks computed where
    they can be (impulse and mean force from the cases' histories), or left out."""
    _, _, s = read_table(sweep_csv)
    n = len(s.get("v_in_m_per_s", []))
    if "impulse_Ns" not in s:
        folders = case_folders(sweep_csv)
        if len(folders) == n and all(os.path.exists(os.path.join(f, "impact_history.csv"))
                                     for f in folders):
            s["impulse_Ns"] = [impulse(os.path.join(f, "impact_history.csv")) for f in folders]
            s["mean_force_N"] = [i / d if d > 0 else 0.0
                                 for i, d in zip(s["impulse_Ns"], s["contact_duration_s"])]
    return s


def impulse(history_csv):
    """[N s] ∫F dt over a case's history (trapezoidal), as fe_stage computes it."""
    _, _, h = read_table(history_csv)
    t, F = h["time"], h["force"]
    return sum(0.5 * (F[i] + F[i + 1]) * (t[i + 1] - t[i]) for i in range(len(t) - 1))


def constant_value(values):
    """The value when every case has it (relative spread below CONSTANT_SPREAD), else None."""
    if not values:
        return None
    lo, hi = min(values), max(values)
    scale = max(abs(lo), abs(hi))
    if scale == 0.0 or (hi - lo) <= CONSTANT_SPREAD * scale:
        return 0.5 * (lo + hi)
    return None


def split_quantities(s):
    """(varying, constant): the QUANTITIES present in the table that change across the sweep,
    and those that do not, each constant with its one value."""
    varying, constant = [], []
    for q in QUANTITIES:
        if q[0] not in s:
            continue
        c = constant_value(s[q[0]])
        if c is None:
            varying.append(q)
        else:
            constant.append((q, c))
    return varying, constant


def groups(s):
    """The cases grouped by journal mass: {mass: [row indices sorted by v]}."""
    by_mass = {}
    for i, m in enumerate(s["journal_mass_kg"]):
        key = next((k for k in by_mass if abs(k - m) <= 1e-9 * m), m)
        by_mass.setdefault(key, []).append(i)
    for k in by_mass:
        by_mass[k].sort(key=lambda i: s["v_in_m_per_s"][i])
    return dict(sorted(by_mass.items()))


def groups_by_velocity(s):
    """{v: [row indices sorted by journal mass]}."""
    by_v = {}
    for i, v in enumerate(s["v_in_m_per_s"]):
        key = next((k for k in by_v if abs(k - v) <= 1e-9 * v), v)
        by_v.setdefault(key, []).append(i)
    for k in by_v:
        by_v[k].sort(key=lambda i: s["journal_mass_kg"][i])
    return dict(sorted(by_v.items()))


def _trend(first, last):
    """'grows', 'falls' or 'stays' from first to last (0.5 percentage points of the gap, or
    1 % of its size, count as no change: the T_c/steps sampling of the peak)."""
    if abs(last - first) <= max(0.005, 0.01 * max(abs(first), abs(last))):
        return "stays"
    return "grows" if last > first else "falls"


def paper_claims(s):
    """The paper's two claims on the dynamic gap (§3.2) beside ours, as rows
    (claim, our numbers, finding, agrees: True/False/None where the sweep cannot tell)."""
    gap = s["dynamic_gap"]
    rows = []
    # "This discrepancy increases with the mass of the journal"
    pairs = []
    for v, idx in groups_by_velocity(s).items():
        if len(idx) >= 2:
            a, b = idx[0], idx[-1]
            pairs.append((v, s["journal_mass_kg"][a], gap[a], s["journal_mass_kg"][b], gap[b]))
    claim = "the gap to the quasi-static force grows with the journal's mass"
    if pairs:
        trends = {_trend(p[2], p[4]) for p in pairs}
        numbers = "; ".join(f"v = {v:.3g} m/s: {100 * g1:+.2f} % at {m1:.4g} kg → "
                            f"{100 * g2:+.2f} % at {m2:.4g} kg" for v, m1, g1, m2, g2 in pairs)
        finding = ("it " + "/".join(sorted(trends)) + " with the mass")
        rows.append((claim, numbers, finding, trends == {"grows"}))
    else:
        rows.append((claim, "one journal mass only", "not tested by this sweep "
                     "(sweep.journal_mass)", None))
    # "this difference tends to zero when the initial velocity of the journal decreases"
    pairs = []
    for m, idx in groups(s).items():
        if len(idx) >= 2:
            a, b = idx[0], idx[-1]
            pairs.append((m, s["v_in_m_per_s"][a], gap[a], s["v_in_m_per_s"][b], gap[b]))
    claim = "the gap → 0 as v → 0"
    if pairs:
        shrinks = [abs(g1) < 0.5 * abs(g2) for _, _, g1, _, g2 in pairs]
        numbers = "; ".join(f"m = {m:.4g} kg: {100 * g1:+.2f} % at {v1:.3g} m/s, "
                            f"{100 * g2:+.2f} % at {v2:.3g} m/s" for m, v1, g1, v2, g2 in pairs)
        # from the lowest v to the highest: 'stays' (a linear response: the rigid journal's
        # line contact), 'grows' (the gap falls a little as v falls: the deformable journal's
        # contact patch stiffens with δ), 'falls'
        trends = {_trend(g1, g2) for _, _, g1, _, g2 in pairs}
        if all(shrinks):
            finding = "it shrinks as v falls"
        elif trends == {"stays"}:
            finding = ("it does not shrink as v falls: at a given mass the linear-elastic "
                       "response scales with v, and the gap is the bearing ring's inertia against "
                       "the contact time, which is set by the mass")
        elif trends == {"grows"}:
            finding = ("it does not shrink to 0 as v falls: it falls only a little (" +
                       "; ".join(f"{100 * (g2 - g1):.2g} points over {v2 / v1:.3g}× in v"
                                 for _, v1, g1, v2, g2 in pairs) +
                       "); the gap is mostly the bearing ring's inertia against the contact "
                       "time, which the mass sets, and the little that changes with v is the "
                       "contact stiffening with δ (a contact patch that grows)")
        else:
            finding = ("it does not shrink as v falls: it " + "/".join(
                "falls" if t == "grows" else "grows" if t == "falls" else "stays"
                for t in sorted(trends)) + " as v falls")
        rows.append((claim, numbers, finding, all(shrinks)))
    else:
        rows.append((claim, "one velocity only", "not tested by this sweep (sweep.velocity)",
                     None))
    return rows
