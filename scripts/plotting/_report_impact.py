"""The report's impact section (issues 12, 31): the FE impact sweep per case (velocity × journal
mass) — peak force, impulse, mean force, δ_max, contact time, restitution, the dynamic gap at the
peak, energy left in the bearing; what does not change across the sweep stated once — the
paper's two claims on the gap beside our numbers, Fig. 5a and 5b, each case's F(t), δ(t), F(δ)
and energy plot folded away, and, where impact_compare ran, the MBD laws' comparison (the law of
the same journal and mesh, c_e with its error bar from Δt and mesh). A restitution ≥ 1 is flagged
beside its value: the time step's resolution, not an energy gain (its c_e unreachable).

Two variants may have run (issue 31 item 2): the rigid journal (summary `impact`, section
#impact) and the deformable, free journal (summary `impact_deformable`, #impact_deformable); each
gets its section, and where both ran, a table sets them side by side at the velocities and the
journal mass they share. Each section names the time integrator (Abaqus's application, HHT α, β,
γ) as the FE stage wrote it."""
import os

from plotting._common import read_table
from plotting._impact_sweep import case_folders, paper_claims, read_sweep, split_quantities
from plotting._report_common import details, esc, image_file_html, load_or_none, rel_link

# [1] How far above 1 a restitution is still the time step's resolution. A heavy journal meets
# the ring quasi-statically, e → 1, and the fast preset's Δt = T_c/40 resolves e only to ~1.3e-3:
# the 25 kg journal gave 1.00126 at T_c/40 against 0.99996 at T_c/80 (docs/benchmarks.md,
# issue 31). Beyond 1 + 5e-3 (the end-to-end test's bound) the step would be creating energy.
E_RESOLUTION = 5e-3


def steps_per_period(s, i):
    """T_c/Δt of case i (the contact period over the time step), or None if not in the table."""
    dt, period = s.get("time_step_s"), s.get("contact_period_s")
    if not dt or not period or i >= len(dt) or not dt[i] > 0:
        return None
    return period[i] / dt[i]


def restitution_flag(e, steps):
    """HTML beside a restitution ≥ 1 saying what it is (the time step's resolution, or beyond
    it); "" below 1. `steps`: T_c/Δt of the case, or None."""
    if not e >= 1.0:
        return ""
    dt = f" (Δt = T_c/{steps:.0f})" if steps else ""
    if e < 1.0 + E_RESOLUTION:
        return (f" <span class='flag'>e ≥ 1: within the time step's resolution{dt}, not an "
                "energy gain; rerun with a finer impact time step</span>")
    return (f" <span class='flag'>e = {e:.4f} is beyond the time step's resolution{dt}: the "
            "journal left with more energy than it brought; check the case's energy balance "
            "and rerun with a finer impact time step</span>")


def journal_of(impact):
    """The variant's journal: the summary's `journal` (loading.journal: rigid, end_faces,
    axis_line), else the first case's manifest's scene, else rigid (runs before issue 31
    item 2 had the rigid journal only)."""
    if impact.get("journal"):
        return impact["journal"]
    sweep = impact.get("sweep")
    if sweep and os.path.exists(sweep):
        for c in case_folders(sweep):
            man = load_or_none(os.path.join(c, "manifest.json")) or {}
            j = man.get("extra", {}).get("scene", {}).get("loading", {}).get("journal")
            if j:
                return j
    return "rigid"


def integrator_html(sweep):
    """The time integrator as the FE stage wrote it: the application's name from the first
    case's manifest (extra.scene.impact.application, defaults resolved) and the scheme with its
    α, β, γ from the first comment line of its impact_history.csv ("Abaqus application
    moderate_dissipation: HHT alpha = …, beta = …, gamma = …"); "" when neither is there."""
    folders = case_folders(sweep) if sweep and os.path.exists(sweep) else []
    if not folders:
        return ""
    man = load_or_none(os.path.join(folders[0], "manifest.json")) or {}
    application = man.get("extra", {}).get("scene", {}).get("impact", {}).get("application")
    scheme = ""
    history = os.path.join(folders[0], "impact_history.csv")
    if os.path.exists(history):
        with open(history) as f:
            first = f.readline()
        at = first.find("Abaqus application ")
        if at >= 0:
            scheme = first[at + len("Abaqus application "):].strip()
    if not application and not scheme:
        return ""
    text = scheme or esc(application)
    alpha = man.get("extra", {}).get("impact", {}).get("alpha")
    if not scheme and alpha is not None:
        text += f" (HHT α = {alpha:.5g})"
    return (f"<p><strong>Time integration</strong>: Abaqus/Standard's application "
            f"<code>{esc(text)}</code> (<code>impact.application</code>: "
            "transient_fidelity | moderate_dissipation | quasi_static; the paper ran moderate "
            "dissipation, docs/fe.md).</p>")


