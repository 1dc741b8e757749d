#!/usr/bin/python3
"""bench/measure_presets.py on its tiny case (issue 32 items 2 and 6), with the stand-in FE stage
(tests/data/fake_stages, scene key fake_discretisation: results with a known order-1 error):
it writes valid `measured` blocks — times, DoFs, errors against the plan's references equal to
the stand-in's known errors, machine, date — into a pipeline file, leaves every other line of
the file as it was, measures a subset alone, refuses to write the repository's pipeline.yaml
with --tiny; run_pipeline then reads the blocks and prints each FE task's time beside its
figure; a bad value written by hand is an input error naming the key.

    measure_presets_test.py RUN_PIPELINE FIT_STAGE MSH_CHECK
"""
import collections
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import measure_presets  # noqa: E402
from fake_build import make_fake_build, write_scenes  # noqa: E402

PIPELINE = """# A test pipeline: comments and layout outside the measured blocks must survive.
schema: clearjoint.pipeline/1
run: r
output_root: out
preset: fast              # a comment beside a key
presets:
  fast:
    fe: {mesh.global_refinements: 0, impact.steps_per_period: 40, rolling.n_steps: 8}
    mbd: null
    measured:
      note: "typed by hand"
      fe_dofs: 3588           # [1] a hand-typed comment, replaced
      fe_case_time: 2.3       # [s]
      pipeline_time: 66       # [s] how it was timed, kept while the figure is
      error_F_max:
        thickness: {percent: 4.8, where: "by hand"}
    # a comment after the block stays
  standard:
    fe: {mesh.global_refinements: 1, impact.steps_per_period: 80, rolling.n_steps: 16}
    mbd: null
  accurate:
    fe: {mesh.global_refinements: 2, impact.steps_per_period: 160, rolling.n_steps: 32}
    mbd: null
    measured:
      note: "by hand"
      fe_case_time: 259
      error_F_max:
        thickness: {percent: 0.85, where: "by hand"}

fe_sweeps:
  - name: thickness
    scene: thickness.yaml
    parameter: {name: t_B, unit: m, key: geometry.t_B}
    values: [0.002, 0.004]
  - name: misalignment
    scene: misalignment.yaml
    parameter: {name: theta, unit: deg, key: misalignment.theta_deg}
    values: [1.0, 2.0]
fit: {weighting: absolute}
mbd_runs: []
impact:
  scene: impact.yaml
  law: {file: law.json}
rolling:
  scene: rolling.yaml
  overrides: {mesh.global_refinements: 0}
report: false
# the end
"""

SCENES = {
    "thickness.yaml": {"study": "radial", "geometry": {"t_B": 0.004}, "fake_discretisation": True},
    "misalignment.yaml": {"study": "misalignment", "misalignment": {"theta_deg": 1.0},
                          "loading": {"journal": "rigid"}, "fake_discretisation": True},
    "impact.yaml": {"study": "impact", "sweep": {"velocity": [0.05, 0.1]},
                    "fake_discretisation": True},
    "rolling.yaml": {"study": "rolling", "rolling": {"n_steps": 16}, "fake_discretisation": True},
}


def without_blocks(text):
    """The file's lines with every preset's measured block taken out."""
    lines = text.split("\n")
    for preset in reversed(measure_presets.PRESETS):
        start, end, _ = measure_presets.find_block(lines, preset)
        if start is not None:
            del lines[start:end]
    return lines


