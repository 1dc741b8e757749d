"""The report's FE part: one section per FE sweep — what was modelled and how it differs from
the paper, F–δ with the paper's law over it, F_ref and n against the parameter (not K: K's unit
N/m^n changes with n), the paper's claim beside ours, the fields (VTK pictures, yield check,
contact-field checks), the law table, and every case's own plots folded away."""
import glob
import math
import os
import subprocess
import sys
import tempfile

import matplotlib.pyplot as plt

from plotting import _paper
from plotting._report_common import (details, esc, figure_html, get, image_file_html,
                                     load_or_none, readable_log_axis, rel_link, shown, thousands,
                                     value_of)

LOADING_WORDS = {
    "end_faces": "a deformable journal pushed at its two end faces (every point of both end "
                 "faces displaced by δ along −y)",
    "rigid": "a rigid journal (only the bearing is meshed; the journal is a moving cylinder)",
    "core": "a deformable journal driven through a rigid inner core (r ≤ R_J/2)",
    "axis_line": "the nodes on the journal's axis displaced by δ (the paper's loading)",
}

# Our reading where our trend differs from the paper's claim (docs/fe.md, sections "Trend with
# t_B" and "Misalignment study"); shown only when the measured trend differs.
REASONS = {
    "theta": "our journal is rigid and pushed δ beyond the first touch of one rim point, so the "
             "load sits under one rim edge whatever θ is; as θ grows that rim point moves inward "
             "(z_P1 = −8.83 mm at 1°, −8.44 mm at θ_max), away from the bearing's free end, where "
             "the ring is stiffer. The paper drove the nodes of the journal's axis of a "
             "deformable journal: a line load whose compliance changes with θ and does not "
             "converge with the mesh (SPEC §2, docs/fe.md “Misalignment study”).",
    "t_B": "the paper's conclusion says the force falls with t_B; its §3.1 text and Fig. 4b say "
           "it grows, as ours does (SPEC §2).",
}
# The same, where it depends on the journal (loading.journal) of the sweep's scene.
REASONS_BY_JOURNAL = {
    ("theta", "core"): "not analysed for this run: on the adaptive meshes of docs/fe.md the "
                       "core-loaded deformable journal's force falls with θ (−15 % from 1° to "
                       "2.5°, frictionless); a step smaller than the mesh error can turn the "
                       "sign, so compare the steps with the error per θ (preset table).",
}


def reason_for(sweep, loading):
    return REASONS_BY_JOURNAL.get((sweep["parameter"], loading),
                                  REASONS.get(sweep["parameter"], "not analysed"))


def case_label(sweep, case):
    v, u = shown(case["value"], sweep["unit"])
    keyword = case.get("keyword")
    middle = f"{keyword} = " if keyword else ""
    name = "θ" if sweep["parameter"] == "theta" else sweep["parameter"]
    return f"{name} = {middle}{v:.5g} {u}"


def param_axis_label(sweep):
    u = shown(1.0, sweep["unit"])[1]
    name = "θ" if sweep["parameter"] == "theta" else sweep["parameter"]
    return f"{name} [{u}]"


def f_ref_interval(law, delta):
    """F(δ) and its 95 % half-width from the regression alone (delta method on ln F = ln K +
    n ln δ with the fit's σ_K, σ_n and their correlation; the t factor the fit used)."""
    K, n = law["law"]["K"], law["law"]["n"]
    F = K * delta ** n
    d = law.get("diagnostics")
    if not d or not d.get("n_std_error"):
        return F, None
    sK, sn, rho = d["K_std_error"], d["n_std_error"], d["correlation_K_n"]
    L = math.log(delta)
    var = (sK / K) ** 2 + (L * sn) ** 2 + 2 * L * rho * (sK / K) * sn
    t = (d["n_ci95"][1] - n) / sn
    return F, F * t * math.sqrt(max(var, 0.0))


def mesh_error(law):
    """The law's measured discretisation error of F [1], or None if not stated."""
    return value_of(get(law, "discretisation_error", "F_relative"))


def trend_words(values):
    diffs = [b - a for a, b in zip(values, values[1:])]
    if all(d > 0 for d in diffs):
        return +1, "grows monotonically"
    if all(d < 0 for d in diffs):
        return -1, "falls monotonically"
    up = sum(1 for d in diffs if d > 0)
    return 0, f"is not monotonic ({up} of {len(diffs)} steps up)"


def own_estimate(man, case=None):
    """fe_stage's own estimate of the relative error of F(δ_max) on an adaptive case's last mesh
    (manifest extra.adaptive.estimated_error_F_max, docs/fe.md "The error estimate"), as
    {"value": [1], "last_change": bool, "method": words, "extrapolated_force": N or None,
    "n_meshes": int, "n_dofs": DoFs of the last mesh, "record": words or None}; None for a case
    without adaptive cycles or with a single mesh (nothing to estimate from). last_change: the
    change in the last cycle, not extrapolated and not a bound (method "change in the last cycle
    (not extrapolated; not a bound)"; manifests before 2026-11-29 said "(a lower bound)", which
    it never was). record: how that fallback compared with the error on the recorded sequences,
    as run_pipeline wrote it beside the case in its summary (`case`: the summary's entry;
    laws::last_change_record, checked against the sequences by the estimator's test)."""
    a = get(man, "extra", "adaptive")
    e = value_of(get(a, "estimated_error_F_max"))
    if e is None:
        return None
    method = str(get(a, "estimated_error_F_max", "method", default=""))
    cycles = get(a, "cycles", default=[]) or []
    return {"value": e, "last_change": "change in the last cycle" in method, "method": method,
            "extrapolated_force": value_of(get(a, "extrapolated_force")),
            "n_meshes": len(cycles), "n_dofs": value_of(get(cycles, -1, "n_dofs")),
            "record": get(case, "own_error_F_max", "last_change_record")}


def own_estimate_words(est):
    """"0.85 % (extrapolated from the sequence)" or "≈ 0.4 % (the change in the last cycle, not
    extrapolated: <its record>)", the record as the summary gives it (none: not quoted)."""
    if est["last_change"]:
        record = f": {est['record']}" if est.get("record") else ""
        return (f"≈ {100 * est['value']:.2g} % (the change in the last cycle, not extrapolated"
                f"{record})")
    return f"{100 * est['value']:.2g} % (extrapolated from the sequence)"


def largest_own_estimate(fs):
    """(estimate, case) with the largest own estimate over the sweep's cases, or None."""
    found = [(own_estimate(man, case), case) for case, _, man in fs.cases]
    found = [(e, c) for e, c in found if e is not None]
    return max(found, key=lambda ec: ec[0]["value"]) if found else None


