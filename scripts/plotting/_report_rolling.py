"""The report's rolling section (issue 13, paper §3.4): the FE rolling study — the bearing turning
at ω_B, the journal (rigid, or deformable with loading.journal core) pushed radially and spun by
friction alone, an elastoplastic bearing (and journal).
The spin rates exact and by the paper's Eqs. 7–8 (the paper's Fig. 10), the energy split (work
in against stored, dissipated and kinetic energy, and the balance error as a % of the work in),
the bore's strains across the contact at the end (Fig. 12), the slip stages of the manifest and
the final numbers with units; warnings when the run is incomplete, when the energy balance does
not close to 5 % of the work in, and when the strain is too large for the small-strain model.

Every column is read by its name (fe_stage/rolling_output.cc; columns fe_stage adds later are
listed, not lost). The section survives a run without a rolling study (no section) and a rolling
task that failed (its message, and whatever the stage wrote before it stopped, from
<fe/rolling>.partial/).
"""
import math
import os

import matplotlib.pyplot as plt

from plotting._common import read_table
from plotting._report_common import (details, esc, figure_html, get, image_file_html,
                                     load_or_none, rel_link, value_of)

# |energy_balance_error| above this fraction of the work in: the balance does not close.
BALANCE_LIMIT = 0.05
# Largest principal strain above this: the small-strain (infinitesimal) model is not accurate.
STRAIN_LIMIT = 0.05

# The energy columns of rolling_history.csv [J]: (column, label, side of the balance).
ENERGY_COLUMNS = [
    ("work_drive", "work of the drive turning the bearing", "in"),
    ("work_push", "work of the push (the journal's axis)", "in"),
    ("work_drive_torque", "work of the drive's torque, ∫ torque_drive dφ", "check"),
    ("elastic_energy", "stored elastic energy", "out"),
    ("plastic_dissipation", "plastic dissipation", "out"),
    ("friction_dissipation", "friction dissipation", "out"),
    ("kinetic_energy", "kinetic energy of the journal's spin", "out"),
]


def _column(h, name):
    """The column as a list, or None when this run's CSV does not have it."""
    values = h.get(name)
    return values if values else None


def _last(h, name):
    values = _column(h, name)
    return values[-1] if values else None


def _csv_status(path):
    """The '# status: ...' line fe_stage's CsvWriter ends a file with (None if absent)."""
    status = None
    try:
        with open(path) as f:
            for line in f:
                if line.startswith("# status:"):
                    status = line[len("# status:"):].strip()
    except OSError:
        return None
    return status


def _fmt(value, fmt="{:.4g}", unit=""):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "not reported"
    return fmt.format(value) + (f" {unit}" if unit else "")


def _failure_line(message):
    """A failed task's message in one line: run_pipeline's first line (which task, exit status)
    and the last line of the stage's log (what went wrong), when they differ."""
    lines = [l.strip() for l in (message or "").splitlines() if l.strip()]
    if not lines:
        return "(no message)"
    return lines[0] if len(lines) == 1 else f"{lines[0]} … {lines[-1]}"


def _folder(rolling):
    """The folder holding this run's rolling outputs: the task's folder, or for a failed task
    the partial output it left (an older complete folder would not be this run's)."""
    if rolling.get("status") == "failed":
        candidates = [rolling.get("partial_dir")]
    else:
        candidates = [rolling.get("fe_dir")]
    for c in candidates:
        if c and os.path.isdir(c):
            return c
    return None