def is_deformable(journal):
    return journal not in ("rigid", None)


def impact_section(impact, base, warnings, anchor="impact"):
    """HTML of one impact section (`anchor`: impact, or impact_deformable for the variant with
    the deformable journal), or "" if the run has no such study."""
    if not impact:
        return ""
    fe_dir = impact["fe_dir"]
    journal = journal_of(impact)
    deformable = is_deformable(journal)
    label = "impact, deformable journal" if deformable else "impact"
    if deformable:
        head = (f"<h2 id='{anchor}'>FE impact study (paper §3.2): both bodies deformable</h2>"
                "<p>As the paper modelled it: the journal is meshed and free (loading.journal: "
                f"{esc(journal)}), its mass the FE mass matrix's, coupled to the bore by dual "
                "mortar; it is launched at first touch toward the bearing (t_B as in the scene) "
                "and followed through the impact by Hilber–Hughes–Taylor α implicit dynamics, "
                "with the contact nodes of the bore massless (docs/fe.md). The sweep runs the "
                "impact velocities at the journal's own mass (a deformable journal's mass is its "
                "mesh's: no journal-mass sweep; the heavier journals are the rigid one's). Beside "
                "each impact, the quasi-static curve of the same journal and mesh, pushed at its "
                "end faces: the dynamic peak is compared with the quasi-static force at the same "
                "δ (the dynamic gap); δ is the journal's centre of mass's displacement.</p>")
    else:
        head = (f"<h2 id='{anchor}'>FE impact study (paper §3.2)"
                + (": rigid journal" if journal == "rigid" else "") + "</h2>"
                "<p>The journal is launched at first touch toward the bearing (t_B as in the "
                "impact scene) and followed through the impact by Hilber–Hughes–Taylor α implicit "
                "dynamics, with the exact active-set contact at every step and the contact nodes "
                "massless (docs/fe.md). The sweep runs every impact velocity with every journal "
                "mass (sweep.velocity × sweep.journal_mass: a heavier journal stands for the mass "
                "a mechanism puts on the pin), so that δ_max spans the quasi-static studies' "
                "range. Beside each impact, the quasi-static curve of the same journal and mesh: "
                "the dynamic peak is compared with the quasi-static force at the same δ (the "
                "dynamic gap).</p>")
    parts = [head]
    sweep = impact.get("sweep")
    if not sweep or not os.path.exists(sweep):
        warnings.add(f"{label} study", f"no sweep table in {esc(fe_dir)} (did the FE task "
                     "fail?)", anchor)
        return "\n".join(parts)
    parts.append(integrator_html(sweep))
    s = read_sweep(sweep)
    parts.append(case_table(s, warnings, label, anchor))
    parts.append(claims_html(s))
    for name, caption in [
            ("fig5a.png", "The paper's Fig. 5a: every case's F(δ) through the impact over the "
                          "quasi-static curve of the same journal and mesh (log–log)"),
            ("fig5b.png", "The paper's Fig. 5b as we read it: the peak force against the impact "
                          "velocity beside the quasi-static force at the peak's δ, and the gap"),
            ("impact_sweep.png", "Impact sweep: the quantities that change across the cases")]:
        png = os.path.join(fe_dir, name)
        if os.path.exists(png):
            parts.append(image_file_html(png, caption))
    cases = [os.path.basename(f) for f in case_folders(sweep)]
    for c in cases:
        # the linear-elastic model's validity at the peak force (its yield check)
        man = load_or_none(os.path.join(fe_dir, c, "manifest.json")) or {}
        yc = man.get("extra", {}).get("yield_check", {})
        if yc.get("exceeded"):
            worst = max(yc.get("bodies", []), key=lambda b: b["max_von_mises"]["value"],
                        default=None)
            if worst:
                warnings.add(f"{label} {esc(c)}",
                             f"von Mises reaches {worst['max_von_mises']['value'] / 1e6:.4g} MPa "
                             f"in the {esc(worst['body'])} at the peak force, above the yield "
                             f"stress {yc['yield_stress']['value'] / 1e6:.4g} MPa: the linear-"
                             "elastic result is not valid there", anchor)
    for c in cases:
        img = os.path.join(fe_dir, c, "impact.png")
        if os.path.exists(img):
            parts.append(details(f"{esc(c)}: F(t), δ(t), F(δ), energy balance",
                                 image_file_html(img, f"{esc(c)}: impact history "
                                                      f"({rel_link(os.path.join(fe_dir, c), base)})")))
    compare = impact.get("compare_dir")
    if compare and os.path.isdir(compare):
        parts.append("<h3>Against the MBD contact laws</h3>")
        for name in sorted(os.listdir(compare)):
            if name.endswith(".png"):
                parts.append(image_file_html(os.path.join(compare, name),
                                             f"FE impact against the MBD law ({esc(name)})"))
        man = load_or_none(os.path.join(compare, "manifest.json"))
        if man is None:
            warnings.add(f"{label} comparison", "no manifest in " + esc(compare), anchor)
            return "\n".join(parts)
        fits = man.get("extra", {}).get("fitted_restitution_coefficient", {})
        extra = man.get("extra", {})
        own = extra.get("law_source") == "own_quasi_static_curve"
        bar_from = extra.get("error_bar_from", {}).get("error_bar", "none given")
        if fits:
            rows = ["<p>The c_e with which each damping model's single impact (the journal's "
                    "mass on the MBD law, bearing rigid) returns the FE restitution"
                    + (" of the deformable journal" if deformable else "") + ". The law: "
                    + ("each case's own quasi-static curve (the same journal and mesh as the "
                       "impact), fitted F = K δ^n" if own else
                       "the law file given (not the impact's own curve)")
                    + f". Error bar: {esc(bar_from)}.</p><table>"
                    "<tr><th>damping model</th><th>c_e (mean over the cases where it is "
                    "reachable)</th>"
                    "<th>spread over the cases</th><th>error bar (Δt, mesh)</th></tr>"]
            for name, f in sorted(fits.items()):
                bar = f.get("error_bar")
                rows.append(f"<tr><td>{esc(name)}</td><td>{f['c_e_mean']:.5f}</td>"
                            f"<td>{f.get('spread_over_cases', f['spread_over_v']):.2g}</td>"
                            f"<td>{'—' if bar is None or not extra.get('error_bar_from', {}).get('levels') else f'± {bar:.2g}'}</td></tr>")
            rows.append("</table>")
            parts.append("".join(rows))
        parts.append(fitted_per_case(os.path.join(compare, "restitution_fit.csv")))
    return "\n".join(parts)