def own_estimate_section(fs, preset_error=None):
    """The run's own error estimate of F(δ_max) per adaptive case beside the chosen preset's
    measured figure (`preset_error`: presets.<p>.measured.error_F_max.<sweep>, {percent, where}
    or None). Where the preset's figure is null (a geometry without a convergence study, e.g. a
    Gmsh bearing) the run's own estimate is the figure to use, and the section says so. Empty
    for a sweep without adaptive cases."""
    rows, estimates = [], []
    for case, _, man in fs.cases:
        est = own_estimate(man, case)
        if est is None:
            continue
        estimates.append(est)
        F = value_of(get(man, "extra", "force_at_delta_max"))
        F_inf = est["extrapolated_force"]
        rows.append(f"<tr><td>{esc(case_label(fs.sweep, case))}</td><td>{est['n_meshes']}</td>"
                    f"<td>{thousands(est['n_dofs']) if est['n_dofs'] else '?'}</td>"
                    f"<td>{thousands(F) if F is not None else '?'}</td>"
                    f"<td>{esc(own_estimate_words(est))}</td>"
                    f"<td>{thousands(F_inf) if F_inf is not None else '—'}</td></tr>")
    if not rows:
        return ""
    percent = get(preset_error, "percent")
    where = get(preset_error, "where", default="")
    out = ["<h4>Mesh error of F(δ_max)</h4>",
           "<p>Every case ran an adaptive sequence of meshes (Kelly indicator); fe_stage "
           "estimates the error of F(δ_max) on the last mesh from the sequence itself (docs/fe.md "
           "“The error estimate”): extrapolated when the last changes shrink steadily, else only "
           "the last cycle's change, which is no bound either way.</p>",
           "<table><tr><th>case</th><th>meshes</th><th>DoFs, last mesh [1]</th>"
           "<th>F(δ_max) [N]</th><th>the run's own estimate of the error of F(δ_max)</th>"
           "<th>extrapolated F [N]</th></tr>", "".join(rows), "</table>"]
    if percent is not None:
        out.append(f"<p>The preset's measured error for this sweep: {percent:.3g} % "
                   f"({esc(where)}). The run's own estimate is set beside it as a check: where "
                   f"they differ much, the measurement may not describe this run's scene.</p>")
        worst, case = largest_own_estimate(fs)
        if 100 * worst["value"] > percent:
            out.append(f"<p class='warn'>At {esc(case_label(fs.sweep, case))} the run's own "
                       f"estimate, {esc(own_estimate_words(worst))}, exceeds the preset's measured "
                       f"{percent:.3g} %. The measured figure comes from longer sequences of the "
                       f"cases its note names; for a case it does not name, the larger is the "
                       f"safer figure.</p>")
    else:
        worst, case = largest_own_estimate(fs)
        out.append(f"<p class='warn'>The preset's error is not measured for this sweep"
                   f"{f' ({esc(where)})' if where else ''}: <strong>the run's own estimate is the "
                   f"figure to use</strong>, the largest here "
                   f"{esc(own_estimate_words(worst))} at {esc(case_label(fs.sweep, case))}."
                   + (" The change in the last cycle is only an indication of the error, "
                      "neither a lower nor an upper bound: run more adaptive cycles "
                      "(mesh.adaptive_cycles) for an extrapolated estimate."
                      if any(e["last_change"] for e in estimates) else "")
                   + " The fitted laws carry it as their mesh error (their law files' "
                     "discretisation_error: each law its case's estimate, the family the "
                     "largest of its cases'), so the MBD band's mesh variants use it.</p>")
    return "".join(out)


class FeSweep:
    """One FE sweep of pipeline_summary.json (its `sweeps`) with its laws and FE manifests loaded."""

    def __init__(self, sweep):
        self.sweep = sweep
        self.cases = []  # (case, law, fe_manifest)
        for case in sweep["cases"]:
            law = load_or_none(case["law"])
            man = load_or_none(os.path.join(case["fe_dir"], "manifest.json"))
            if law is not None:
                self.cases.append((case, law, man))
        self.anchor = "sweep-" + sweep["name"]

    def first_scene(self):
        for _, _, man in self.cases:
            s = get(man, "extra", "scene")
            if s:
                return s
        return {}

    def delta_ref(self):
        return min(l["valid_range"]["delta_max"] for _, l, _ in self.cases)

    def values_shown(self):
        return [shown(c["value"], self.sweep["unit"])[0] for c, _, _ in self.cases]


def gmsh_mesh_name(path):
    """A Gmsh mesh's file with its folder: run_pipeline's mesh tasks write
    mesh/<.geo stem>-<hash>/mesh.msh, whose folder names the .geo."""
    parts = str(path).replace("\\", "/").split("/")
    return "/".join(parts[-2:]) if parts[-1] == "mesh.msh" and len(parts) > 1 else parts[-1]