def main():
    run_pipeline, fit_stage, msh_check = sys.argv[1:4]
    bad = []

    def expect(ok, what):
        if not ok:
            bad.append(what)

    def close(a, b, what, rel=5e-3):  # figures have 3 significant digits
        expect(a is not None and abs(a - b) <= rel * abs(b), f"{what}: {a} against {b}")

    d = tempfile.mkdtemp(prefix="measure_presets_")
    try:
        # A sweep's own preset settings (fe_sweeps[i].presets, issue 31 item 5) come after its
        # overrides in run_pipeline, so a reference's `set` (a longer adaptive sequence) must be
        # written after them too, or the sweep's cycles would win over the reference's.
        args = type("A", (), {"pipeline": os.path.join(d, "p.yaml"), "work": os.path.join(d, "w"),
                              "set": {}})()
        sweep = {"name": "misalignment", "scene": "s.yaml", "values": [1.0],
                 "parameter": {"name": "theta", "unit": "deg", "key": "misalignment.theta_deg"},
                 "overrides": {"loading.journal": "core"},
                 "presets": {"fast": {"mesh.adaptive_cycles": 2}, "standard": None,
                             "accurate": {"mesh.adaptive_cycles": 4}}}
        m = measure_presets.Measurer(
            args, {"presets": {p: {"fe": None, "mbd": None} for p in measure_presets.PRESETS},
                   "fe_sweeps": [sweep]},
            {"studies": {"misalignment": {"kind": "fe_sweep", "value": 1.0}}})
        gen = m.pipeline_for("misalignment", {"preset": "accurate",
                                              "set": {"mesh.adaptive_cycles": 5}})
        s0 = gen["fe_sweeps"][0]
        expect(s0["presets"]["accurate"] == {"mesh.adaptive_cycles": 5}
               and s0["presets"]["fast"] == {"mesh.adaptive_cycles": 5}
               and s0["presets"]["standard"] == {"mesh.adaptive_cycles": 5}
               and s0["overrides"]["loading.journal"] == "core",
               f"a reference's set after the sweep's own presets: {s0}")
        expect(sweep["presets"]["accurate"] == {"mesh.adaptive_cycles": 4},
               "the pipeline's own sweep is left as it was")
        # The same for the rolling study's own preset settings (rolling.presets): a reference's
        # finer steps must not be undone by the preset's own rolling.n_steps.
        rolling = {"scene": "r.yaml", "overrides": {"mesh.global_refinements": 0},
                   "presets": {"fast": {"mesh.contact_refinements": 0, "rolling.n_steps": 32},
                               "standard": None, "accurate": None}}
        m = measure_presets.Measurer(
            args, {"presets": {p: {"fe": None, "mbd": None} for p in measure_presets.PRESETS},
                   "rolling": rolling},
            {"studies": {"rolling": {"kind": "rolling"}}})
        r0 = m.pipeline_for("rolling", {"preset": "fast", "set": {"rolling.n_steps": 128}})["rolling"]
        expect(r0["presets"]["fast"] == {"mesh.contact_refinements": 0, "rolling.n_steps": 128}
               and r0["presets"]["standard"] == {"rolling.n_steps": 128}
               and r0["overrides"] == {"mesh.global_refinements": 0, "rolling.n_steps": 128},
               f"a reference's set after the rolling study's own presets: {r0}")
        expect(rolling["presets"]["fast"]["rolling.n_steps"] == 32,
               "the pipeline's own rolling block is left as it was")
        # A part that compares a run with itself (the impact's mesh part, {set: 80 steps}
        # against {preset: accurate, set: 80 steps}, measured for the accurate preset) is the
        # same run: error() leaves it out instead of counting 0 %.
        m = measure_presets.Measurer(
            args, {"presets": {p: {"fe": {"mesh.global_refinements": i}, "mbd": None}
                               for i, p in enumerate(measure_presets.PRESETS)},
                   "impact": {"scene": "i.yaml"}},
            {"studies": {"impact": {"kind": "impact"}}})
        steps = {"impact.steps_per_period": 80}
        of, finest = {"set": steps}, {"preset": "accurate", "set": steps}
        expect(m.run_key("impact", m.spec(of, "accurate")) == m.run_key("impact", m.spec(finest, "accurate")),
               "the accurate preset's mesh part compares its own run")
        expect(m.run_key("impact", m.spec(of, "standard")) != m.run_key("impact", m.spec(finest, "standard")),
               "the standard preset's mesh part compares two meshes")
        # ... and --jobs does not start it either: runs_needed() lists the runs error() asks
        # for, read from the same parts (before, it also listed a left-out part's run; the
        # real plan's is one of its Richardson runs, so nothing was made for nothing there).
        m.plan["studies"]["impact"]["reference"] = {"parts": [
            {"name": "the time step", "richardson": [{"set": {"impact.steps_per_period": n}}
                                                     for n in (160, 320, 640)]},
            {"name": "the mesh", "of": of, "run": finest}]}
        m.args.times_only = False
        for preset, n_refs in (("accurate", 3), ("standard", 5)):
            needed = m.runs_needed("impact", preset)
            expect(len(needed) == 1 + n_refs and needed[0] == ({"preset": preset, "set": {}}, True),
                   f"{preset}: its own run and {n_refs} references: {needed}")
        expect(m.spec(finest, "accurate") not in [s for s, _ in m.runs_needed("impact", "accurate")],
               "the accurate preset's left-out mesh part makes no run")
        # --jobs: a forced (own) run asked for while the same run goes on as a reference runs
        # after it, not beside it (both would write one output folder); a reference asked for
        # twice is made once.
        jargs = type("J", (), {"pipeline": os.path.join(d, "p.yaml"), "work": os.path.join(d, "wj"),
                               "set": {}, "jobs": 2, "presets": ["standard"]})()
        m = measure_presets.Measurer(
            jargs, {"presets": {p: {"fe": None, "mbd": None} for p in measure_presets.PRESETS},
                    "rolling": {"scene": "r.yaml"}},
            {"studies": {"rolling": {"kind": "rolling"}}})
        m.studies = ["rolling"]
        spans = []

        def fake_execute(study, spec, own, p, key, after=None):
            if after is not None:
                after.result()
            start = time.monotonic()
            time.sleep(0.3)
            spans.append((own, start, time.monotonic()))
            return {"value": 1.0, "own": own}

        m.execute = fake_execute
        ref = m.start("rolling", {"preset": "fast", "set": {}}, False)  # fast: not measured here
        again = m.start("rolling", {"preset": "fast", "set": {}}, False)
        forced = m.start("rolling", {"preset": "fast", "set": {}}, True)
        expect(again is ref and forced is not ref, "a reference asked twice is one run; a forced one is another")
        expect(forced.result()["own"] and not ref.result()["own"], "the forced run is the own run")
        spans.sort(key=lambda x: x[1])
        expect(len(spans) == 2 and spans[1][1] >= spans[0][2],
               f"the forced run starts after the reference's end: {spans}")
        m.pool.shutdown()
        build = make_fake_build(d, fit_stage, msh_check)
        write_scenes(d, SCENES)
        shutil.copy(os.path.join(ROOT, "laws", "paper_tB4.json"), os.path.join(d, "law.json"))
        p = os.path.join(d, "p.yaml")
        with open(p, "w") as f:
            f.write(PIPELINE)
        command = [sys.executable, os.path.join(ROOT, "bench", "measure_presets.py"), "--tiny",
                   "--pipeline", p, "--build-dir", build, "--run-pipeline", run_pipeline,
                   "--work", os.path.join(d, "work"), "--no-plots", "--set", "contact.mu=0.1"]

        # 1. every preset, every study but the whole pipeline (the tiny plan's default)
        done = subprocess.run(command, capture_output=True, text=True, cwd=d)
        expect(done.returncode == 0, f"measure_presets --tiny exit {done.returncode}:\n"
                                     f"{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
        with open(p) as f:
            text = f.read()
        expect(without_blocks(text) == without_blocks(PIPELINE),
               "every line outside the measured blocks unchanged")
        m = yaml.safe_load(text)["presets"]
        # the stand-in's errors (fake_fe_stage.py): F scales by 1 + 0.1 h, h = 2^-(contact
        # refinements) = 1, 1/2, 1/4 for fast, standard, accurate: 10, 5, 2.5 %
        expected = {"fast": {"thickness": 10.0, "misalignment": 10.0,
                             # 500 (1 + 0.1) (1 - 4/10) against 500 (1 + 0.1/4)
                             "impact": 100 * (1 - 1.1 * 0.6 / 1.025),
                             # (1 + 1/4) against 1 (time step) + 1.2 against 1.1 (mesh)
                             "rolling": 25.0 + 100 / 11},
                    "standard": {"thickness": 5.0, "misalignment": 5.0,
                                 "impact": 100 * (1 - 1.05 * 0.8 / 1.025), "rolling": 12.5 + 100 / 11},
                    "accurate": {"thickness": 2.5, "misalignment": 2.5,
                                 "impact": 100 * (1 - 0.9), "rolling": 6.25 + 100 / 11}}
        dofs = {"fast": 1000, "standard": 2000, "accurate": 4000}
        for preset, errors in expected.items():
            b = (m.get(preset) or {}).get("measured") or {}
            for study, percent in errors.items():
                close((b.get("error_F_max", {}).get(study) or {}).get("percent"), percent,
                      f"{preset} {study} error")
            for key in ("fe_case_time", "impact_time", "rolling_time"):
                expect(isinstance(b.get(key), (int, float)) and b[key] > 0, f"{preset} {key}: {b.get(key)}")
            expect((b.get("case_times") or {}).get("misalignment", 0) > 0,
                   f"{preset} case_times.misalignment: {b.get('case_times')}")
            expect(b.get("fe_dofs") == dofs[preset], f"{preset} fe_dofs {b.get('fe_dofs')}")
            expect((b.get("dofs") or {}).get("impact") == dofs[preset], f"{preset} dofs: {b.get('dofs')}")
            expect((b.get("dofs") or {}).get("rolling") == 1000, f"{preset} rolling dofs: {b.get('dofs')}")
            expect(b.get("machine", {}).get("cores") == os.cpu_count(), f"{preset} machine {b.get('machine')}")
            expect(isinstance(b.get("date"), str) and "UTC" in b["date"], f"{preset} date {b.get('date')}")
            expect("--tiny" in b.get("note", ""), f"{preset} note says it is a smoke run: {b.get('note')}")
            where = (b.get("error_F_max", {}).get("thickness") or {}).get("where", "")
            expect("Richardson value over fast; standard; accurate" in where and "p = 1" in where,
                   f"{preset} thickness where names its reference: {where}")
        kept = m["fast"]["measured"]
        expect(kept.get("pipeline_time") == 66 and "from earlier: pipeline_time" in kept.get("note", ""),
               f"a figure not measured is kept and the note says so: {kept}")
        # ... with what was said of it: its comment, and the note before (one note back)
        text = open(p).read()
        expect("# [s] how it was timed, kept while the figure is" in text,
               "a kept figure keeps its comment")
        expect("a hand-typed comment, replaced" not in text, "a measured figure's comment is new")
        expect(kept.get("note", "").endswith(" || the previous note: typed by hand"),
               f"the note carries the note before it: {kept.get('note')}")

        # 1b. the same with --jobs 2 (runs beside each other, issue 32 item 2's command on two
        # cores): the same figures, and the same runs, each made once (a reference two parts
        # or two presets ask for is not made twice, however the pool orders them)
        p2 = os.path.join(d, "p2.yaml")
        with open(p2, "w") as f:
            f.write(PIPELINE)
        jobs = subprocess.run(command + ["--pipeline", p2, "--work", os.path.join(d, "work2"),
                                         "--jobs", "2", "--cpu-time"],
                              capture_output=True, text=True, cwd=d)
        expect(jobs.returncode == 0, f"measure_presets --jobs 2 exit {jobs.returncode}:\n"
                                     f"{jobs.stdout[-3000:]}\n{jobs.stderr[-3000:]}")
        m2 = yaml.safe_load(open(p2))["presets"]
        for preset in expected:
            one = {k: v.get("percent") for k, v in m[preset]["measured"]["error_F_max"].items()}
            two = {k: v.get("percent") for k, v in m2[preset]["measured"]["error_F_max"].items()}
            expect(one == two, f"{preset}: --jobs 2's figures {two} against one at a time {one}")

        def runs_made(stdout):  # "  run   STUDY, SPEC: command" (or "ref  "): one per run made
            return collections.Counter(l.split(": ")[0].split(None, 1)[1] for l in stdout.splitlines()
                                       if l.startswith(("  run  ", "  ref  ")))
        made = runs_made(jobs.stdout)
        expect(made == runs_made(done.stdout) and max(made.values(), default=0) == 1,
               f"--jobs 2 makes the runs one at a time makes, each once: {made} against "
               f"{runs_made(done.stdout)}")
        refused = subprocess.run(command + ["--jobs", "2", "--dry-run"], capture_output=True,
                                 text=True, cwd=d)
        expect(refused.returncode != 0 and "--cpu-time" in refused.stderr,
               f"--jobs 2 without --cpu-time refused: {refused.returncode} {refused.stderr}")

        # 2. run_pipeline reads the blocks and prints each FE task's time beside its figure
        run = subprocess.run([run_pipeline, p, "--no-plots", "--build-dir", build, "--jobs", "1"],
                             capture_output=True, text=True, cwd=d)
        log = run.stdout + run.stderr
        expect(run.returncode == 0, f"run_pipeline on the written file: exit {run.returncode}\n{log[-3000:]}")
        for task in ("fe/thickness/t_B=0.004", "fe/misalignment/theta=1", "fe/impact", "fe/rolling"):
            line = next((l for l in log.splitlines() if "done    " + task + " " in l), "")
            expect("(preset fast measured " in line, f"{task}'s time beside its figure: '{line}'")
        with open(os.path.join(d, "out", "r", "pipeline_summary.json")) as f:
            summary = json.load(f)
        keys = {t["name"]: (t.get("preset_time") or {}).get("key") for t in summary["tasks"]}
        expect(keys.get("fe/misalignment/theta=2") == "case_times.misalignment"
               and keys.get("fe/thickness/t_B=0.002") == "fe_case_time"
               and keys.get("fe/impact") == "impact_time" and keys.get("fe/rolling") == "rolling_time",
               f"the summary's tasks carry the figure they were compared with: {keys}")
        expect(summary.get("wall_time", {}).get("unit") == "s", "the summary has the run's wall time")

        # 3. a subset: one preset, one study (by fe_stage's scene name), times only — as CPU
        # times (--cpu-time, for a shared machine: the note says so)
        before = yaml.safe_load(open(p))["presets"]
        sub = subprocess.run(command + ["--presets", "fast", "--studies", "radial", "--times-only",
                                        "--cpu-time"],
                             capture_output=True, text=True, cwd=d)
        expect(sub.returncode == 0, f"the subset: exit {sub.returncode}\n{sub.stderr[-2000:]}")
        after = yaml.safe_load(open(p))["presets"]
        expect(after["standard"] == before["standard"] and after["accurate"] == before["accurate"],
               "the other presets untouched")
        a, b = after["fast"]["measured"], before["fast"]["measured"]
        expect(a["error_F_max"] == b["error_F_max"] and a["impact_time"] == b["impact_time"],
               "only the thickness case's time and DoFs measured")
        expect("fe_case_time, fe_dofs" in a["note"] and "error_F_max.thickness" in a["note"].split("from earlier")[1],
               f"the note says what this run wrote and what is older: {a['note']}")
        expect("--cpu-time (task times are CPU times" in a["note"], f"CPU times said: {a['note']}")
        expect(isinstance(a["fe_case_time"], (int, float)) and a["fe_case_time"] > 0,
               f"a CPU time written: {a['fe_case_time']}")

        # 4. the whole pipeline's time
        whole = subprocess.run(command + ["--presets", "fast", "--studies", "pipeline"],
                               capture_output=True, text=True, cwd=d)
        expect(whole.returncode == 0, f"--studies pipeline: exit {whole.returncode}\n{whole.stderr[-2000:]}")
        t = yaml.safe_load(open(p))["presets"]["fast"]["measured"].get("pipeline_time")
        expect(isinstance(t, (int, float)) and t > 0 and t != 66, f"pipeline_time measured: {t}")

        # 5. --tiny never writes the repository's own pipeline.yaml
        refuse = subprocess.run([sys.executable, os.path.join(ROOT, "bench", "measure_presets.py"),
                                 "--tiny", "--pipeline", os.path.join(ROOT, "pipeline.yaml")],
                                capture_output=True, text=True)
        expect(refuse.returncode != 0 and "give a copy with --pipeline" in refuse.stderr,
               f"--tiny on the repository's pipeline.yaml refused: {refuse.returncode} {refuse.stderr}")

        # 6. a bad figure typed by hand: an input error naming the key
        for old, new, key in [("fe_case_time: 259", "fe_case_time: -259", "presets.accurate.measured.fe_case_time"),
                              ("fe_case_time: 259", "fe_case_time: slow", "presets.accurate.measured.fe_case_time"),
                              ("fe_case_time: 259", "fe_case_time: 259\n      case_times: {radial: 3}",
                               "presets.accurate.measured.case_times.radial")]:
            with open(os.path.join(d, "bad.yaml"), "w") as f:
                f.write(PIPELINE.replace(old, new))
            chk = subprocess.run([run_pipeline, os.path.join(d, "bad.yaml"), "--check", "--build-dir", build],
                                 capture_output=True, text=True, cwd=d)
            expect(chk.returncode != 0 and key in chk.stderr + chk.stdout,
                   f"'{new}': exit {chk.returncode}, naming {key}: {chk.stderr[-600:]}")
    finally:
        if not bad:
            shutil.rmtree(d, ignore_errors=True)
        else:
            print(f"(scratch kept: {d})")

    if bad:
        print("FAILED:\n  " + "\n  ".join(bad))
        return 1
    print("measure_presets --tiny: valid measured blocks, read by run_pipeline; subsets; refusals: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
