#!/usr/bin/python3
"""The report's presets table (report.py preset_section), from presets shaped as run_pipeline
writes them into pipeline_summary.json (pipeline/presets.cc: each measured time {value, unit} or
null, error_F_max.<name> {percent or null, where}): the measured times of one FE curve, the
impact sweep, the rolling study and the whole pipeline in their columns with their unit, a null
time "not measured"; an error column per FE sweep, named by what it is the error of (F(δ_max);
the impact study's peak force; the rolling study's plastic dissipation), each cell carrying its
`where` as a tooltip and listed below the table, a null percent "not yet measured"; the impact
and rolling time columns left out of a run that has neither the study nor a measured time.

    presets_table_test.py
"""
import html.parser
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))

from plotting.report import preset_section  # noqa: E402

WHERE_IMPACT = "peak force at v = 0.1 m/s, level 0"
WHERE_ROLLING = "plastic dissipation at 40 ms, 8 time steps, against the Richardson value"
WHERE_THICKNESS = "t_B = 4 mm, Richardson over levels 0, 1, 2"


def seconds(v):
    return None if v is None else {"value": v, "unit": "s"}


def preset(name, chosen, dofs, case, pipeline, impact, rolling, errors):
    return {"name": name, "chosen": chosen, "fe": {"rolling.n_steps": 8}, "mbd": {},
            "measured": {"note": f"note {name}", "fe_dofs": {"value": dofs, "unit": "1"},
                         "fe_case_time": seconds(case), "pipeline_time": seconds(pipeline),
                         "impact_time": seconds(impact), "rolling_time": seconds(rolling),
                         "error_F_max": errors}}


PRESETS = [
    preset("fast", False, 3588, 2.3, 66, 14, 27,
           {"thickness": {"percent": 4.8, "where": WHERE_THICKNESS},
            "impact": {"percent": 5.4, "where": WHERE_IMPACT},
            "rolling": {"percent": 14.6, "where": WHERE_ROLLING}}),
    preset("accurate", True, 145959, 259, None, None, 47,
           {"thickness": {"percent": 0.85, "where": WHERE_THICKNESS},
            "impact": {"percent": 1.3, "where": WHERE_IMPACT},
            "rolling": {"percent": None, "where": "not yet: 64 steps"}}),
]


class Table(html.parser.HTMLParser):
    """The first table's rows as lists of (text, title) per cell, and the list items after it."""

    def __init__(self):
        super().__init__()
        self.rows, self.items, self.cell, self.in_table, self.item = [], [], None, False, None

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.in_table = True
        elif tag == "tr" and self.in_table:
            self.rows.append([])
        elif tag in ("td", "th") and self.in_table:
            self.cell = ["", dict(attrs).get("title")]
        elif tag == "li":
            self.item = ""

    def handle_endtag(self, tag):
        if tag == "table":
            self.in_table = False
        elif tag in ("td", "th") and self.cell is not None:
            self.rows[-1].append((self.cell[0].strip(), self.cell[1]))
            self.cell = None
        elif tag == "li" and self.item is not None:
            self.items.append(self.item)
            self.item = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell[0] += data
        if self.item is not None:
            self.item += data


def parse(text):
    t = Table()
    t.feed(text)
    return t