def modelled_paragraph(fs):
    s = fs.first_scene()
    sweep = fs.sweep
    loading = get(s, "loading", "journal", default="?")
    mu = get(s, "contact", "mu")
    g = get(s, "geometry", default={})
    mesh = get(s, "mesh", default={})
    man = fs.cases[0][2] if fs.cases else None
    sym = value_of(get(man, "extra", "symmetry_factor"))
    dofs = value_of(get(man, "extra", "n_dofs"))
    values = ", ".join(f"{v:.4g}" for v in fs.values_shown())
    parts = [f"<p><strong>What was modelled.</strong> {esc(sweep['name'])}: "
             f"{esc(param_axis_label(sweep))} ∈ {{{esc(values)}}}; "
             f"{esc(LOADING_WORDS.get(loading, loading))}"]
    if g:
        parts.append(f"; bearing R_B = {g.get('R_B', 0) * 1e3:.4g} mm, L_B = {g.get('L_B', 0) * 1e3:.4g} mm, "
                     f"radial clearance c_r = {g.get('c_r', 0) * 1e3:.4g} mm")
    d_max = get(s, "loading", "delta_max")
    n_inc = get(s, "loading", "n_increments")
    if d_max:
        parts.append(f"; pushed to δ = {d_max * 1e3:.4g} mm in {n_inc} increments beyond first touch")
    parts.append("; " + ("frictionless contact (μ = 0)" if mu == 0 else
                         f"Coulomb friction μ = {mu:g}" if mu is not None else "friction not stated"))
    if sym:
        parts.append(f"; {'quarter' if sym == 4 else 'half' if sym == 2 else 'full'} model "
                     f"(forces × {sym:g} for the full joint)")
    if mesh and g.get("mesh"):
        # a Gmsh bearing: its cells, not the generated base mesh's counts
        parts.append(f"; Q{mesh.get('degree', '?')} elements on the Gmsh mesh "
                     f"{esc(gmsh_mesh_name(g['mesh']))} (the bearing on its polar chart, so "
                     f"refined faces follow the cylinders), {mesh.get('global_refinements')} global "
                     f"and {mesh.get('contact_refinements')} contact-zone refinements")
    elif mesh:
        parts.append(f"; Q{mesh.get('degree', '?')} elements, base mesh "
                     f"{mesh.get('n_circumferential')}×{mesh.get('n_radial')}×{mesh.get('n_axial')}, "
                     f"{mesh.get('global_refinements')} global and {mesh.get('contact_refinements')} "
                     f"contact-zone refinements")
    if mesh and (mesh.get("adaptive_cycles") or 0) > 0:
        parts.append(f", then {mesh['adaptive_cycles']} adaptive cycles refining the "
                     f"{100 * (mesh.get('adaptive_fraction') or 0.2):.3g} % of cells with the "
                     f"largest Kelly indicators (the curve on the last mesh; each mesh in the "
                     f"case's adaptive_cycles.csv)")
    if dofs:
        parts.append(f" ({thousands(dofs)} DoFs for the first case)")
    parts.append(".</p>")
    diffs = []
    if loading != _paper.MODEL["loading"]:
        diffs.append(f"the paper displaced the nodes of the journal's axis (a line load, whose force "
                     f"drifts with the mesh in 3D); here {esc(LOADING_WORDS.get(loading, loading))}")
    if mu is not None and mu != _paper.MODEL["mu"]:
        diffs.append(f"the paper had Coulomb friction μ = {_paper.MODEL['mu']}; this run is "
                     f"{'frictionless' if mu == 0 else f'μ = {mu:g}'} (μ = 0.1 raises F by 0.3–0.5 %, "
                     f"docs/fe.md)")
    if sym and sym > 1:
        diffs.append("symmetry planes are used (the paper modelled the whole joint); the forces "
                     "shown are the full joint's")
    diffs.append("the material is linear elastic as in the paper's §3.1–3.3, but stresses above "
                 "the steel's yield stress are reported (below), not hidden")
    parts.append("<p><strong>How it differs from the paper.</strong> " + "; ".join(diffs) + ".</p>")
    return "".join(parts)


def force_figure(fs):
    sweep = fs.sweep
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11.5, 4.6))
    for case, law, _ in fs.cases:
        K, n = law["law"]["K"], law["law"]["n"]
        top = law["valid_range"]["delta_max"]
        # from a tenth of the range: below it the log–log panel would show a line without data
        xs = [top * (0.1 + 0.9 * i / 100) for i in range(101)]
        label = case_label(sweep, case)
        line, = ax1.plot([x * 1e3 for x in xs], [K * x ** n for x in xs], "-", label=label)
        ax2.plot([x * 1e3 for x in xs], [K * x ** n for x in xs], "-", color=line.get_color())
        d = law.get("diagnostics")
        if d:
            pts = [(x * 1e3, f) for x, f in zip(d["delta"], d["force"]) if x > 0 and f > 0]
            for ax in (ax1, ax2):
                ax.plot([p[0] for p in pts], [p[1] for p in pts], "o", ms=3, color=line.get_color())
    xs = [_paper.DELTA_MAX * (0.1 + 0.9 * i / 100) for i in range(101)]
    for ax in (ax1, ax2):
        ax.plot([x * 1e3 for x in xs], [_paper.tb4_force(x) for x in xs], "k--", lw=1.6,
                label="paper, t_B = 4 mm, aligned: 338240·δ^1.0114")
        ax.set_xlabel("penetration δ [mm]")
        ax.set_ylabel("contact force F [N]")
        ax.grid(True, which="both", alpha=0.3)
    ax2.set_xscale("log")
    ax2.set_yscale("log")
    readable_log_axis(ax2.xaxis)
    readable_log_axis(ax2.yaxis)
    ax1.set_title("linear")
    ax2.set_title("log–log (slope = n)")
    ax1.legend(fontsize=8)
    fig.tight_layout()
    return figure_html(fig, f"Sweep {esc(sweep['name'])}: FE data (points) and fits F = K·δ^n "
                            f"(lines) for every case, with the paper's t_B = 4 mm law (dashed). "
                            f"Forces are the full joint's.")


def fref_figure(fs):
    """F_ref and n against the parameter with the regression's 95 % interval and, for F_ref,
    the measured mesh error as a second, wider bar."""
    sweep = fs.sweep
    dref = fs.delta_ref()
    xs = fs.values_shown()
    F, F_hw, F_mesh, ns, n_lo, n_hi = [], [], [], [], [], []
    for _, law, _ in fs.cases:
        f, hw = f_ref_interval(law, dref)
        F.append(f)
        F_hw.append(hw or 0.0)
        e = mesh_error(law)
        F_mesh.append(f * e if e else 0.0)
        ns.append(law["law"]["n"])
        ci = get(law, "diagnostics", "n_ci95", default=[law["law"]["n"]] * 2)
        n_lo.append(law["law"]["n"] - ci[0])
        n_hi.append(ci[1] - law["law"]["n"])
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11.5, 4.3))
    if any(F_mesh):
        a1.errorbar(xs, F, yerr=F_mesh, fmt="none", ecolor="C1", elinewidth=8, alpha=0.35,
                    label="± measured mesh error of F (preset)")
    a1.errorbar(xs, F, yerr=F_hw, fmt="o-", color="C0", capsize=4,
                label="F_ref, 95 % interval of the fit")
    a2.errorbar(xs, ns, yerr=[n_lo, n_hi], fmt="s-", color="C3", capsize=4,
                label="n, 95 % interval of the fit")
    if sweep["parameter"] == "t_B":
        a1.plot([_paper.TB4_T_B * 1e3], [_paper.tb4_force(dref)], "k*", ms=12,
                label="paper t_B = 4 mm")
        px = sorted([_paper.TB4_T_B] + list(_paper.N_BY_T_B))
        pn = {**_paper.N_BY_T_B, _paper.TB4_T_B: _paper.TB4_N}
        a2.plot([x * 1e3 for x in px], [pn[x] for x in px], "k*", ms=12, label="paper (§3.1)")
    # (no paper line for θ: its aligned law, 16 344 N at 0.05 mm, is ~3× our tilted forces and
    # would flatten the trend this panel is for; the caption gives the number)
    a1.set_xlabel(param_axis_label(sweep))
    a1.set_ylabel(f"F_ref = F(δ = {dref * 1e3:.3g} mm) [N]")
    a2.set_xlabel(param_axis_label(sweep))
    a2.set_ylabel("exponent n [1]")
    for a in (a1, a2):
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    return figure_html(fig, f"F_ref — the force at the reference penetration δ_ref = "
                            f"{dref * 1e3:.3g} mm, comparable across laws with different n — and "
                            f"the exponent n against {esc(param_axis_label(sweep))}. K is not "
                            f"plotted: its unit N/m^n differs from law to law."
                            + ("" if sweep["parameter"] == "t_B" else
                               f" For scale: the paper's aligned t_B = 4 mm law gives "
                               f"{_paper.tb4_force(dref):.0f} N at this δ."))