class RollingRun:
    """What the report reads of one rolling run: history, strain profile, manifest."""

    def __init__(self, rolling):
        self.rolling = rolling
        self.folder = _folder(rolling)
        self.history = self.units = self.profile = None
        self.history_status = self.profile_status = None
        self.manifest = None
        if not self.folder:
            return
        self.manifest = load_or_none(os.path.join(self.folder, "manifest.json"))
        path = os.path.join(self.folder, "rolling_history.csv")
        if os.path.exists(path):
            try:
                _, self.units, self.history = read_table(path)
            except (OSError, ValueError):
                self.history = None
            self.history_status = _csv_status(path)
        path = os.path.join(self.folder, "rolling_strain_profile.csv")
        if os.path.exists(path):
            try:
                self.profile = read_table(path)[2]
            except (OSError, ValueError):
                self.profile = None
            self.profile_status = _csv_status(path)

    @property
    def summary(self):
        return get(self.manifest, "extra", "rolling", default={}) or {}

    @property
    def scene(self):
        return get(self.manifest, "extra", "scene", default={}) or {}

    def has_steps(self):
        return bool(self.history) and len(self.history.get("time", [])) > 1

    def work_in(self):
        """|work_drive| + |work_push| at the end [J] (the manifest's measure of the balance)."""
        w = [abs(v) for v in (_last(self.history, "work_drive"), _last(self.history, "work_push"))
             if v is not None]
        return sum(w) if w else None

    def balance_error(self):
        """energy_balance_error at the end [J]: the stage's column, or computed from the split
        when the column is missing."""
        h = self.history
        err = _last(h, "energy_balance_error")
        if err is not None:
            return err
        ins = [_last(h, c) for c, _, side in ENERGY_COLUMNS if side == "in"]
        outs = [_last(h, c) for c, _, side in ENERGY_COLUMNS if side == "out"]
        if None in ins or None in outs:
            return None
        return sum(ins) - sum(outs)

    def balance_fraction(self):
        err, w = self.balance_error(), self.work_in()
        if err is not None and w:
            return err / w
        return value_of(get(self.summary, "energy_balance_error"))

    def max_of(self, column, summary_key):
        values = _column(self.history, column)
        if values:
            return max(values)
        return value_of(get(self.summary, summary_key))


def _incomplete_reasons(run):
    rolling = run.rolling
    reasons = []
    status = run.manifest.get("status") if isinstance(run.manifest, dict) else None
    if status and status != "complete":
        reasons.append(f"fe_stage's manifest says <strong>{esc(status)}</strong>" +
                       (f": {esc(run.manifest.get('message', ''))}" if run.manifest.get("message") else ""))
    for name, st in (("rolling_history.csv", run.history_status),
                     ("rolling_strain_profile.csv", run.profile_status)):
        if st and st != "complete":
            reasons.append(f"{name} says <em>{esc(st)}</em>")
    if rolling.get("status") == "complete" and run.folder and run.history is None:
        reasons.append("no rolling_history.csv in " + esc(run.folder))
    return reasons


def _plot_columns(ax, x, table, specs):
    """Each (column, style, label) of `table` present in the run, against x."""
    for col, style, label in specs:
        values = _column(table, col)
        if values:
            ax.plot(x, values, style, marker="o", ms=2.5, label=label)


def _spin_figure(run):
    h = run.history
    t = [x * 1e3 for x in h["time"]]
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    _plot_columns(ax, t, h, [("phi_rate", "C0-", "φ̇ bearing (driven), exact"),
                             ("phi_rate_paper", "C0--", "φ̇ by the paper's Eqs. 4–5, 7"),
                             ("gamma_rate", "C1-", "γ̇ journal (torque balance), exact"),
                             ("gamma_rate_paper", "C1--", "γ̇ by the paper's Eqs. 6, 7")])
    rate = value_of(get(run.summary, "rolling_rate"))
    if rate:
        ax.axhline(rate, color="k", ls=":", lw=1,
                   label=f"rolling without slip at δ_max: {rate:.4g} rad/s")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("spin rate [rad/s]")
    ax.set_title("spin rates of bearing and journal (the paper's Fig. 10)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return figure_html(fig, "Rolling: the bearing's φ̇ and the journal's γ̇ against time, exact "
                            "(solid) and by the paper's Eqs. 7–8 from the displacement of the "
                            "points that touch at t = 0 (dashed) — the counterpart of the "
                            "paper's Fig. 10")