def fitted_per_case(path):
    """The cases without a c_e said in words (restitution_fit.csv writes −1 for them), and each
    case's fitted c_e folded away, "unreachable" where it is −1; "" without the table."""
    if not os.path.exists(path):
        return ""
    _, _, f = read_table(path)
    models = [k[4:] for k in f if k.startswith("c_e_") and not k.endswith("_error_bar")]
    n = len(f.get("v_in", []))
    if not models or not n or "fe_restitution" not in f:
        return ""
    mass = f.get("journal_mass", [None] * n)

    def case(i):
        return f"v = {f['v_in'][i]:.3g} m/s" + (f", m = {mass[i]:.4g} kg" if mass[i] else "")

    def cell(i, model):
        c = f["c_e_" + model][i]
        if c > 0:
            return f"{c:.5f}"
        return ("unreachable (e ≥ 1)" if f["fe_restitution"][i] >= 1.0 else
                "unreachable (its damping factor is bounded)")

    above = [i for i in range(n) if f["fe_restitution"][i] >= 1.0]
    text = ""
    if above:
        text = (f"<p>c_e is unreachable in {len(above)} of the {n} cases ("
                + "; ".join(case(i) for i in above) + "), where the FE restitution is e ≥ 1: "
                "no damping model returns more energy than it got (restitution_fit.csv writes "
                "−1 there). That e ≥ 1 is the time step's resolution, not an energy gain (see "
                f"the case table); the means above are over the other {n - len(above)}.</p>")
    bounded = sorted({m for m in models for i in range(n)
                      if f["c_e_" + m][i] <= 0 and f["fe_restitution"][i] < 1.0})
    if bounded:
        text += ("<p>Unreachable with e < 1 (the model's damping factor is bounded): "
                 + ", ".join(esc(m.replace("_", " ")) for m in bounded)
                 + "; see each case's c_e below.</p>")
    head = ("<table><tr><th>v [m/s]</th><th>journal mass [kg]</th><th>FE restitution</th>" +
            "".join(f"<th>c_e, {esc(m.replace('_', ' '))}</th>" for m in models) + "</tr>")
    rows = [head] + [
        f"<tr><td>{f['v_in'][i]:.3g}</td><td>{(mass[i] or 0):.4g}</td>"
        f"<td>{f['fe_restitution'][i]:.5f}</td>" +
        "".join(f"<td>{cell(i, m)}</td>" for m in models) + "</tr>" for i in range(n)]
    return text + details("each case's fitted c_e", "".join(rows) + "</table>")