def main():
    bad = []

    def expect(ok, what):
        if not ok:
            bad.append(what)

    # a sweep's, the rolling and the impact study's own settings for a preset
    # (fe_sweeps[i].presets, rolling.presets, impact.presets; {} for a null entry, null
    # without them) follow the preset's own map
    presets = [dict(p) for p in PRESETS]
    presets[0].update({"sweeps": {"thickness": {"mesh.adaptive_cycles": 2}},
                       "rolling": {"rolling.n_steps": 32, "mesh.contact_refinements": 0},
                       "impact": {"mesh.adaptive_cycles": 2}})
    presets[1].update({"sweeps": {"thickness": {}}, "rolling": {}, "impact": {}})
    summary = {"presets": presets, "sweeps": [{"name": "thickness"}],
               "impact": {"scene": "impact.yaml"}, "rolling": {"status": "complete"}}
    t = parse(preset_section(summary))
    heads = [text for text, _ in t.rows[0]]
    rows = {r[0][0].split()[0]: dict(zip(heads, r)) for r in t.rows[1:]}
    expect(set(rows) == {"fast", "accurate"}, f"one row per preset: {sorted(rows)}")
    for head in ("one FE curve [s]", "FE impact sweep [s]", "FE rolling study [s]",
                 "whole pipeline [s]", "FE DoFs [1]", "error of F(δ_max), thickness [%]",
                 "error of peak force, impact [%]", "error of plastic dissipation, rolling [%]"):
        expect(head in heads, f"a column '{head}': {heads}")
    if not bad:
        fast, accurate = rows["fast"], rows["accurate"]
        expect(fast["FE impact sweep [s]"][0] == "14", f"fast impact time: {fast['FE impact sweep [s]']}")
        expect(fast["FE rolling study [s]"][0] == "27", f"fast rolling time: {fast['FE rolling study [s]']}")
        expect(fast["one FE curve [s]"][0] == "2.3", f"fast FE curve: {fast['one FE curve [s]']}")
        expect(fast["whole pipeline [s]"][0] == "66", f"fast pipeline: {fast['whole pipeline [s]']}")
        expect(accurate["FE impact sweep [s]"][0] == "not measured",
               f"a null impact time: {accurate['FE impact sweep [s]']}")
        expect(accurate["whole pipeline [s]"][0] == "not measured",
               f"a null pipeline time: {accurate['whole pipeline [s]']}")
        expect(accurate["FE rolling study [s]"][0] == "47",
               f"accurate rolling time: {accurate['FE rolling study [s]']}")
        rolling = "error of plastic dissipation, rolling [%]"
        impact = "error of peak force, impact [%]"
        expect(fast[rolling] == ("14.6 %", WHERE_ROLLING), f"fast rolling error and where: {fast[rolling]}")
        expect(fast[impact] == ("5.4 %", WHERE_IMPACT), f"fast impact error and where: {fast[impact]}")
        expect(accurate[rolling] == ("not yet measured", "not yet: 64 steps"),
               f"a null rolling percent: {accurate[rolling]}")
        expect("(this run)" in accurate["preset"][0], f"the chosen preset marked: {accurate['preset']}")
        settings = "FE scene settings"
        expect(fast[settings][0] == "rolling.n_steps = 8; sweep thickness: mesh.adaptive_cycles = 2; "
               "rolling study: mesh.contact_refinements = 0, rolling.n_steps = 32; "
               "impact study: mesh.adaptive_cycles = 2",
               f"the preset's, the sweep's, the rolling and impact studies' settings: {fast[settings]}")
        expect(accurate[settings][0] == "rolling.n_steps = 8",
               f"null entries add nothing: {accurate[settings]}")
    for where in (WHERE_ROLLING, WHERE_IMPACT, WHERE_THICKNESS):
        expect(sum(where in item for item in t.items) == 1,
               f"'{where}' listed once below the table: {t.items}")
    expect(any(item.startswith("thickness (fast, accurate)") for item in t.items),
           f"a where shared by presets listed once, naming them: {t.items}")

    # A run without the impact and rolling studies whose presets measured neither: no such columns.
    plain = [preset("fast", True, 3588, 2.3, 66, None, None,
                    {"thickness": {"percent": None, "where": WHERE_THICKNESS}})]
    # (a summary written before issue 29 calls the sweeps `studies`: read the same)
    t = parse(preset_section({"presets": plain, "studies": [{"name": "thickness"}]}))
    heads = [text for text, _ in t.rows[0]]
    expect("FE impact sweep [s]" not in heads and "FE rolling study [s]" not in heads,
           f"no impact or rolling time columns without the studies: {heads}")
    cell = dict(zip(heads, t.rows[1])).get("error of F(δ_max), thickness [%]")
    expect(cell is not None and cell[0] == "not yet measured", f"a null thickness percent: {t.rows[1]}")

    # Issue 32 item 2: this run's times beside the chosen preset's figures, a figure missed by
    # more than 1.5x either way flagged as stale; reused tasks measure nothing; an FE sweep's
    # own case time (case_times) gets its column.
    def task(name, stage, seconds, key, figure, outcome="ran"):
        return {"name": name, "stage": stage, "outcome": outcome,
                "wall_time": {"value": seconds, "unit": "s"},
                "preset_time": {"value": figure, "unit": "s", "key": key}}

    standard = preset("standard", True, 21996, 19.2, 260, 103, 34,
                      {"thickness": {"percent": 2.0, "where": WHERE_THICKNESS}})
    standard["measured"]["case_times"] = {"misalignment": {"value": 7.8, "unit": "s"}}
    run = {"presets": [preset("fast", False, 3588, 2.3, 66, 14, 27, {}), standard],
           "sweeps": [{"name": "thickness"}, {"name": "misalignment"}],
           "impact": {"scene": "impact.yaml"}, "rolling": {"status": "complete"},
           "wall_time": {"value": 449.0, "unit": "s"},
           "tasks": [task("fe/thickness/t_B=0.002", "fe_stage", 19.0, "fe_case_time", 19.2),
                     task("fe/thickness/t_B=0.004", "fe_stage", 21.0, "fe_case_time", 19.2),
                     task("fe/misalignment/theta=1", "fe_stage", 8.1, "case_times.misalignment", 7.8),
                     task("fe/impact", "fe_impact", 40.0, "impact_time", 103),
                     task("fe/rolling", "fe_rolling", 33.0, "rolling_time", 34),
                     {"name": "fit/thickness/t_B=0.004", "stage": "fit_stage", "outcome": "ran",
                      "wall_time": {"value": 0.5, "unit": "s"}}]}
    text = preset_section(run)
    t = parse(text)
    heads = [h for h, _ in t.rows[0]]
    expect("one FE case, misalignment [s]" in heads, f"a column for case_times.misalignment: {heads}")
    this = [r for r in t.rows[1:] if r[0][0] == "this run"]
    expect(len(this) == 1, f"one row of this run's times: {[r[0][0] for r in t.rows]}")
    if this:
        cells = dict(zip(heads, this[0]))
        expect(cells["one FE curve [s]"][0] == "20 (mean of 2)", f"FE cases: {cells['one FE curve [s]']}")
        expect(cells["one FE case, misalignment [s]"][0] == "8.1", f"misalignment: {cells['one FE case, misalignment [s]']}")
        expect(cells["FE rolling study [s]"][0] == "33", f"rolling within 1.5x: {cells['FE rolling study [s]']}")
        expect(cells["whole pipeline [s]"][0].startswith("⚠ 449") and "1.7× the figure" in cells["whole pipeline [s]"][0],
               f"the pipeline 1.7x slower than its figure flagged: {cells['whole pipeline [s]']}")
        expect(cells["FE impact sweep [s]"][0].startswith("⚠ 40") and "0.39× the figure" in cells["FE impact sweep [s]"][0],
               f"a figure 2.6x too high flagged too: {cells['FE impact sweep [s]']}")
        expect(not cells["one FE curve [s]"][0].startswith("⚠"), "20 s against 19.2 s is no stale figure")
    expect("Stale preset figures" in text and "2 of the preset" in text
           and "bench/measure_presets.py --presets standard" in text,
           "a warning naming the stale figures and the command that refreshes them")
    # reused tasks measure nothing: no flag, the whole pipeline not compared
    for tk in run["tasks"]:
        if tk["stage"] == "fe_impact":
            tk["outcome"] = "reused"
    run["tasks"][0]["outcome"] = "reused"
    text = preset_section(run)
    t = parse(text)
    this = [r for r in t.rows[1:] if r[0][0] == "this run"]
    if this:
        cells = dict(zip(heads, this[0]))
        expect(cells["FE impact sweep [s]"][0] == "reused", f"a reused impact: {cells['FE impact sweep [s]']}")
        expect(cells["whole pipeline [s]"][0] == "reused", f"a run with reused tasks: {cells['whole pipeline [s]']}")
        expect(cells["one FE curve [s]"][0] == "21", f"only the case that ran: {cells['one FE curve [s]']}")
    expect("Stale preset figures" not in text, "nothing stale when the slow and fast ones were reused")

    if bad:
        print("FAILED:\n  " + "\n  ".join(bad))
        return 1
    print("presets table: times, errors by what they measure, where texts, nulls: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