def _energy_figure(run, extra_columns):
    h = run.history
    t = [x * 1e3 for x in h["time"]]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.2))
    for col, label, side in ENERGY_COLUMNS:
        values = _column(h, col)
        if values:
            ax.plot(t, values, ls="--" if side == "in" else ("-." if side == "check" else "-"),
                    label=f"{label} ({'in' if side == 'in' else 'stored/lost' if side == 'out' else 'check'})")
    for col in extra_columns:
        ax.plot(t, h[col], ls=":", label=f"{col} (added by fe_stage)")
    err = _column(h, "energy_balance_error")
    if err:
        ax.plot(t, err, "k:", label="balance error")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("energy [J]")
    ax.set_title("energy split")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    wd, wp = _column(h, "work_drive"), _column(h, "work_push")
    if err and wd and wp:
        pct = [100 * e / (abs(a) + abs(b)) if (abs(a) + abs(b)) > 0 else float("nan")
               for e, a, b in zip(err, wd, wp)]
        bx.plot(t, pct, "k-", marker="o", ms=2.5, label="fixed frame: error / (|work_drive| + |work_push|)")
        wf, fe = _column(h, "work_frame"), _column(h, "frame_balance_error")
        if wf and fe:
            bx.plot(t, [100 * e / abs(w) if w else float("nan") for e, w in zip(fe, wf)], "C2-",
                    marker="o", ms=2.5, label="bearing's frame: error / |work_frame|")
        for s in (1, -1):
            bx.axhline(s * 100 * BALANCE_LIMIT, color="C3", ls=":", lw=1)
        bx.legend(fontsize=7)
    bx.set_xlabel("t [ms]")
    bx.set_ylabel("balance error [% of the work in]")
    bx.set_title(f"energy balance error (warning beyond ±{100 * BALANCE_LIMIT:g} %)")
    bx.grid(True, alpha=0.3)
    fig.tight_layout()
    return figure_html(fig, "Rolling: the energy split against time — the work in (drive and "
                            "push) against the stored elastic energy, the plastic and friction "
                            "dissipation and the journal's kinetic energy — and the balance "
                            "error as a % of the work in")


def _split_by_body(p):
    """The profile's rows per body: {0: bore, 1: journal} (older runs: all rows the bore's)."""
    bodies = _column(p, "body")
    if not bodies:
        return {0: p}
    split = {}
    for b in sorted(set(int(x) for x in bodies)):
        split[b] = {k: [v for v, x in zip(vals, bodies) if int(x) == b]
                    for k, vals in p.items()}
    return split