def impact_headline(impact, anchor="impact"):
    """One sentence for the report's summary: the range of δ_max and of the dynamic gap, the
    restitution, the paper's claims found or not, and the c_e that reproduces the restitution;
    "" without an impact study. `anchor`: the section it links to (impact_deformable for the
    deformable journal's)."""
    if not impact or not impact.get("sweep") or not os.path.exists(impact["sweep"]):
        return ""
    deformable = is_deformable(journal_of(impact))
    s = read_sweep(impact["sweep"])
    v, gaps, e = s["v_in_m_per_s"], [100 * g for g in s["dynamic_gap"]], s["restitution"]
    def span(values, fmt):
        """'a to b', or 'a' when they agree to the digits shown."""
        lo, hi = fmt.format(min(values)), fmt.format(max(values))
        return lo if lo == hi else f"{lo} to {hi}"

    claims = paper_claims(s)
    found = "; ".join(f"“{esc(c)}”: {'yes' if ok else 'no' if ok is False else 'not tested'}"
                      for c, _, _, ok in claims)
    text = (("<p>Impact, both bodies deformable (<a href='#" + anchor + "'>FE impact study, "
             "deformable journal</a>)" if deformable else
             f"<p>Impact (<a href='#{anchor}'>FE impact study</a>)") + f", {len(v)} cases, "
            f"v = {min(v):.3g}–{max(v):.3g} m/s, journal mass "
            f"{span(s['journal_mass_kg'], '{:.4g}').replace(' to ', '–')} kg: δ_max "
            f"{span([d * 1e6 for d in s['delta_max_m']], '{:.3g}')} µm, peak force "
            f"{min(s['peak_force_N']):.4g}–{max(s['peak_force_N']):.4g} N, "
            f"<strong>{span(gaps, '{:+.1f}')} % above the quasi-static force at the same δ"
            f"</strong>, restitution {span(e, '{:.4f}')}")
    above = sum(1 for x in e if x >= 1.0)
    if above:
        text += (f" (e ≥ 1 in {above} case{'s' if above > 1 else ''}: the time step's "
                 "resolution, not an energy gain; see the case table)")
    text += f"; the paper's claims: {found}"
    man = load_or_none(os.path.join(impact.get("compare_dir", ""), "manifest.json")) or {}
    fits = man.get("extra", {}).get("fitted_restitution_coefficient", {})
    if fits:
        text += ("; the damping models return it with c_e = " +
                 ", ".join(f"{f['c_e_mean']:.4f} ({esc(n.replace('_', ' '))})"
                           for n, f in sorted(fits.items())))
    return text + ".</p>"


def case_table(s, warnings, label="impact", anchor="impact"):
    """Per case the quantities that change across the sweep; those that do not, once below.
    `label`, `anchor`: the variant's name in the warnings and the section they link to."""
    varying, constant = split_quantities(s)
    head = ("<table><tr><th>v [m/s]</th><th>journal mass [kg]</th>" +
            "".join(f"<th>{esc(label)}</th>" for _, _, label, _ in varying) +
            "<th>quasi-static F at the peak's δ [N]</th>"
            "<th>energy left in the bearing [% of ½mv²]</th></tr>")
    rows = [head]
    for i, v in enumerate(s["v_in_m_per_s"]):
        separated = s["separated"][i] > 0.5
        m = s["journal_mass_kg"][i]
        e = s["restitution"][i] if "restitution" in s else None
        note = (" (still in contact)" if not separated else
                restitution_flag(e, steps_per_period(s, i)) if e is not None else "")
        cells = "".join(f"<td>{fmt.format(s[key][i] * scale)}"
                        + (note if key == "restitution" else "")
                        + "</td>" for key, scale, _, fmt in varying)
        rows.append(f"<tr><td>{v:.3g}</td><td>{m:.4g}</td>{cells}"
                    f"<td>{s['quasi_static_force_at_peak_delta_N'][i]:.4g}</td>"
                    f"<td>{100 * s['bearing_energy_left_J'][i] / s['kinetic_initial_J'][i]:.2f}"
                    "</td></tr>")
        if not separated:
            warnings.add(f"{label} at v = {v:.3g} m/s, m = {m:.4g} kg",
                         "the journal had not left the bearing at the end time", anchor)
        elif e is not None and e >= 1.0 + E_RESOLUTION:
            warnings.add(f"{label} at v = {v:.3g} m/s, m = {m:.4g} kg",
                         f"restitution {e:.4f}: the journal left with more energy than it "
                         "brought, beyond the time step's resolution (check the energy "
                         "balance; a finer impact time step)", anchor)
    rows.append("</table>")
    if constant:
        separated = all(x > 0.5 for x in s["separated"])
        rows.append("<p>The same in every case (to 1 part in 10⁴, so not plotted): " +
                    "; ".join(f"{esc(label)} {fmt.format(c * scale)}"
                              + (restitution_flag(c, steps_per_period(s, 0))
                                 if key == "restitution" and separated else "")
                              for (key, scale, label, fmt), c in constant) + ".</p>")
    return "".join(rows)