def trend_finding(fs):
    """One sentence for the summary: our trend of F_ref over the parameter beside the paper's
    claim, or None with fewer than two cases."""
    claim = _paper.CLAIMS.get(fs.sweep["parameter"])
    dref = fs.delta_ref()
    Fs = [f_ref_interval(l, dref)[0] for _, l, _ in fs.cases]
    if len(Fs) < 2:
        return None
    sign, words = trend_words(Fs)
    xs = fs.values_shown()
    text = (f"<a href='#{esc(fs.anchor)}'>{esc(fs.sweep['name'])}</a>: F at δ = {dref * 1e3:.3g} mm "
            f"{words} over {esc(param_axis_label(fs.sweep))} = {xs[0]:.4g} … {xs[-1]:.4g} "
            f"({Fs[0]:.0f} → {Fs[-1]:.0f} N, {100 * (Fs[-1] - Fs[0]) / Fs[0]:+.1f} %)")
    if claim:
        expected, _ = claim
        if sign == expected:
            text += " — as the paper says"
        else:
            text += (" — <strong>the paper says it " + ("grows" if expected > 0 else "falls") +
                     "</strong>; our reading of why in the sweep's section")
    return text


def claim_table(fs):
    sweep = fs.sweep
    claim = _paper.CLAIMS.get(sweep["parameter"])
    dref = fs.delta_ref()
    Fs = [f_ref_interval(l, dref)[0] for _, l, _ in fs.cases]
    if len(Fs) < 2:
        return ""
    sign, words = trend_words(Fs)
    first, last = Fs[0], Fs[-1]
    change = 100 * (last - first) / first
    errs = [mesh_error(l) for _, l, _ in fs.cases]
    e = max([x for x in errs if x] or [0.0])
    ours = (f"F_ref {words} from {thousands(first)} N to {thousands(last)} N ({change:+.1f} %) over "
            f"{esc(param_axis_label(sweep))} = {fs.values_shown()[0]:.4g} … "
            f"{fs.values_shown()[-1]:.4g}")
    if e:
        steps = [abs(b - a) / a for a, b in zip(Fs, Fs[1:])]
        small = sum(1 for s in steps if s < 2 * e)
        ours += (f"; {small} of {len(steps)} steps are smaller than twice the measured mesh "
                 f"error ({100 * e:.3g} %)" if small else "")
    rows = ["<table><tr><th>quantity</th><th>the paper</th><th>this run</th><th>agree?</th>"
            "<th>why they differ</th></tr>"]
    if claim:
        expected, text = claim
        agree = sign == expected
        loading = get(fs.first_scene(), "loading", "journal", default="?")
        reason = "" if agree else reason_for(sweep, loading)
        rows.append(f"<tr><td>trend of F at fixed δ</td><td>{esc(text)}</td><td>{ours}</td>"
                    f"<td>{'yes' if agree else '<strong>no</strong>'}</td><td>{esc(reason)}</td></tr>")
    if sweep["parameter"] == "theta" and claim:
        # F(θ) itself beside the claim: each value and each step against the mesh error
        cells = []
        for (case, law, _), F in zip(fs.cases, Fs):
            e_case = mesh_error(law)
            cells.append(f"{esc(case_label(sweep, case))}: {thousands(F)} N"
                         + (f" (mesh ±{100 * e_case:.2g} %)" if e_case else ""))
        steps = [f"{100 * (b - a) / a:+.1f} %" for a, b in zip(Fs, Fs[1:])]
        rows.append(f"<tr><td>F at δ = {dref * 1e3:.3g} mm per θ, and each step</td>"
                    f"<td>{esc(claim[1])}</td><td>{'; '.join(cells)}; steps {', '.join(steps)}</td>"
                    f"<td>{'yes' if sign == claim[0] else '<strong>no</strong>'}</td>"
                    f"<td>the journal: {esc(LOADING_WORDS.get(get(fs.first_scene(), 'loading', 'journal', default='?'), '?'))}</td></tr>")
    if sweep["parameter"] == "t_B":
        for case, law, _ in fs.cases:
            if abs(case["value"] - _paper.TB4_T_B) < 1e-9:
                f, hw = f_ref_interval(law, _paper.DELTA_MAX)
                pf = _paper.tb4_force(_paper.DELTA_MAX)
                e = mesh_error(law)
                rows.append(
                    f"<tr><td>F at δ = 0.05 mm, t_B = 4 mm</td><td>{thousands(pf)} N</td>"
                    f"<td>{thousands(f)} N ({round(100 * (f - pf) / pf, 1) + 0.0:+.1f} %; fit ±{thousands(hw or 0)} N"
                    f"{f', mesh ±{100 * e:.3g} %' if e else ''})</td>"
                    f"<td>{'within the error' if abs(f - pf) <= (hw or 0) + (e or 0) * f else 'no'}</td>"
                    f"<td>paper: axis-line loading (its force falls with refinement, docs/fe.md: "
                    f"our axis_line gives +3.9 % on the default mesh), μ = 0.1 (+0.3–0.5 %), its "
                    f"own 3.12 % mesh error; ours: "
                    f"{esc(get(fs.first_scene(), 'loading', 'journal', default='?'))} loading, "
                    f"stiffer than a driven line</td></tr>")
                ci = get(law, "diagnostics", "n_ci95", default=[None, None])
                ci_txt = f" (95 %: {ci[0]:.4f} … {ci[1]:.4f})" if ci[0] is not None else ""
                rows.append(
                    f"<tr><td>exponent n, t_B = 4 mm</td><td>{_paper.TB4_N}</td>"
                    f"<td>{law['law']['n']:.4f}{ci_txt}</td>"
                    f"<td>{'yes' if ci[0] is not None and ci[0] <= _paper.TB4_N <= ci[1] else 'no'}</td>"
                    f"<td>our n is mesh-dependent (the contact zone widens by node rows, which the "
                    f"power law absorbs; docs/fe.md) and its 95 % interval is the regression's "
                    f"only</td></tr>")
    rows.append("</table>")
    return "<h4>The paper's claims beside ours</h4>" + "".join(rows)


