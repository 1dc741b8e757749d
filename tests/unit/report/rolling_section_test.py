#!/usr/bin/python3
"""The report's rolling section (issue 13 item 5) from hand-made fe_stage rolling outputs with
fe_stage's real column names (fe_stage/rolling_output.cc) and manifest shape
(rolling_summary_json): the section, its three figures (Fig. 10, energy, Fig. 12), the final
numbers with units, the slip stages, and exactly the warnings the data call for — none for a
clean run; an incomplete run; an energy balance error beyond 5 % of the work in; a strain beyond
0.05 (small strain not accurate); a failed task (its message, its partial output, not an older
complete folder); a missing folder. Columns are read by name: shuffled columns and a column
fe_stage may add (work_drive_torque) change nothing else. No rolling study: no section. And the
whole report (report.py) with a rolling study: contents entry, summary sentence, section.

    rolling_section_test.py
"""
import json
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import matplotlib  # noqa: E402
matplotlib.use("Agg")

from plotting import report  # noqa: E402
from plotting._report_common import Warnings  # noqa: E402
from plotting._report_rolling import rolling_headline, rolling_section  # noqa: E402
import rolling_fields_vtu  # noqa: E402

# fe_stage/rolling_output.cc, rolling_history_table()
COLUMNS = [
    ("time", "s"), ("delta", "m"), ("force_normal", "N"), ("force_tangential", "N"), ("phi", "rad"),
    ("gamma", "rad"), ("phi_rate", "rad/s"), ("gamma_rate", "rad/s"), ("slip_speed", "m/s"),
    ("torque_drive", "N m"), ("torque_journal", "N m"), ("work_drive", "J"), ("work_push", "J"),
    ("elastic_energy", "J"), ("plastic_dissipation", "J"), ("friction_dissipation", "J"),
    ("kinetic_energy", "J"), ("energy_balance_error", "J"), ("work_frame", "J"),
    ("frame_balance_error", "J"), ("max_plastic_strain", "1"), ("max_strain", "1"),
    ("plastic_volume", "m^3"), ("active_contact_points", "1"), ("slipping_contact_points", "1"),
    ("spin_iterations", "1"), ("newton_iterations", "1"), ("line_search_steps", "1"), ("contact_iterations", "1"),
    ("linear_iterations", "1"), ("cuts", "1"), ("spin_coupled", "1"), ("phi_paper", "rad"), ("gamma_paper", "rad"),
    ("phi_rate_paper", "rad/s"), ("gamma_rate_paper", "rad/s"), ("wall_time", "s")]
PROFILE = [("angle", "rad"), ("arc", "m"), ("strain_radial", "1"), ("strain_tangential", "1"),
           ("strain_axial", "1"), ("plastic_strain", "1"), ("von_mises", "Pa")]


def step(k, n=4, error=0.05, strain=0.02, force=12345.6):
    """Row k of n: the end row has work in 3 J (2 drive + 1 push) split as 1.5 elastic,
    0.5 plastic, 0.9 friction, 0.05 kinetic, and `error` J left over."""
    f = k / n
    return {"time": 0.25 * f, "delta": 5e-5 * f, "force_normal": force * f,
            "force_tangential": 0.3 * force * f, "phi": 12.56 * 0.25 * f, "gamma": 13.0 * 0.25 * f,
            "phi_rate": 12.56, "gamma_rate": 13.1 * f, "slip_speed": 0.02 * (1 - f) + 0.0042,
            "torque_drive": 37.0 * f, "torque_journal": 35.0 * f, "work_drive": 2.0 * f,
            "work_push": 1.0 * f, "elastic_energy": 1.5 * f, "plastic_dissipation": 0.5 * f,
            "friction_dissipation": 0.9 * f, "kinetic_energy": 0.05 * f,
            "energy_balance_error": error * f, "work_frame": 2.05 * f,
            "frame_balance_error": 0.05 * f, "max_plastic_strain": 0.0123 * f,
            "max_strain": strain * f, "plastic_volume": 1e-9 * f, "active_contact_points": 6,
            "slipping_contact_points": 2, "spin_iterations": 3, "newton_iterations": 4, "line_search_steps": 1,
            "contact_iterations": 5, "linear_iterations": 40, "cuts": 1, "spin_coupled": 1, "phi_paper": 3.0 * f,
            "gamma_paper": 3.1 * f, "phi_rate_paper": 12.3, "gamma_rate_paper": 12.9 * f,
            "wall_time": 1.5 * k, "work_drive_torque": 2.4 * f}