def claims_html(s):
    """The paper's two claims on the dynamic gap beside our numbers."""
    rows = ["<h3>The paper's claims beside ours</h3><table><tr><th>the paper (§3.2)</th>"
            "<th>our numbers</th><th>what we find</th><th>agrees?</th></tr>"]
    for claim, numbers, finding, ok in paper_claims(s):
        rows.append(f"<tr><td>{esc(claim)}</td><td>{esc(numbers)}</td><td>{esc(finding)}</td>"
                    f"<td>{'yes' if ok else 'no' if ok is False else '—'}</td></tr>")
    rows.append("</table>")
    return "".join(rows)


# [1] Two journal masses are the same journal's when they agree to this: the rigid journal's
# ρπR_J²L_J against the deformable one's FE mass matrix, 1e-6 apart on the curved mapping
# (docs/fe.md), far below any mass a sweep would set beside it.
SAME_MASS = 1e-3

# (column, scale, label, format) set side by side for the two journals
BOTH = [("peak_force_N", 1.0, "peak force [N]", "{:.4g}"),
        ("impulse_Ns", 1e3, "impulse [mN s]", "{:.4g}"),
        ("delta_max_m", 1e6, "δ_max [µm]", "{:.4g}"),
        ("contact_duration_s", 1e6, "contact time [µs]", "{:.4g}"),
        ("restitution", 1.0, "restitution [1]", "{:.4f}"),
        ("dynamic_gap", 100.0, "dynamic gap [%]", "{:+.2f}")]


def both_journals_html(rigid, deformable):
    """The rigid and the deformable journal side by side at the velocities and the journal mass
    both ran (the rigid journal's own mass against the deformable one's FE mass); "" when they
    share no case (or a table is missing)."""
    if not rigid.get("sweep") or not deformable.get("sweep"):
        return ""
    if not os.path.exists(rigid["sweep"]) or not os.path.exists(deformable["sweep"]):
        return ""
    r, d = read_sweep(rigid["sweep"]), read_sweep(deformable["sweep"])
    pairs = []
    for j, (v, m) in enumerate(zip(d["v_in_m_per_s"], d["journal_mass_kg"])):
        i = next((i for i, (vr, mr) in enumerate(zip(r["v_in_m_per_s"], r["journal_mass_kg"]))
                  if abs(vr - v) <= 1e-9 * v and abs(mr - m) <= SAME_MASS * m), None)
        if i is not None:
            pairs.append((i, j))
    if not pairs:
        return ""
    cols = [q for q in BOTH if q[0] in r and q[0] in d]
    head = ("<h3>Rigid and deformable journal side by side</h3>"
            "<p>The same impacts (velocity and the journal's own mass) with the journal rigid "
            "(a point mass behind a rigid bore-shaped surface) and deformable (meshed, free: "
            "the paper's set-up); each cell rigid / deformable, and the deformable one's ratio "
            "to the rigid. Both on this run's mesh and time step (the preset; the deformable "
            "variant's overrides may keep it coarser: the scenes in scenes/).</p>"
            "<table><tr><th>v [m/s]</th><th>journal mass [kg]</th>" +
            "".join(f"<th>{esc(label)}</th>" for _, _, label, _ in cols) + "</tr>")
    rows = [head]
    for i, j in sorted(pairs, key=lambda p: d["v_in_m_per_s"][p[1]]):
        cells = ""
        for key, scale, _, fmt in cols:
            a, b = r[key][i], d[key][j]
            ratio = f" ({b / a:.3f}×)" if key != "dynamic_gap" and a else ""
            cells += f"<td>{fmt.format(a * scale)} / {fmt.format(b * scale)}{ratio}</td>"
        rows.append(f"<tr><td>{d['v_in_m_per_s'][j]:.3g}</td>"
                    f"<td>{r['journal_mass_kg'][i]:.5g} / {d['journal_mass_kg'][j]:.5g}</td>"
                    f"{cells}</tr>")
    rows.append("</table>")
    return "".join(rows)