def law_table(fs, base):
    sweep = fs.sweep
    dref = fs.delta_ref()
    rows = ["<table><tr><th>case</th><th>F = K·δ^n, δ in mm, F in N</th><th>K [N/m^n] (SI)</th>"
            "<th>n (95 %)</th><th>F_ref at δ_ref [N] (fit 95 %)</th><th>mesh error of F</th>"
            "<th>R²</th><th>files</th></tr>"]
    for case, law, _ in fs.cases:
        d = law.get("diagnostics") or {}
        n_ci = d.get("n_ci95", [float("nan")] * 2)
        f, hw = f_ref_interval(law, dref)
        e = mesh_error(law)
        links = [rel_link(case["law"], base, "law"),
                 rel_link(os.path.join(case["fe_dir"], "force_penetration.csv"), base, "CSV")]
        pvd = os.path.join(case["fe_dir"], "fields", "solution.pvd")
        if os.path.exists(pvd):
            links.append(rel_link(pvd, base, "fields (ParaView)"))
        if case.get("mesh"):
            links.append(rel_link(case["mesh"], base, "mesh"))
        rows.append(f"<tr><td>{esc(case_label(sweep, case))}</td>"
                    f"<td>{law['mm_N']['K']:.6g}·δ^{law['law']['n']:.4f}</td><td>{law['law']['K']:.5g}</td>"
                    f"<td>{law['law']['n']:.4f} ({n_ci[0]:.4f} … {n_ci[1]:.4f})</td>"
                    f"<td>{f:.5g} ± {hw or 0:.3g}</td>"
                    f"<td>{f'± {100 * e:.3g} %' if e else 'not measured'}</td>"
                    f"<td>{d.get('r_squared', float('nan')):.6f}</td><td>{' · '.join(links)}</td></tr>")
    rows.append("</table>")
    fam = sweep.get("family")
    if fam:
        rows.append(f"<p>Law family over {esc(sweep['parameter'])} (parameter in "
                    f"{esc(sweep.get('family_unit', sweep['unit']))}, SI): {rel_link(fam, base)}.</p>")
    return "".join(rows)


def picture_case(fs):
    """The case drawn for the sweep: t_B = 4 mm (the paper's bearing), θ = 2.5° (Fig. 7b)."""
    want = {"t_B": 0.004, "theta": 2.5}.get(fs.sweep["parameter"])
    best = None
    for case, law, man in fs.cases:
        if not os.path.exists(os.path.join(case["fe_dir"], "fields", "solution.pvd")):
            continue
        score = abs(case["value"] - want) if want is not None else 0
        if best is None or score < best[0]:
            best = (score, case, law, man)
    return best[1:] if best else None


def yield_check(case, man, picture_stats):
    """The yield check of one case: the manifest's `yield_check` block when fe_stage writes one
    (keys below), else the report's own from the VTU. Returns (dict, where-it-came-from)."""
    y = get(man, "extra", "yield_check")
    if isinstance(y, dict) and isinstance(y.get("bodies"), list) and y["bodies"]:
        # fe_stage's block: per body (bearing, journal) its volume, volume above yield and
        # largest von Mises with its place (full-body volumes)
        bodies = y["bodies"]
        worst = max(bodies, key=lambda b: value_of(b.get("max_von_mises"), 0.0))
        above = sum(value_of(b.get("volume_above_yield"), 0.0) for b in bodies)
        total = sum(value_of(b.get("volume"), 0.0) for b in bodies)
        bearing = [b for b in bodies if b.get("body") == "bearing"]
        loc = worst.get("max_location")
        loc = loc.get("value") if isinstance(loc, dict) else loc
        where = None
        if isinstance(loc, list) and len(loc) == 3:
            where = (f"largest in the {worst.get('body')} at ("
                     + ", ".join(f"{c * 1e3:.3g}" for c in loc) + ") mm")
        return {"yield_stress": value_of(y.get("yield_stress")),
                "max_von_mises": value_of(worst.get("max_von_mises")),
                "volume_above_yield": above,
                "volume_above_yield_bearing":
                    value_of(bearing[0].get("volume_above_yield")) if bearing else None,
                "volume_fraction_above_yield": above / total if total > 0 else None,
                "where": where}, "fe_stage manifest"
    if isinstance(y, dict):
        return {"yield_stress": value_of(y.get("yield_stress")),
                "max_von_mises": value_of(y.get("max_von_mises")),
                "volume_above_yield": value_of(y.get("volume_above_yield")),
                "volume_above_yield_bearing": value_of(y.get("volume_above_yield_bearing")),
                "volume_fraction_above_yield": value_of(y.get("volume_fraction_above_yield")),
                "where": y.get("location") or y.get("where")}, "fe_stage manifest"
    if picture_stats and "max_von_mises" in picture_stats:
        s = picture_stats
        frac = s["volume_above_yield"] / s["volume_total"] if s.get("volume_total") else None
        where = None
        if s.get("above_yield_box"):
            lo, hi = s["above_yield_box"]
            where = ("cells with centres in x " + f"{lo[0] * 1e3:.3g}…{hi[0] * 1e3:.3g}, y "
                     f"{lo[1] * 1e3:.3g}…{hi[1] * 1e3:.3g}, z {lo[2] * 1e3:.3g}…{hi[2] * 1e3:.3g} mm")
        return {"yield_stress": s["yield_stress"], "max_von_mises": s["max_von_mises"],
                "volume_above_yield": s["volume_above_yield"],
                "volume_above_yield_bearing": s.get("volume_above_yield_bearing"),
                "volume_fraction_above_yield": frac, "where": where}, \
            "computed by the report from the last increment's VTU"
    return None, None