def write_run(folder, rows=4, complete=True, message="", shuffle=False, extra_column=False,
              journal=None, kinematics=None, **kw):
    os.makedirs(folder, exist_ok=True)
    cols = list(COLUMNS) + ([("work_drive_torque", "J")] if extra_column else [])
    if shuffle:
        cols = cols[::-1]
    marker = "# status: complete\n" if complete else f"# status: incomplete: {message}\n"
    with open(os.path.join(folder, "rolling_history.csv"), "w") as f:
        f.write("# clearjoint fe_stage: rolling study (hand-made for the report's test)\n")
        f.write("# units: " + ",".join(u for _, u in cols) + "\n" + ",".join(c for c, _ in cols) + "\n")
        f.write(",".join("0" for _ in cols) + "\n")
        for k in range(1, rows + 1):
            r = step(k, 4, **kw)
            f.write(",".join(repr(r[c]) for c, _ in cols) + "\n")
        f.write(marker)
    # a deformable journal (journal "core"): fe_stage adds the body column, 0 the bore's rows
    # and 1 the journal's
    profile = PROFILE + ([("body", "1")] if journal == "core" else [])
    with open(os.path.join(folder, "rolling_strain_profile.csv"), "w") as f:
        f.write("# units: " + ",".join(u for _, u in profile) + "\n" + ",".join(c for c, _ in profile) + "\n")
        for body in ((0, 1) if journal == "core" else (None,)):
            for i in range(-3, 4):
                f.write(f"{0.1 * i},{0.001 * i},{-0.004 / (1 + i * i)},{0.002 / (1 + i * i)},"
                        f"{0.0005 / (1 + i * i)},{0.0123 / (1 + i * i)},{3e8 / (1 + i * i)}" +
                        (f",{body}" if body is not None else "") + "\n")
        f.write(marker)
    last = step(rows, 4, **kw)
    manifest = {
        "schema": "clearjoint.manifest/1", "stage": "fe_stage",
        "status": "complete" if complete else "incomplete", "message": message,
        "extra": {
            "scene": {"study": "rolling",
                      "loading": dict({"delta_max": 5e-5}, **({"journal": journal} if journal else {})),
                      "contact": {"mu": 0.3},
                      "rolling": {"omega_B": 12.56, "ramp_time": 0.25, "end_time": 0.25, "n_steps": 4},
                      **({"material": {"kinematics": kinematics}} if kinematics else {})},
            "rolling": {
                "journal_inertia": {"value": 1.8e-6, "unit": "kg m^2"},
                "rolling_rate": {"value": 13.22, "unit": "rad/s", "meaning": "..."},
                "time_step": {"value": 0.0625, "unit": "s"},
                "slip_stages": {"found": True,
                                "slip_speed_max": {"value": 0.0197, "unit": "m/s"},
                                "end_of_slip": {"value": 0.125, "unit": "s", "meaning": "..."},
                                "settled": {"value": 0.1875, "unit": "s", "meaning": "..."},
                                "slip_speed_final": {"value": 0.0042, "unit": "m/s"}},
                "max_plastic_strain": last["max_plastic_strain"],
                "max_strain": {"value": last["max_strain"], "meaning": "..."},
                "energy_balance_error": {"value": abs(last["energy_balance_error"]) / 3.0},
                "final": {"time": last["time"], "force_normal": last["force_normal"]}}}}
    with open(os.path.join(folder, "manifest.json"), "w") as f:
        json.dump(manifest, f)
    return folder


def section(rolling, base):
    w = Warnings()
    return rolling_section(rolling, base, w), w