def _profile_figure(run):
    parts = _split_by_body(run.profile)
    fig, axes = plt.subplots(1, len(parts), figsize=(7.5 * len(parts), 4.2), squeeze=False)
    names = {0: "bore", 1: "journal's surface"}
    for ax, (body, p) in zip(axes[0], parts.items()):
        arc = [x * 1e3 for x in p["arc"]] if _column(p, "arc") else \
            [math.degrees(a) for a in p.get("angle", [])]
        where = names.get(body, f"body {body}")
        ax.set_xlabel(f"arc along the {where} from the contact point [mm]" if _column(p, "arc")
                      else "angle from the contact point [°]")
        _plot_columns(ax, arc, p, [("strain_radial", "C0-", "radial"),
                                   ("strain_tangential", "C1-", "tangential"),
                                   ("strain_axial", "C2-", "axial"),
                                   ("plastic_strain", "k--", "equivalent plastic")])
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_ylabel(f"strain at the {where} [1]")
        ax.set_title(f"{where} strains across the contact at the end (the paper's Fig. 12)",
                     fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    return figure_html(fig, "Rolling: the radial, tangential and axial strain and the "
                            "equivalent plastic strain across the contact zone at the end of the "
                            "run (axial mid-plane), on the bore and, with a deformable journal, "
                            "on the journal's surface — the counterpart of the paper's Fig. 12")


# What the paper's Fig. 11 shows (§3.4), for the caption of ours.
PAPER_FIG_11 = ("The paper's Fig. 11a shows the principal strains after 0.250 s, at the full push "
                "of 1 mm with the bearing half a turn on, in the bearing and the journal (the "
                "journal's body hidden behind its contact surface), with a strain field in the "
                "bearing made asymmetric by the tangential strains of rolling; Fig. 11b labels "
                "the interface elements with their principal strains. Its text gives no values.")


def _strain_cell(value, where=None, sign=True):
    if value is None:
        return "—"
    text = f"{value:+.3g}" if sign else f"{value:.3g}"
    if where:
        text += f" <small>(r = {where[0] * 1e3:.2f} mm from its axis, z = {where[1] * 1e3:.2f} mm)</small>"
    return text


def _strain_map(run, base, warnings):
    """The principal-strain map of the bore and the journal at the end (Fig. 11) from the run's
    last fields (scripts/plotting/rolling_strains.py), with the extremes per body; a note when
    the run wrote no fields or they cannot be drawn."""
    try:
        import vtk  # noqa: F401
        from plotting import rolling_strains
    except ImportError:
        warnings.add("FE rolling study", "no principal-strain map (Fig. 11): VTK's Python "
                     "bindings are missing (Debian package python3-vtk9)", "rolling")
        return ("<p>No principal-strain map: VTK's Python bindings are missing "
                "(python3-vtk9).</p>")
    try:
        m = rolling_strains.read_strain_map(run.folder)
        if "note" in m:
            return f"<p>No principal-strain map: {esc(m['note'])}.</p>"
        png = os.path.join(base, "pictures", "rolling_strains.png")
        os.makedirs(os.path.dirname(png), exist_ok=True)
        rolling_strains.draw(m, png)
    except Exception as e:  # a damaged VTU must not stop the report
        warnings.add("FE rolling study", "the principal-strain map (Fig. 11) could not be drawn: " +
                     esc(f"{type(e).__name__}: {e}"), "rolling")
        return (f"<p class='warn'>No principal-strain map: the fields could not be drawn "
                f"({esc(type(e).__name__)}: {esc(str(e))}).</p>")
    ang = m["angles"]
    when = (f"at t = {ang['time']:.4g} s (δ = {ang['delta'] * 1e3:.4g} mm), the bearing turned by "
            f"φ = {math.degrees(ang['phi']):.1f}° and the journal by γ = "
            f"{math.degrees(ang['gamma']):.1f}° since the start" if ang else
            f"at the last field output (t = {m['field_time']:.4g} s); {esc(m['angles_note'])}")
    numbers = "; ".join(
        f"{name}: largest principal strain {_strain_cell(b.get('near_contact_max_tension'))}, "
        f"smallest {_strain_cell(b.get('near_contact_max_compression'))} near the contact"
        for name, b in m["bodies"].items())
    caption = (f"Rolling: the principal strains at the end — {PAPER_FIG_11} Ours: {when}, cut at "
               f"the axial mid-plane z = {m['mid_plane_z'] * 1e3:g} mm (the model's symmetry "
               "plane), each body placed where it is in the fixed frame (fe_stage computes each "
               "in its own turning frame). (a) The section: the plastic zone (cells where a point "
               "has yielded, ε_p > 0) filled and outlined, the bore points in contact, and the "
               "two material points that touched at t = 0, turned on with their bodies; (b) the "
               "largest and (c) the smallest principal strain in the window around the contact "
               f"(red tension, blue compression). {numbers}." +
               (f" This run pushes {ang['delta'] * 1e3:.3g} mm, not the paper's 1 mm: the "
                "pattern compares, the size of the strains does not." if ang and ang["delta"] < 0.9e-3
                else ""))
    table = ["<table><tr><th>body</th><th>largest principal strain (tension), whole body [1]</th>"
             "<th>smallest principal strain (compression), whole body [1]</th>"
             "<th>near the contact, mid-plane: largest / smallest [1]</th>"
             "<th>largest equivalent plastic strain [1]</th></tr>"]
    for name, b in m["bodies"].items():
        table.append(f"<tr><td>{esc(name)}</td>"
                     f"<td>{_strain_cell(b['max_tension'], b['max_tension_at'])}</td>"
                     f"<td>{_strain_cell(b['max_compression'], b['max_compression_at'])}</td>"
                     f"<td>{_strain_cell(b.get('near_contact_max_tension'))} / "
                     f"{_strain_cell(b.get('near_contact_max_compression'))}</td>"
                     f"<td>{_strain_cell(b.get('max_plastic_strain'), sign=False)}</td></tr>")
    table.append("</table>")
    rigid = "" if "journal" in m["bodies"] else (
        "<p>The journal is rigid in this run: it has no strain; its outline is drawn.</p>")
    return (image_file_html(png, caption) + "".join(table) + rigid +
            "<p>The whole-body values are those of the output points (each Q2 cell written as "
            "2×2×2 sub-cells, the strain at their corners); where they lie far from the contact "
            "(the columns give each point's distance from its body's axis), they are not the "
            "contact's. From " + rel_link(m["file"], base) + ".</p>")


def _effort(h):
    """The run's material Newton iterations and the line search's rejected trial points, summed
    over its steps (each step's counts include its failed attempts)."""
    newton, rejected = _column(h, "newton_iterations"), _column(h, "line_search_steps")
    if not newton:
        return "not recorded"
    text = f"{sum(newton):.0f} material Newton iterations"
    if rejected:
        text += f", {sum(rejected):.0f} line-search trial points rejected"
    return text


def _final_table(run):
    h, s = run.history, run.summary
    rate = value_of(get(s, "rolling_rate"))
    gamma = _last(h, "gamma_rate")
    share = f" ({100 * gamma / rate:.1f} % of the rolling rate {rate:.4g} rad/s)" \
        if gamma is not None and rate else ""
    frac = run.balance_fraction()
    delta = _last(h, "delta")
    cuts = _column(h, "cuts")
    rows = [
        ("end of the run", _fmt(_last(h, "time"), "{:.4g}", "s") +
         f" after {len(h['time']) - 1} time steps" +
         (f" ({sum(cuts):.0f} step cuts)" if cuts else "")),
        ("solver effort", _effort(h)),
        ("push δ at the end", _fmt(delta * 1e3 if delta is not None else None, "{:.4g}", "mm")),
        ("contact force at the end, normal", _fmt(_last(h, "force_normal"), "{:.5g}", "N")),
        ("contact force at the end, tangential", _fmt(_last(h, "force_tangential"), "{:.5g}", "N")),
        ("bearing spin rate φ̇", _fmt(_last(h, "phi_rate"), "{:.5g}", "rad/s")),
        ("journal spin rate γ̇", _fmt(gamma, "{:.5g}", "rad/s") + share),
        ("journal spin rate by the paper's Eq. 7", _fmt(_last(h, "gamma_rate_paper"), "{:.5g}", "rad/s")),
        ("slip speed at the contact", _fmt(_last(h, "slip_speed"), "{:.4g}", "m/s")),
        ("largest equivalent plastic strain", _fmt(run.max_of("max_plastic_strain", "max_plastic_strain"),
                                                   "{:.4g}", "[1]")),
        ("largest principal strain", _fmt(run.max_of("max_strain", "max_strain"), "{:.4g}", "[1]")),
        ("energy balance error", _fmt(100 * frac if frac is not None else None, "{:+.2f}",
                                      "% of the work in")),
    ]
    wall = _last(h, "wall_time")
    if wall is not None:
        rows.append(("wall time up to the last converged step", _fmt(wall, "{:.3g}", "s")))
    return ("<table><tr><th>quantity</th><th>value</th></tr>" +
            "".join(f"<tr><td>{esc(a)}</td><td>{b}</td></tr>" for a, b in rows) + "</table>")


def _energy_table(run, extra_columns):
    h = run.history
    w = run.work_in()
    rows = ["<table><tr><th>energy at the end</th><th>column</th><th>[J]</th>"
            "<th>% of the work in</th></tr>"]

    def row(label, col, value):
        pct = f"{100 * value / w:+.2f} %" if value is not None and w else "—"
        rows.append(f"<tr><td>{esc(label)}</td><td><code>{esc(col)}</code></td>"
                    f"<td>{_fmt(value, '{:.5g}')}</td><td>{pct}</td></tr>")

    for col, label, side in ENERGY_COLUMNS:
        value = _last(h, col)
        if value is None and col == "work_drive_torque":
            continue  # only newer fe_stage outputs have it
        row(("in: " if side == "in" else "" if side == "out" else "check: ") + label, col, value)
    for col in extra_columns:
        row("added by fe_stage (not interpreted here)", col, _last(h, col))
    row("balance error: work in − the rest", "energy_balance_error", run.balance_error())
    rows.append("</table>")
    text = ("".join(rows) + f"<p>Work in = |work_drive| + |work_push| = "
            f"{_fmt(w, '{:.5g}', 'J')} (the manifest's measure).")
    wf, fe = _last(h, "work_frame"), _last(h, "frame_balance_error")
    if wf is not None and fe is not None:
        text += (f" In the bearing's own frame the contact forces' work on it, work_frame = "
                 f"{_fmt(wf, '{:.5g}', 'J')}, against its elastic energy and plastic dissipation "
                 f"leaves {_fmt(fe, '{:.4g}', 'J')}" +
                 (f" ({100 * fe / abs(wf):+.2f} % of work_frame)" if wf else "") + ".")
    return text + "</p>"


def _slip_stages(run):
    st = get(run.summary, "slip_stages")
    if not isinstance(st, dict):
        return "<p>Slip stages: not in the manifest.</p>"
    found = st.get("found")
    rows = [("found", "yes" if found else "no")]
    for key, label, fmt in [("slip_speed_max", "largest slip speed", "{:.4g}"),
                            ("end_of_slip", "end of gross slip (the slip speed first below half "
                                            "its largest value)", "{:.4g}"),
                            ("settled", "settled (from here within 5 % of the largest value "
                                        "about the final one)", "{:.4g}"),
                            ("slip_speed_final", "final slip speed", "{:.4g}")]:
        q = st.get(key)
        unit = q.get("unit", "") if isinstance(q, dict) else ""
        rows.append((label, _fmt(value_of(q), fmt, unit)))
    note = "" if found else ("<p>No slip stages were found in this run (too few steps, no slip, or "
                             "the slip speed never fell below half its largest value before the "
                             "end: the run ended in gross slip or before the journal caught up): "
                             "the times above are not meaningful.</p>")
    return ("<h3>Slip stages (fe_stage's manifest)</h3><table><tr><th>stage</th><th>value</th></tr>" +
            "".join(f"<tr><td>{esc(a)}</td><td>{esc(b)}</td></tr>" for a, b in rows) +
            "</table>" + note)


def _finite_strain(scene):
    """The run's kinematics was finite (fe_stage writes the scene it ran, defaults included;
    a scene without the key is from before the rolling study's default became finite)."""
    return get(scene, "material", "kinematics") == "finite" if isinstance(scene, dict) else False


def _what_was_modelled(run):
    sc = run.scene
    r = sc.get("rolling", {}) if isinstance(sc, dict) else {}
    omega = r.get("omega_B")
    ramp = r.get("ramp_time")
    delta = get(sc, "loading", "delta_max")
    mu = get(sc, "contact", "mu")
    parts = []
    if omega is not None:
        parts.append(f"ω_B = {omega:.4g} rad/s")
    if delta is not None:
        parts.append(f"δ_max = {delta * 1e3:.4g} mm" + (f" reached at {ramp:.4g} s" if ramp else ""))
    if mu is not None:
        parts.append(f"Coulomb friction μ = {mu:g}")
    if r.get("n_steps") is not None:
        parts.append(f"{r['n_steps']} nominal time steps")
    deformable = get(sc, "loading", "journal") == "core"
    bodies = ("the journal is deformable too, its core clamped in its own frame, which carries "
              "the push and the spin; both bodies are elastoplastic (von Mises, isotropic "
              "hardening), each computed in the frame that turns with it, and meet by dual "
              "mortar searched again at every time step" if deformable else
              "the bearing is elastoplastic (von Mises, isotropic hardening) and computed in the "
              "frame that turns with it")
    return ("<p>The bearing turns at ω_B; the " + ("deformable" if deformable else "rigid") +
            " journal's axis is pushed radially into it and the journal turns freely, driven by "
            "friction alone; " + bodies + " (docs/fe.md, “Rolling study”). Coarse mesh, " +
            ("finite strain (total Lagrangian, J2 in the logarithmic strain space)"
             if _finite_strain(sc) else "small strain") + "." + (f" This run: {esc(', '.join(parts))}." if parts else "") + "</p>")


def _frame_note(h):
    """Where fe_stage writes it, the bearing's own balance in its frame (work_frame against its
    elastic energy and plastic dissipation): tells a gap in the drive's work from a gap in the
    bearing's bookkeeping (docs/fe.md)."""
    wf, fe = _last(h, "work_frame"), _last(h, "frame_balance_error")
    if wf is None or fe is None or not wf:
        return ""
    return (f"; the bearing's own balance in its frame is {100 * fe / abs(wf):+.1f} % of "
            f"work_frame = {wf:.4g} J")


def rolling_section(rolling, base, warnings):
    """HTML of the rolling section, or "" if the run has no rolling study."""
    if not rolling:
        return ""
    parts = ["<h2 id='rolling'>FE rolling study (paper §3.4)</h2>"]
    status = rolling.get("status", "complete")
    run = RollingRun(rolling)
    parts.append(_what_was_modelled(run))
    if status == "failed":
        msg = rolling.get("message") or "(no message)"
        warnings.add("FE rolling study", "the fe_stage task <strong>failed</strong>: " +
                     esc(_failure_line(msg)) + " — the rest of the run went on", "rolling")
        parts.append("<div class='warn'><p><strong>The rolling task failed.</strong> Its message:"
                     f"</p><pre>{esc(msg)}</pre>" +
                     (f"<p>What it wrote before it stopped is in {rel_link(run.folder, base)} "
                      "(shown below); the next run redoes the task.</p>" if run.folder else
                      "<p>It left no output to show.</p>") + "</div>")
    elif status == "not_run":
        warnings.add("FE rolling study", esc(rolling.get("message", "not run")), "rolling")
        parts.append(f"<p class='warn'>Not run: {esc(rolling.get('message', ''))}.</p>")
        return "\n".join(parts)
    if not run.folder:
        if status != "failed":
            warnings.add("FE rolling study", f"no output folder {esc(rolling.get('fe_dir', '?'))}",
                         "rolling")
        return "\n".join(parts)
    reasons = _incomplete_reasons(run)
    if reasons and status != "failed":
        warnings.add("FE rolling study", "the run is <strong>incomplete</strong>: " +
                     "; ".join(reasons), "rolling")
    if reasons:
        parts.append("<p class='warn'>Incomplete: " + "; ".join(reasons) +
                     ". The numbers below are those of the last converged step.</p>")
    if not run.has_steps():
        parts.append("<p>No converged time step to show.</p>")
        return "\n".join(parts)

    h = run.history
    known = {c for c, _, _ in ENERGY_COLUMNS} | {"energy_balance_error", "work_frame",
                                                 "frame_balance_error"}
    extra_energy = [c for c in h if (run.units or {}).get(c) == "J" and c not in known and h[c]]

    frac = run.balance_fraction()
    if frac is not None and abs(frac) > BALANCE_LIMIT:
        warnings.add("FE rolling study",
                     f"the energy balance does not close: its error at the end is "
                     f"<strong>{100 * frac:+.1f} % of the work in</strong> (|work_drive| + "
                     f"|work_push| = {run.work_in():.4g} J; limit ±{100 * BALANCE_LIMIT:g} %)" +
                     _frame_note(h), "rolling")
    eps = run.max_of("max_strain", "max_strain")
    if eps is not None and eps > STRAIN_LIMIT and not _finite_strain(run.scene):
        warnings.add("FE rolling study",
                     f"the largest principal strain reaches <strong>{eps:.3g}</strong> (above "
                     f"{STRAIN_LIMIT:g}): the small-strain model is not accurate there — a "
                     "finite-strain formulation is needed (docs/fe.md)", "rolling")

    parts.append("<h3>Final numbers</h3>")
    parts.append(_final_table(run))
    parts.append(_spin_figure(run))
    parts.append("<h3>Energy split</h3>")
    parts.append(_energy_table(run, extra_energy))
    parts.append(_energy_figure(run, extra_energy))
    parts.append("<h3>Strains across the contact (Fig. 12)</h3>")
    if run.profile and _column(run.profile, "arc") or (run.profile and _column(run.profile, "angle")):
        parts.append(_profile_figure(run))
        pe = _column(run.profile, "plastic_strain")
        if pe:
            parts.append(f"<p>Largest equivalent plastic strain on the profile: {max(pe):.4g} [1].</p>")
    else:
        parts.append("<p>No strain profile (rolling_strain_profile.csv missing or empty).</p>")
    parts.append("<h3>Principal strains in the bore and the journal at the end (Fig. 11)</h3>")
    parts.append(_strain_map(run, base, warnings))
    parts.append(_slip_stages(run))
    files = [f for f in ("rolling_history.csv", "rolling_strain_profile.csv", "manifest.json")
             if os.path.exists(os.path.join(run.folder, f))]
    parts.append("<p>Files: " + ", ".join(rel_link(os.path.join(run.folder, f), base) for f in files) +
                 (", fields: " + rel_link(os.path.join(run.folder, "fields", "solution.pvd"), base)
                  if os.path.exists(os.path.join(run.folder, "fields", "solution.pvd")) else "") +
                 ".</p>")
    png = os.path.join(run.folder, "rolling.png")
    if os.path.exists(png):
        parts.append(details("fe_stage's own rolling plot: spin rates, slip speed, forces, energy, "
                             "strains, strain profile",
                             image_file_html(png, "Rolling: fe_stage's plot of the run "
                                                  f"({rel_link(run.folder, base)})")))
    return "\n".join(parts)


def rolling_headline(rolling):
    """One sentence for the report's summary; "" without a rolling study."""
    if not rolling:
        return ""
    link = "<a href='#rolling'>FE rolling study</a>"
    status = rolling.get("status", "complete")
    if status == "not_run":
        return f"<p>Rolling ({link}): not run ({esc(rolling.get('message', ''))}).</p>"
    run = RollingRun(rolling)
    failed = ("<strong>the task failed</strong>: " + esc(_failure_line(rolling.get("message")))
              ) if status == "failed" else ""
    if not run.has_steps():
        return f"<p>Rolling ({link}): {failed or 'no converged time step'}.</p>"
    h = run.history
    rate = value_of(get(run.summary, "rolling_rate"))
    gamma = _last(h, "gamma_rate")
    frac = run.balance_fraction()
    text = (f"<p>Rolling ({link}){', ' + failed + '; up to the last converged step' if failed else ''}: "
            f"at t = {_fmt(_last(h, 'time'), '{:.4g}', 's')}, contact force "
            f"{_fmt(_last(h, 'force_normal'), '{:.5g}', 'N')}, journal spin "
            f"{_fmt(gamma, '{:.4g}', 'rad/s')}" +
            (f" ({100 * gamma / rate:.1f} % of rolling without slip)" if gamma is not None and rate else "") +
            f", slip speed {_fmt(_last(h, 'slip_speed'), '{:.3g}', 'm/s')}, largest plastic strain "
            f"{_fmt(run.max_of('max_plastic_strain', 'max_plastic_strain'), '{:.3g}', '[1]')}, energy "
            f"balance error {_fmt(100 * frac if frac is not None else None, '{:+.1f}', '%')} of the "
            f"work in.</p>")
    return text