def contact_field_notes(stats, mu, label, warnings, anchor):
    """Checks of what an Abaqus user reads into CPRESS/CSHEAR/CSTATUS/CSLIP (issue 15 item 4),
    from the fields: a frictionless run should show zero shear and no 'stick' status, a
    frictional one shear within Coulomb's cone (|t_T| ≤ μ p), and both slip only where in
    contact."""
    if not stats or mu is None:
        return ""
    issues = []
    if mu == 0:
        if stats.get("max_contact_shear", 0) > 0:
            issues.append(f"contact_shear reaches {stats['max_contact_shear'] / 1e6:.4g} MPa "
                          f"({stats.get('max_shear_over_pressure', 0):.3g}× the pressure) in a "
                          f"frictionless run")
        if stats.get("n_stick_points", 0) > 0:
            issues.append(f"contact_status = stick at {stats['n_stick_points']} of "
                          f"{stats.get('n_active_points', 0)} active points in a frictionless run")
    elif stats.get("max_shear_over_pressure", 0) > mu * (1 + 1e-4):
        # Coulomb's cone |t_T| ≤ μ p: fe_stage converges the slip law to 1e-6 of the largest
        # nodal force, and the VTU stores floats (~1e-7), so 1e-4 is far above both
        issues.append(f"contact_shear exceeds μ·p: up to {stats['max_shear_over_pressure']:.4g} × "
                      f"the pressure with μ = {mu:g}")
    if stats.get("n_slip_points_not_in_contact", 0) > 0:
        issues.append(f"contact_slip is non-zero at {stats['n_slip_points_not_in_contact']} points "
                      f"not in contact")
    if not issues:
        return "<p>Contact fields: consistent (" + \
            ("zero shear, no stick status" if mu == 0 else
             f"friction within Coulomb's cone, shear ≤ {stats.get('max_shear_over_pressure', 0):.4g} × "
             f"pressure with μ = {mu:g}, {stats.get('n_stick_points', 0)} of "
             f"{stats.get('n_active_points', 0)} active points stick") + \
            ", slip only where in contact).</p>"
    warnings.add(f"FE fields, {label}", "; ".join(esc(i) for i in issues) +
                 " — read contact_shear/status/slip with care", anchor)
    return "<p class='warn'>Contact fields: " + "; ".join(esc(i) for i in issues) + \
        ". These fields do not yet mean what CSHEAR/CSTATUS/CSLIP mean in Abaqus.</p>"


def scene_yield_stress(man):
    """The yield stress the case is checked against [Pa]: the one its scene names
    (material.yield_stress; fe_stage writes its default there too), else SPEC §2's."""
    ys = value_of(get(man, "extra", "scene", "material", "yield_stress"))
    return ys if isinstance(ys, (int, float)) and ys > 0 else _paper.YIELD_STRESS


_FIELD_STATS = {}


def cached_field_stats(case, man, warnings, anchor, stick_code=2):
    """fields.field_stats of a case's last increment, read once per report (None without
    fields or when they cannot be read — then a warning says so)."""
    key = (case["fe_dir"], stick_code)
    if key not in _FIELD_STATS:
        from plotting import fields
        sym = value_of(get(man, "extra", "symmetry_factor"), 1.0)
        mu = get(man, "extra", "scene", "contact", "mu")
        R_B = get(man, "extra", "scene", "geometry", "R_B")
        try:
            _FIELD_STATS[key] = fields.field_stats(case["fe_dir"], scene_yield_stress(man), sym,
                                                   mu, stick_code, R_B)
        except Exception as e:  # a broken VTU must not take the report down: say so instead
            warnings.add(f"FE fields, {case['fe_dir']}", f"could not be read ({esc(str(e))})", anchor)
            _FIELD_STATS[key] = None
    return _FIELD_STATS[key]


def yield_section(fs, warnings):
    """Every case's largest von Mises stress and volume above the yield stress (fe_stage's
    manifest block when present, else the report's own from the VTU), and one warning for the
    sweep when any case exceeds it."""
    rows, above, limits = [], [], set()
    for case, law, man in fs.cases:
        stats = None if isinstance(get(man, "extra", "yield_check"), dict) else \
            cached_field_stats(case, man, warnings, fs.anchor)
        y, source = yield_check(case, man, stats)
        if not y or y.get("max_von_mises") is None:
            rows.append(f"<tr><td>{esc(case_label(fs.sweep, case))}</td><td colspan='5'>no fields, "
                        f"no yield check in the manifest</td></tr>")
            continue
        ys = y["yield_stress"] or scene_yield_stress(man)
        limits.add(ys)
        vm, vol, frac = y["max_von_mises"], y.get("volume_above_yield"), y.get("volume_fraction_above_yield")
        vb = y.get("volume_above_yield_bearing")
        if vm > ys:
            above.append((case, vm, vol, frac, ys))
        rows.append(f"<tr><td>{esc(case_label(fs.sweep, case))}</td><td>{vm / 1e6:.0f}</td>"
                    f"<td>{f'{vol * 1e9:.4g}' if vol is not None else '–'}</td>"
                    f"<td>{f'{vb * 1e9:.4g}' if vb is not None else '–'}</td>"
                    f"<td>{f'{100 * frac:.3g} %' if frac is not None else '–'}</td>"
                    f"<td>{esc(source)}</td></tr>")
    if not rows:
        return ""
    if above:
        vms = [a[1] for a in above]
        vols = [a[2] for a in above if a[2] is not None]
        yss = sorted({a[4] for a in above})  # the scene may name its own yield stress
        ys_txt = " / ".join(f"{y / 1e6:.4g}" for y in yss)
        warnings.add(f"FE {fs.sweep['name']}",
                     f"stress above the yield stress {ys_txt} MPa in "
                     f"{len(above)} of {len(fs.cases)} cases: largest von Mises "
                     f"{min(vms) / 1e6:.0f} … {max(vms) / 1e6:.0f} MPa"
                     + (f", up to {max(vols) * 1e9:.4g} mm³ of the joint above it" if vols else "")
                     + "; the model is linear elastic, so the force there is an upper bound",
                     fs.anchor)
    own = sorted(y for y in limits if abs(y - _paper.YIELD_STRESS) > 1e-6 * _paper.YIELD_STRESS)
    limit_txt = (f"the paper's steel yields at {_paper.YIELD_STRESS / 1e6:.4g} MPa (SPEC §2, first "
                 f"point of the hardening table)")
    if own:
        limit_txt += (f"; these cases were checked against the yield stress their scene names "
                      f"(material.yield_stress): {' / '.join(f'{y / 1e6:.4g}' for y in sorted(limits))} MPa")
    return ("<h4>Yield check</h4><p>The FE model is linear elastic; " + limit_txt + ". "
            "Where von Mises exceeds it the real joint would yield and carry less force: the laws "
            "hold only while that zone stays small.</p>"
            "<table><tr><th>case</th><th>largest von Mises [MPa]</th><th>volume above yield, "
            "full joint [mm³]</th><th>of which in the bearing [mm³]</th><th>share of the "
            "modelled volume</th><th>from</th></tr>" +
            "".join(rows) + "</table>")


# The VTK pictures: `plot.py fields`, a process of ~2-3 s each. start_pictures() starts every
# picture the report will show when it begins, so that they render beside each other and beside
# the report's own work (~5 s of a ~20 s report on 2 cores); each section then waits for its
# own (render_picture). {png: (process, its stderr in a temporary file)}
_STARTED_PICTURES = {}
PLOT_PY = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "plot.py")