def main():
    bad = []

    def expect(ok, what):
        if not ok:
            bad.append(what)

    def warning_texts(w):
        return [t for _, t, _ in w.items]

    with tempfile.TemporaryDirectory() as d:
        # No rolling study: no section, no warning, no sentence.
        html, w = section(None, d)
        expect(html == "" and not w.items and rolling_headline(None) == "",
               "no rolling study gives no section")

        # A clean complete run.
        clean = write_run(os.path.join(d, "clean", "fe", "rolling"))
        html, w = section({"fe_dir": clean, "status": "complete"}, d)
        expect("id='rolling'" in html, "the section has its anchor")
        expect(html.count("<img") == 3, f"three figures (Fig. 10, energy, Fig. 12): {html.count('<img')}")
        for part in ("Fig. 10", "Fig. 12", "Eqs. 7–8", "energy split",
                     "12346 N",            # contact force at the end
                     "3703.7 N",           # tangential
                     "13.1 rad/s (99.1 % of the rolling rate 13.22 rad/s)",  # journal spin
                     "12.9 rad/s",         # by Eq. 7
                     "0.0042 m/s",         # slip speed
                     "0.0123 [1]",         # largest plastic strain
                     "0.02 [1]",           # largest strain
                     "+1.67 % of the work in",  # balance 0.05 J of 3 J
                     "0.05 mm",            # δ at the end
                     "0.25 s after 4 time steps (4 step cuts)",
                     "16 material Newton iterations, 4 line-search trial points rejected",
                     "end of gross slip", "0.125 s", "0.1875 s", "0.0197 m/s",  # slip stages
                     "ω_B = 12.56 rad/s", "μ = 0.3",
                     "rolling_history.csv", "rolling_strain_profile.csv"):
            expect(part in html, f"clean run: the section shows {part!r}")
        expect("work_drive_torque" not in html, "no work_drive_torque row when the column is absent")
        expect("Fig. 11)</h3>" in html and "No principal-strain map: the run wrote no fields" in html,
               "no fields: the Fig. 11 part is a note")
        expect(not w.items, f"a clean run has no warnings: {warning_texts(w)}")
        head = rolling_headline({"fe_dir": clean, "status": "complete"})
        for part in ("href='#rolling'", "12346 N", "13.1 rad/s", "99.1 % of rolling without slip",
                     "0.0042 m/s", "+1.7 %"):
            expect(part in head, f"the summary sentence shows {part!r}: {head}")

        # Shuffled columns and a column fe_stage may add: read by name, the new one listed.
        other = write_run(os.path.join(d, "shuffled"), shuffle=True, extra_column=True)
        html2, w2 = section({"fe_dir": other, "status": "complete"}, d)
        for part in ("12346 N", "13.1 rad/s (99.1 %", "0.0042 m/s", "+1.67 % of the work in"):
            expect(part in html2, f"shuffled columns: the section still shows {part!r}")
        expect("<code>work_drive_torque</code>" in html2 and "2.4" in html2,
               "work_drive_torque is listed in the energy table when present")
        expect(not w2.items, f"shuffled: no warnings: {warning_texts(w2)}")

        # The energy balance off by 10 % of the work in.
        off = write_run(os.path.join(d, "balance"), error=0.3)
        _, w = section({"fe_dir": off, "status": "complete"}, d)
        expect(len(w.items) == 1 and "+10.0 % of the work in" in w.items[0][1] and
               "its frame is +2.4 % of work_frame = 2.05 J" in w.items[0][1],
               f"a 10 % balance error gives one warning: {warning_texts(w)}")
        # ... and within 5 %: none (the limit, not any error, triggers it)
        ok = write_run(os.path.join(d, "balance_ok"), error=-0.14)
        _, w = section({"fe_dir": ok, "status": "complete"}, d)
        expect(not w.items, f"a -4.7 % balance error gives no warning: {warning_texts(w)}")

        # Strain beyond 0.05: small strain is not accurate.
        big = write_run(os.path.join(d, "strain"), strain=0.08)
        _, w = section({"fe_dir": big, "status": "complete"}, d)
        expect(len(w.items) == 1 and "0.08" in w.items[0][1] and "small-strain" in w.items[0][1],
               f"strain 0.08 gives the small-strain warning: {warning_texts(w)}")
        html, _ = section({"fe_dir": big, "status": "complete"}, d)
        expect("small strain." in html, "a run without kinematics is said to be small strain")
        # ... but not in a finite-strain run (the rolling study's default since issue 30), which
        # the section says it was
        big_finite = write_run(os.path.join(d, "strain_finite"), strain=0.08, kinematics="finite")
        html, w = section({"fe_dir": big_finite, "status": "complete"}, d)
        expect(not w.items, f"strain 0.08 in finite strain gives no warning: {warning_texts(w)}")
        expect("finite strain (total Lagrangian" in html and "small strain." not in html,
               "a finite-strain run is said to be finite strain")

        # Incomplete (manifest and CSV say so) though the task itself exited 0.
        inc = write_run(os.path.join(d, "incomplete"), rows=2, complete=False,
                        message="time step 3 did not converge after 10 cuts")
        html, w = section({"fe_dir": inc, "status": "complete"}, d)
        expect(len(w.items) == 1 and "incomplete" in w.items[0][1] and
               "time step 3 did not converge" in w.items[0][1],
               f"an incomplete run gives one warning with its message: {warning_texts(w)}")
        expect("last converged step" in html and "0.125 s after 2 time steps" in html,
               "an incomplete run shows its last converged step")

        # A failed task: the message, the partial output (not an older complete folder).
        stale = write_run(os.path.join(d, "failed", "fe", "rolling"), force=99999.0)
        partial = write_run(os.path.join(d, "failed", "fe", "rolling.partial"), rows=2,
                            complete=False, message="time step 3 did not converge")
        msg = ("fe_rolling failed in task fe/rolling (exit status 2); its log "
               f"{stale}.log ends with:\nfe_stage: time step 3 did not converge <after 10 cuts>")
        failed = {"fe_dir": stale, "status": "failed", "message": msg, "partial_dir": partial}
        html, w = section(failed, d)
        expect("The rolling task failed" in html and "&lt;after 10 cuts&gt;" in html,
               "a failed task's section shows its whole message, escaped")
        expect("6172.8 N" in html and "99999" not in html and "1e+05" not in html,
               "a failed task shows its partial output, not the older complete folder")
        expect(any("failed" in t and "exit status 2" in t and
                   "time step 3 did not converge &lt;after 10 cuts&gt;" in t for t in warning_texts(w)),
               f"a failed task is in the warnings, with the stage's last line: {warning_texts(w)}")
        expect(len(w.items) == 1, f"one warning for the failure, not a second for 'incomplete': "
                                  f"{warning_texts(w)}")
        head = rolling_headline(failed)
        expect("the task failed" in head and "did not converge" in head and "99999" not in head
               and "6172.8 N" in head,
               f"the summary sentence says it failed and shows the last step: {head}")
        # ... and one that left nothing
        gone = dict(failed, partial_dir=os.path.join(d, "nowhere.partial"))
        html, w = section(gone, d)
        expect("left no output" in html and "exit status 2" in html and "<img" not in html,
               "a failed task without output shows its message only")
        expect("the task failed" in rolling_headline(gone), "headline of a failure without output")

        # A configured study whose folder is missing (status complete).
        html, w = section({"fe_dir": os.path.join(d, "missing"), "status": "complete"}, d)
        expect(len(w.items) == 1 and "no output folder" in w.items[0][1],
               f"a missing folder is a warning: {warning_texts(w)}")

        # The deformable journal: the text names it, the strain profile figure has both bodies
        # (one figure, its two panels), and the rest is as for the rigid one.
        core = write_run(os.path.join(d, "core", "fe", "rolling"), journal="core")
        html, w = section({"fe_dir": core, "status": "complete"}, d)
        expect("the deformable journal" in html and "both bodies are elastoplastic" in html,
               "the deformable journal is named")
        expect(html.count("<img") == 3, f"three figures with the deformable journal: {html.count('<img')}")
        expect("on the journal's surface" in html, "the profile's caption names the journal's surface")
        html, w = section({"fe_dir": clean, "status": "complete"}, d)
        expect("the rigid journal" in html, "the rigid journal is named")

        # Fields at the end (tiny, tests/unit/report/rolling_fields_vtu.py): the principal-strain
        # map (Fig. 11) is drawn, with each body's extremes and the paper's figure beside it.
        with_fields = write_run(os.path.join(d, "fields", "fe", "rolling"), journal="core")
        rolling_fields_vtu.write_fields(with_fields, 0.25)
        man_path = os.path.join(with_fields, "manifest.json")
        man = json.load(open(man_path))
        man["extra"]["scene"]["geometry"] = {"R_B": rolling_fields_vtu.R_B, "c_r": rolling_fields_vtu.C_R,
                                             "t_B": rolling_fields_vtu.T_B}
        json.dump(man, open(man_path, "w"))
        base = os.path.join(d, "fields")
        html, w = section({"fe_dir": with_fields, "status": "complete"}, base)
        expect(html.count("<img") == 4, f"four figures with fields (Fig. 10, energy, Fig. 12, Fig. 11): "
                                        f"{html.count('<img')}")
        fig11 = html[html.find("Fig. 11)</h3>"):html.find("<h3>Slip stages")]
        for part in ("The paper&#x27;s Fig. 11a shows the principal strains after 0.250 s",
                     "φ = 179.9°",                      # 12.56 rad/s × 0.25 s
                     "mid-plane z = 0 mm",
                     "bearing: largest principal strain +0.001, smallest -0.002 near the contact",
                     "journal: largest principal strain +0.003, smallest -0.004 near the contact",
                     "<td>bearing</td><td>+0.001 <small>(r = 10.00 mm from its axis",
                     "<td>journal</td><td>+0.003",
                     "not the paper&#x27;s 1 mm",       # this run pushes 0.05 mm
                     "solution_0001.vtu"):
            expect(part in fig11, f"fields: the Fig. 11 part shows {part!r}")
        expect(os.path.exists(os.path.join(base, "pictures", "rolling_strains.png")),
               "the picture is written beside the report")
        expect(not w.items, f"fields: no warnings: {warning_texts(w)}")
        # ... fields that cannot be read: a note, not a crash
        with open(os.path.join(with_fields, "fields", "solution_0001.vtu"), "w") as f:
            f.write("not a VTU file")
        import vtk
        vtk.vtkObject.GlobalWarningDisplayOff()  # the reader's error, expected here
        html, w = section({"fe_dir": with_fields, "status": "complete"}, base)
        vtk.vtkObject.GlobalWarningDisplayOn()
        expect("No principal-strain map: solution_0001.vtu could not be read" in html and
               html.count("<img") == 3, "unreadable fields: a note instead of the picture")

        # The whole report with a rolling study and nothing else.
        summary = {"schema": "clearjoint.pipeline_summary/1", "run": "r", "preset": "fast",
                   "pipeline_file": "p.yaml", "presets": [], "tasks": [], "sweeps": [],
                   "mbd_runs": [], "rolling": {"fe_dir": big, "status": "complete"}}
        sp = os.path.join(d, "pipeline_summary.json")
        with open(sp, "w") as f:
            json.dump(summary, f)
        out = os.path.join(d, "report.html")
        expect(report.main([sp, "--output", out]) == 0, "report.py runs")
        text = open(out).read()
        nav = text[text.find("<nav>"):text.find("</nav>")]
        expect("href='#rolling'" in nav, "the contents list the rolling study")
        s = text[text.find("id='summary'"):text.find("<nav>")]
        expect("Rolling (<a href='#rolling'>" in s, "the summary has the rolling sentence")
        expect(re.search(r"FE rolling study</strong>: the largest principal strain", s),
               "the summary lists the rolling warning")
        expect(text.find("<nav>") < text.find("id='rolling'") < text.find("id='timing'"),
               "the rolling section comes after the contents, before the wall times")

    if bad:
        print("FAILED:\n  " + "\n  ".join(bad))
        return 1
    print("rolling section: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