def _start_picture(png, args):
    os.makedirs(os.path.dirname(png), exist_ok=True)
    err = tempfile.TemporaryFile(mode="w+")  # not a pipe: a chatty VTK cannot block on it
    return subprocess.Popen([sys.executable, PLOT_PY, "fields"] + args,
                            stdout=subprocess.DEVNULL, stderr=err, text=True), err


def render_picture(png, args):
    """Waits for the picture start_pictures() started for `png`, else renders it now. Returns
    (written, the renderer's stderr)."""
    proc, err = _STARTED_PICTURES.pop(png, None) or _start_picture(png, args)
    with err:
        proc.wait()
        err.seek(0)
        text = err.read()
    return proc.returncode == 0 and os.path.exists(png), text


def _picture_scales(man):
    """`plot.py fields`'s --bore-radius and --yield-stress from a case's FE manifest, None when
    it names no bore radius (R_B)."""
    R_B = get(man, "extra", "scene", "geometry", "R_B")
    if not R_B:
        return None
    ys = value_of(get(man, "extra", "yield_check", "yield_stress")) or scene_yield_stress(man)
    return ["--bore-radius", repr(R_B), "--yield-stress", repr(ys)]


def field_picture(fs, run_dir, case, man):
    """The picture of the sweep's drawn case: (png, plot.py fields arguments), the arguments
    None when the manifest names no bore radius (R_B)."""
    png = os.path.join(run_dir, "pictures", f"{fs.sweep['name']}_fields.png")
    scales = _picture_scales(man)
    if scales is None:
        return png, None
    label = case_label(fs.sweep, case)
    return png, [case["fe_dir"], "--output", png] + scales + [
        # VTK's default font has no Greek letters
        "--title", f"{fs.sweep['name']}: {label.replace('θ', 'theta').replace('°', ' deg')}"]


def fig7_case(fs, theta):
    """(case, manifest) of the misalignment sweep at θ = theta [deg], or None."""
    pick = [(c, m) for c, _, m in fs.cases
            if abs(shown(c["value"], fs.sweep["unit"])[0] - theta) < 1e-9]
    return pick[0] if pick else None


def fig7_picture(fs, run_dir, case, man, theta, panel):
    """The side cut of the paper's Fig. 7 (panel a or b) at θ = theta: (png, arguments), the
    arguments None without R_B."""
    png = os.path.join(run_dir, "pictures", f"{fs.sweep['name']}_fig7{panel}.png")
    scales = _picture_scales(man)
    if scales is None:
        return png, None
    return png, [case["fe_dir"], "--cut", "--output", png] + scales + [
        "--title", f"{fs.sweep['name']}: theta = {theta:g} deg (paper Fig. 7{panel})"]


def start_pictures(sweeps, run_dir):
    """Starts the pictures sweep_section() will show for these sweeps (pipeline_summary.json's
    `sweeps`): each sweep's drawn case and, over θ, the two Fig. 7 cuts."""
    from plotting import fields
    for sweep in sweeps:
        fs = FeSweep(sweep)
        jobs = []
        pick = picture_case(fs)
        if pick:
            jobs.append(field_picture(fs, run_dir, pick[0], pick[2]))
        if sweep["parameter"] == "theta":
            for theta, panel in FIG7_THETAS:
                c = fig7_case(fs, theta)
                if c and fields.last_field_file(c[0]["fe_dir"]) is not None:
                    jobs.append(fig7_picture(fs, run_dir, c[0], c[1], theta, panel))
        for png, args in jobs:
            if args and png not in _STARTED_PICTURES:
                _STARTED_PICTURES[png] = _start_picture(png, args)


def pictures_and_checks(fs, run_dir, warnings):
    pick = picture_case(fs)
    if not pick:
        return "<p>No field files (VTU) to draw: the FE cases were run without fields.</p>", None
    case, law, man = pick
    label = case_label(fs.sweep, case)
    from plotting import fields
    sym = value_of(get(man, "extra", "symmetry_factor"), 1.0)
    mu = get(man, "extra", "scene", "contact", "mu")
    stats = None
    # fe_stage may name its status codes (manifest extra.contact_fields.status_codes, either
    # {"stick": 1, ...} or {"1": "stick", ...}); fe_stage's codes (Abaqus's): 0 open, 1 slip, 2 stick
    codes = get(man, "extra", "contact_fields", "status_codes", default={}) or {}
    stick_code = 2
    for k, v in codes.items():
        if k == "stick" and isinstance(v, (int, float)):
            stick_code = int(v)
        elif v == "stick" and str(k).lstrip("-").isdigit():
            stick_code = int(k)
    stats = cached_field_stats(case, man, warnings, fs.anchor, stick_code)
    out = []
    png, args = field_picture(fs, run_dir, case, man)
    rendered = False
    if args:
        rendered, err = render_picture(png, args)
        if not rendered:
            warnings.add(f"pictures, {label}", "not rendered: " + esc(err.strip()[-300:]),
                         fs.anchor)
    else:
        warnings.add(f"pictures, {label}", "not rendered: the FE manifest's scene names no "
                                           "geometry.R_B (the bore, where the contact is)", fs.anchor)
    if rendered:
        out.append(image_file_html(
            png, f"{esc(fs.sweep['name'])}, {esc(label)}, δ = "
                 f"{get(man, 'extra', 'scene', 'loading', 'delta_max', default=0) * 1e3:.3g} mm "
                 f"(last increment), rendered off-screen with VTK from "
                 f"{esc(os.path.relpath(fields.last_field_file(case['fe_dir']), run_dir))}: the mesh, von "
                 f"Mises stress on the symmetry plane x = 0 near the contact (the paper's Fig. 7 "
                 f"shows the radial normal stress"
                 + (", drawn below for θ = 1° and 2.5°" if fs.sweep["parameter"] == "theta" else "")
                 + f"; open the .pvd in ParaView for any other component), contact pressure on "
                 f"the bore."))
    y, source = yield_check(case, man, stats)
    if y and y.get("max_von_mises") is not None:
        ys = y["yield_stress"] or scene_yield_stress(man)
        vm = y["max_von_mises"]
        vol = y.get("volume_above_yield")
        frac = y.get("volume_fraction_above_yield")
        source_of_ys = ("SPEC §2, first point of the hardening table"
                        if abs(ys - _paper.YIELD_STRESS) <= 1e-6 * _paper.YIELD_STRESS
                        else "the scene's material.yield_stress")
        text = (f"largest von Mises stress {thousands(vm / 1e6)} MPa against the yield stress "
                f"{ys / 1e6:.4g} MPa ({source_of_ys})")
        if vm > ys:
            extra = ""
            if vol is not None:
                extra = f"; {vol * 1e9:.4g} mm³ of the full joint above it"
                if frac is not None:
                    extra += f" ({100 * frac:.3g} % of the modelled volume)"
            if y.get("where"):
                extra += f", {y['where']}"
            out.append(f"<p class='warn'><strong>Yield check ({esc(label)}, {esc(source)}):</strong> "
                       f"{text}{extra}. The model is linear elastic: where the stress exceeds the "
                       f"yield stress the real steel would yield and the force would be lower; the "
                       f"law is valid only as far as that zone stays small.</p>")
        else:
            out.append(f"<p>Yield check ({esc(label)}, {esc(source)}): {text}: elastic everywhere.</p>")
    out.append(contact_field_notes(stats, mu, label, warnings, fs.anchor))
    return "".join(out), stats


# The paper's Fig. 7: the radial normal stress in the side cut at θ = 1° (a) and 2.5° (b).
FIG7_THETAS = ((1.0, "a"), (2.5, "b"))


def fig7_cuts(fs, run_dir, warnings):
    """The misalignment sweep's counterpart of the paper's Fig. 7: for θ = 1° and 2.5° (the
    cases at those values, when they have fields), the radial normal stress beside von Mises on
    the plane x = 0 (`plot.py fields --cut`), written to pictures/<sweep>_fig7<a|b>.png."""
    from plotting import fields
    out = []
    for theta, panel in FIG7_THETAS:
        pick = fig7_case(fs, theta)
        if not pick:
            out.append(f"<p>Fig. 7{panel} (θ = {theta:g}°): no case at this θ in the sweep.</p>")
            continue
        case, man = pick
        label = case_label(fs.sweep, case)
        if fields.last_field_file(case["fe_dir"]) is None:
            out.append(f"<p>Fig. 7{panel} ({esc(label)}): the case was run without fields.</p>")
            continue
        png, args = fig7_picture(fs, run_dir, case, man, theta, panel)
        rendered, err = render_picture(png, args) if args else (False, "")
        if not rendered:
            why = ("the FE manifest's scene names no geometry.R_B" if not args
                   else err.strip()[-300:])
            warnings.add(f"pictures, Fig. 7{panel}", "not rendered: " + esc(why), fs.anchor)
            continue
        loading = get(man, "extra", "scene", "loading", "journal", default="?")
        out.append(image_file_html(
            png, f"The paper's Fig. 7{panel}, {esc(label)}: the radial normal stress σ_rr = n·σ·n "
                 f"(n radial from the bearing's axis; negative: compression) beside von Mises, on "
                 f"the symmetry plane x = 0 near the contact, at δ = "
                 f"{get(man, 'extra', 'scene', 'loading', 'delta_max', default=0) * 1e3:.3g} mm "
                 f"(last increment), {esc(LOADING_WORDS.get(loading, loading))}. The paper shows "
                 f"σ_rr in MPa on its own scale; ours is symmetric about 0 at the 95th percentile "
                 f"of |σ_rr| on the cut, saturated beyond (the colour bar gives the peak: the "
                 f"journal's rim is a corner, whose peak grows with the mesh)."))
    return "<h4>The paper's Fig. 7: radial normal stress in the side cut</h4>" + "".join(out)


def per_case_details(fs, base):
    out = []
    for case, law, man in fs.cases:
        label = case_label(fs.sweep, case)
        body = []
        status = get(man, "status", default="missing")
        wall = value_of(get(man, "wall_time"))
        body.append(f"<p>fe_stage: {esc(str(status))}"
                    + (f", {wall:.1f} s" if wall else "")
                    + f"; {rel_link(os.path.join(case['fe_dir'], 'stage.log'), base, 'log')} · "
                      f"{rel_link(os.path.join(case['fe_dir'], 'manifest.json'), base, 'manifest')}</p>")
        pngs = [os.path.join(case["fe_dir"], "force_penetration.png")] + \
            sorted(glob.glob(os.path.join(os.path.dirname(case["law"]), "*.png")))
        for png in pngs:
            if os.path.exists(png):
                kind = "FE force–penetration (linear and log–log)" if "force_pen" in png \
                    else "fit: data, law and residuals"
                body.append(image_file_html(png, f"{esc(label)}: {kind}"))
        out.append(details(f"{esc(label)}: F(δ_max) = "
                           f"{thousands(value_of(get(man, 'extra', 'force_at_delta_max'), float('nan')))} N, "
                           f"n = {law['law']['n']:.4f} — per-case plots and files",
                           "".join(body)))
    fam_png = os.path.splitext(fs.sweep.get("family") or "")[0] + ".png"
    if fs.sweep.get("family") and os.path.exists(fam_png):
        out.append(details(f"law family over {esc(fs.sweep['parameter'])}: plot",
                           image_file_html(fam_png, "law family: members and F_ref, n")))
    return "".join(out)


def fe_case_warnings(fs, warnings):
    for case, law, man in fs.cases:
        label = f"FE {fs.sweep['name']}, {case_label(fs.sweep, case)}"
        status = get(man, "status")
        if status != "complete":
            warnings.add(label, f"fe_stage status {esc(str(status))}: "
                                f"{esc(str(get(man, 'message', default='')))}", fs.anchor)
        r2 = get(law, "diagnostics", "r_squared")
        if r2 is not None and r2 < 0.999:
            warnings.add(label, f"R² = {r2:.5f} < 0.999 (the paper's criterion): the data do "
                                f"not follow one power law well", fs.anchor)


def sweep_section(sweep, base, warnings, preset_error=None):
    """`preset_error`: the chosen preset's measured error of F(δ_max) for this sweep
    ({percent, where}, or None where the preset states none)."""
    fs = FeSweep(sweep)
    head = (f"<h2 id='{esc(fs.anchor)}'>FE sweep “{esc(sweep['name'])}”: contact force over "
            f"{esc(param_axis_label(sweep))}</h2>")
    if not fs.cases:
        warnings.add(f"FE {sweep['name']}", "no fitted laws found", fs.anchor)
        return head + "<p>No fitted laws found.</p>", fs
    fe_case_warnings(fs, warnings)
    pictures, _ = pictures_and_checks(fs, base, warnings)
    parts = [head, modelled_paragraph(fs), force_figure(fs), fref_figure(fs), claim_table(fs),
             own_estimate_section(fs, preset_error), "<h4>Fields</h4>", pictures,
             fig7_cuts(fs, base, warnings) if sweep["parameter"] == "theta" else "",
             yield_section(fs, warnings), "<h4>Laws</h4>",
             law_table(fs, base),
             "<h4>Every case</h4>", per_case_details(fs, base)]
    return "".join(parts), fs
