#!/usr/bin/env python3
"""Measures the presets' cost and error and writes pipeline.yaml's `measured` blocks (issue 32
item 2), so that no figure there is typed by hand.

    bench/measure_presets.py [--pipeline pipeline.yaml] [--plan bench/measure_presets.yaml]
        [--presets fast standard accurate] [--studies thickness misalignment impact impact_deformable rolling pipeline]
        [--times-only] [--tiny] [--set KEY=VALUE ...] [--build-dir build]
        [--run-pipeline build/pipeline/run_pipeline] [--work /tmp/clearjoint-measure]
        [--no-plots] [--dry-run] [--no-check] [--cpu-time] [--jobs N]

For each preset and study asked for, the plan (bench/measure_presets.yaml; its header says every
key) names the study's reference case and its reference. Every run goes through run_pipeline on
a generated pipeline file holding that one case with the pipeline's own presets, so whatever a
preset sets — uniform levels, adaptive cycles, a target error — is what gets measured:

- time [s]: the run_pipeline task's wall time (what run_pipeline prints beside the figure; with
  plots unless --no-plots), of the preset's own run, which always runs (--force), one task at
  a time; `pipeline` is the whole run_pipeline process on the pipeline file with --preset P;
  with --cpu-time instead the CPU time (user + system) of that run_pipeline process and its
  children — the task, and a few seconds of scene checks and impact_compare — for a shared
  machine, where the wall time measures the other sessions' load (one-rank tasks: their CPU time
  is what they take alone on a quiet core); `pipeline` keeps its wall time;
- DoFs: the case's manifest (extra.n_dofs; an impact sweep's first case);
- error [%]: |q − ref| / |ref| of the study's quantity against the plan's reference (Richardson
  over three runs, a single finer run, or a sum of parts such as time step + mesh), its `where`
  written out with the values, the order p and the date. Reference runs are reused from --work
  when their inputs are unchanged (run_pipeline's reuse), so a second preset costs only its own
  run. A reference that does not converge (not monotone) gives percent: null and says why;
  or, for an FE sweep (reference: recorded), the largest error over the sweep, the figure a
  preset quotes: the preset's own run at every sweep value the plan's `values` asks for (all,
  or a list) against that value's reference interval [F_low, F_high], recorded in a file of
  adaptive sequences (tests/data/fe/adaptive_sequences.txt; the plan names each value's
  sequence) — the upper figure against the far end, the lower against the near end (0 inside
  it) — its `where` listing each value's range and naming the values with no sequence (not
  run), the file, the journal and mu of the runs (checked against the plan's), the date and
  this command. `value` stays the case whose time and DoFs are written;
- machine (CPU model, cores), date and the load average before and after, in the block.

Only the asked presets' blocks change, and in them only the figures measured (the rest is kept
and the note says which figures this run wrote); the rest of the file — comments, order — is
untouched. The file is read back (yaml) and, unless --no-check, checked with `run_pipeline
--check`. --times-only measures times and DoFs and keeps the error entries (no reference runs).

--tiny uses bench/measure_presets_tiny.yaml: presets of 1.4-18 k DoFs (level 0, contact
refinements 0-2), three increments, one impact velocity — a smoke case of the machinery in
minutes with the real fe_stage, in seconds with the tests' stand-in stages. Its figures are not
the presets': it refuses to write the repository's own pipeline.yaml. --set KEY=VALUE adds a
scene key (YAML value) to every run.
--dry-run prints the new blocks without writing.

--jobs N runs up to N runs at once (each `run_pipeline --jobs 1`, one task: every preset's own
runs and every reference run their figures need, started together, each run once however many
parts ask for it); the figures are the same as one at a time. Each run's CPU time is its own
(its process's, from wait4), but a wall time beside other runs is not what the run takes alone,
so --jobs above 1 needs --cpu-time. The whole pipeline (`pipeline`) runs alone, after every
other run started.
"""
import argparse
import concurrent.futures
import csv
import datetime
import hashlib
import json
import math
import os
import shlex
import subprocess
import sys
import threading
import time

import yaml

import adaptive_sequences  # (bench/ is this script's own folder)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PRESETS = ["fast", "standard", "accurate"]
QUANTITY_TEXT = {"force_at_delta_max": ("F(δ_max)", "N"), "peak_force": ("peak force", "N"),
                 "plastic_dissipation": ("plastic dissipation at the end", "J")}
# The keys of `measured` this command writes, in the order written (error_F_max last).
ORDER = ["note", "date", "machine", "fe_dofs", "fe_case_time", "case_times", "dofs",
         "pipeline_time", "impact_time", "impact_deformable_time", "rolling_time", "error_F_max"]
UNITS = {"fe_dofs": "[1] DoFs of the thickness sweep's reference case",
         "fe_case_time": "[s] run_pipeline's task: the thickness sweep's reference case",
         "case_times": "[s] one FE case of these sweeps (run_pipeline's task)",
         "dofs": "[1] DoFs of these studies' reference cases",
         "pipeline_time": "[s] the whole run_pipeline run",
         "impact_time": "[s] run_pipeline's task: the FE impact sweep",
         "impact_deformable_time": "[s] run_pipeline's task: the FE impact sweep with the "
                                   "deformable journal",
         "rolling_time": "[s] run_pipeline's task: the FE rolling study"}


# Where a note carries the note before it (what it said of the figures kept from earlier).
EARLIER_NOTE = " || the previous note: "


class MeasureError(Exception):
    pass


PRINT_LOCK = threading.Lock()


def say(line):
    """Prints one whole line: the pool's threads (--jobs) print too, and print() writes the text
    and its newline apart, so two lines could run into one."""
    with PRINT_LOCK:
        sys.stdout.write(line + "\n")
        sys.stdout.flush()


def significant(x, digits=3):
    """x rounded to `digits` significant digits, as a float (or an int when whole)."""
    if x == 0 or not math.isfinite(x):
        return x
    r = round(x, digits - 1 - int(math.floor(math.log10(abs(x)))))
    return int(r) if float(r).is_integer() and abs(r) >= 10 ** (digits - 1) else r


def machine():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return {"cpu": cpu, "cores": os.cpu_count() or 1}


def load_average():
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


def read_csv(path):
    with open(path) as f:
        rows = [r for r in csv.reader(l for l in f if not l.startswith("#"))]
    return rows[0], rows[1:]


def richardson(values, ratio):
    """(ref, p) from three values, coarse to fine, each refined `ratio` times the last."""
    q1, q2, q3 = values
    d1, d2 = q1 - q2, q2 - q3
    if d2 == 0 or d1 / d2 <= 1:
        raise MeasureError(f"the three values {q1:.6g}, {q2:.6g}, {q3:.6g} do not converge "
                           f"(differences {d1:.3g}, {d2:.3g}: not of one sign and shrinking): "
                           f"no Richardson value")
    p = math.log(d1 / d2) / math.log(ratio)
    return q3 - d2 / (ratio ** p - 1), p


def fe_sweeps(pipeline):
    """The pipeline's FE sweeps: `fe_sweeps`, or `fe_studies` as files written before issue 29
    call them (run_pipeline reads both, with a warning)."""
    return pipeline.get("fe_sweeps") or pipeline.get("fe_studies") or []


# --- recorded references: an interval per sweep value, from a file of adaptive sequences -----

RECORDED_KEYS = ("file", "journal", "mu", "sequences")
# fe_stage's loading.journal values; a sequence's `journal` line says rigid or deformable only
JOURNALS = ("rigid", "end_faces", "axis_line", "core")
def read_sequences(path):
    """tests/data/fe/adaptive_sequences.txt's blocks (bench/adaptive_sequences.py), its errors
    as this command's."""
    try:
        return adaptive_sequences.read_sequences(path)
    except adaptive_sequences.SequenceFileError as e:
        raise MeasureError(str(e))


def same_value(a, b):
    """Sweep values as the plan and the pipeline write them: numbers to round-off (a YAML key
    0.010 is the pipeline's 0.01), names (theta_max) exactly."""
    number = lambda x: isinstance(x, (int, float)) and not isinstance(x, bool)  # noqa: E731
    if number(a) and number(b):
        return abs(a - b) <= 1e-9 * max(1.0, abs(a), abs(b))
    return a == b


def value_text(v, unit, resolved=None):
    """A sweep value as the docs write it: t_B in mm; a name with what it resolved to."""
    if isinstance(v, str):
        return v + (f" ({resolved:.6g} {unit})" if isinstance(resolved, (int, float)) else "")
    if unit == "m":
        return f"{v * 1e3:g} mm"
    return f"{v:g} {unit}"


def reference_parts(ref):
    """A plan's reference as its list of parts (a reference of one part has no `parts`)."""
    return ref["parts"] if "parts" in ref else [dict(ref, name="")]


def value_spec(preset, v):
    """The preset's own run at sweep value v (a recorded reference's other values)."""
    return {"preset": preset, "set": {}, "value": v}


def sweep_cases(study, entry, pipeline):
    """For an fe_sweep study whose reference is `recorded`: (recorded block, path of its file,
    [(sweep value, its sequence or None)]) over the values the study's `values` asks for. For
    any other study: None, after checking that it has no `values` (they need a recorded
    reference). Read before any run, so that a bad plan costs no run; every error names the
    plan's key and what it allows."""
    key = f"studies.{study}"
    ref = entry.get("reference") or {}
    if "recorded" not in ref:
        if "values" in entry:
            raise MeasureError(f"{key}.values: only with reference.recorded (the other references "
                               f"measure the error at the study's one `value`)")
        return None
    if entry.get("kind") != "fe_sweep":
        raise MeasureError(f"{key}.reference.recorded: only for kind fe_sweep, not '{entry.get('kind')}'")
    if len(ref) != 1:
        others = ", ".join(k for k in ref if k != "recorded")
        raise MeasureError(f"{key}.reference: 'recorded' alone, not with {others}")
    rec = ref["recorded"]
    if not isinstance(rec, dict):
        raise MeasureError(f"{key}.reference.recorded: a mapping with keys {', '.join(RECORDED_KEYS)}")
    for k in rec:
        if k not in RECORDED_KEYS:
            raise MeasureError(f"{key}.reference.recorded.{k}: unknown key "
                               f"(allowed: {', '.join(RECORDED_KEYS)})")
    for k in ("file", "journal", "sequences"):
        if k not in rec:
            raise MeasureError(f"{key}.reference.recorded.{k}: missing")
    if rec["journal"] not in JOURNALS:
        raise MeasureError(f"{key}.reference.recorded.journal: '{rec['journal']}' (allowed: "
                           f"{', '.join(JOURNALS)}, the runs' loading.journal)")
    if "mu" in rec and (isinstance(rec["mu"], bool) or not isinstance(rec["mu"], (int, float))
                        or not rec["mu"] >= 0):
        raise MeasureError(f"{key}.reference.recorded.mu: '{rec['mu']}' (a number >= 0, the runs' "
                           f"contact.mu)")
    if not isinstance(rec["sequences"], dict) or not rec["sequences"]:
        raise MeasureError(f"{key}.reference.recorded.sequences: a mapping of sweep value to "
                           f"sequence name, not '{rec['sequences']}'")
    path = rec["file"] if os.path.isabs(str(rec["file"])) else os.path.join(ROOT, str(rec["file"]))
    try:
        seqs = read_sequences(path)
    except OSError as e:
        raise MeasureError(f"{key}.reference.recorded.file: cannot read '{rec['file']}' ({e.strerror})")
    matching = [s for s in fe_sweeps(pipeline) if s["name"] == study]
    if not matching:
        raise MeasureError(f"{key}: the pipeline has no FE sweep '{study}'")
    swept = list(matching[0].get("values") or [])
    allowed = ", ".join(str(v) for v in swept)
    values = entry.get("values", [entry.get("value")])
    if values == "all":
        values = swept
    elif not isinstance(values, list) or not values:
        raise MeasureError(f"{key}.values: '{values}' (allowed: all, or a list of the sweep's "
                           f"values: {allowed})")
    for v in values:
        if not any(same_value(v, s) for s in swept):
            raise MeasureError(f"{key}.values: {v} is not a value of the pipeline's sweep ({allowed})")
    want = "rigid" if rec["journal"] == "rigid" else "deformable"
    named = []
    for v, name in rec["sequences"].items():
        at = f"{key}.reference.recorded.sequences.{v}"
        # a value the sweep does not have is a stale or mistyped key (a quoted "1.0" is no 1.0):
        # left alone, it would turn a measured value into "no reference" without a word
        if not any(same_value(v, s) for s in swept):
            raise MeasureError(f"{at}: {v} is not a value of the pipeline's sweep ({allowed})")
        if name not in seqs:
            raise MeasureError(f"{at}: '{name}' is no sequence of {rec['file']} (its sequences: "
                               + "; ".join(f"'{n}'" for n in seqs) + ")")
        journal = seqs[name].get("journal")
        if journal != want:
            raise MeasureError(f"{at}: '{name}' is a sequence of a {journal or 'unstated'} journal; "
                               f"reference.recorded.journal {rec['journal']} is a {want} one")
        named.append((v, seqs[name]))
    cases = []
    for v in values:
        seq = next((s for k, s in named if same_value(k, v)), None)
        cases.append((v, seq))
    return rec, path, cases


class Measurer:
    def __init__(self, args, pipeline, plan):
        self.args, self.pipeline, self.plan = args, pipeline, plan
        self.cwd = os.path.dirname(os.path.abspath(args.pipeline))
        self.results = {}  # run key → result
        self.forced = set()
        # --jobs: runs started and not yet read (run key → (Future, own)); the lock guards them
        # and `results`, which the pool's threads write
        self.pending = {}
        self.lock = threading.Lock()
        self.jobs = max(1, int(getattr(args, "jobs", 1) or 1))
        self.pool = concurrent.futures.ThreadPoolExecutor(max_workers=self.jobs)
        os.makedirs(os.path.join(args.work, "pipelines"), exist_ok=True)

    def preset_fe(self, preset):
        if "presets" in self.plan:
            return dict(self.plan["presets"][preset])
        return dict(((self.pipeline["presets"][preset] or {}).get("fe")) or {})

    def presets_block(self):
        return {p: {"fe": self.preset_fe(p) or None,
                    "mbd": (self.pipeline["presets"][p] or {}).get("mbd")} for p in PRESETS}

    def study_set(self, study):
        s = dict(self.plan["studies"][study].get("set") or {})
        s.update(self.args.set)
        return s

    @staticmethod
    def describe(spec):
        s = spec["preset"]
        if "value" in spec:  # a sweep value other than the study's `value` (recorded references)
            s += f" at {spec['value']}"
        if spec.get("set"):
            s += " with " + ", ".join(f"{k} = {json.dumps(v)}" for k, v in spec["set"].items())
        return s

    def pipeline_for(self, study, spec):
        """A pipeline file (as a dict) that runs `study`'s reference case as `spec` says."""
        entry = self.plan["studies"][study]
        extra = {**self.study_set(study), **(spec.get("set") or {})}
        presets = self.presets_block()
        p = {"schema": "clearjoint.pipeline/1", "output_root": os.path.join(self.args.work, "out"),
             "preset": spec["preset"], "mpi_ranks": self.pipeline.get("mpi_ranks", 1),
             "presets": presets, "fe_sweeps": [], "fit": self.pipeline.get("fit", {"weighting": "absolute"}),
             "mbd_runs": [], "report": False}
        kind = entry["kind"]
        if kind == "fe_sweep":
            matching = [s for s in fe_sweeps(self.pipeline) if s["name"] == study]
            if not matching:
                raise MeasureError(f"the pipeline has no FE sweep '{study}'")
            s = json.loads(json.dumps(matching[0]))
            # one case: the study's `value`, or another sweep value a recorded reference asks for
            s["values"] = [spec.get("value", entry["value"])]
            s["overrides"] = {**(s.get("overrides") or {}), **extra}
            # a sweep's own preset settings come after its overrides: `set` must win there too
            for name, own in (s.get("presets") or {}).items():
                s["presets"][name] = {**(own or {}), **extra}
            p["fe_sweeps"] = [s]
        elif kind == "impact":
            if "impact" not in self.pipeline:
                raise MeasureError("the pipeline has no impact study")
            fe = dict(presets[spec["preset"]]["fe"] or {})
            fe.update(extra)  # the impact study has no overrides of its own: after the preset
            presets[spec["preset"]]["fe"] = fe
            p["impact"] = {"scene": self.pipeline["impact"]["scene"],
                           "law": {"file": os.path.join(ROOT, "laws", "paper_tB4.json")}}
        elif kind == "impact_deformable":
            # the deformable journal's sweep as the impact study's own scene (one task, stage
            # fe_impact): the preset, then impact.deformable.overrides, then the plan's keys —
            # the order the pipeline's variant applies them in
            d = (self.pipeline.get("impact") or {}).get("deformable")
            if not d:
                raise MeasureError("the pipeline has no impact.deformable study")
            fe = dict(presets[spec["preset"]]["fe"] or {})
            fe.update(d.get("overrides") or {})
            fe.update(extra)
            presets[spec["preset"]]["fe"] = fe
            p["impact"] = {"scene": d["scene"],
                           "law": {"file": os.path.join(ROOT, "laws", "paper_tB4.json")}}
        elif kind == "rolling":
            if "rolling" not in self.pipeline:
                raise MeasureError("the pipeline has no rolling study")
            r = json.loads(json.dumps(self.pipeline["rolling"]))
            r["overrides"] = {**(r.get("overrides") or {}), **extra}
            # the block's own preset settings (rolling.presets) come after its overrides: `set`
            # must win there too
            for name, own in (r.get("presets") or {}).items():
                r["presets"][name] = {**(own or {}), **extra}
            p["rolling"] = r
        else:
            raise MeasureError(f"study '{study}': kind '{kind}' has no reference case")
        return p

    @staticmethod
    def key_of(pipeline):
        """A generated pipeline's identity: runs of equal keys are one run (made once, read twice)."""
        return hashlib.sha256(json.dumps(pipeline, sort_keys=True).encode()).hexdigest()[:10]

    def run_key(self, study, spec):
        return self.key_of(self.pipeline_for(study, spec))

    def run(self, study, spec, own):
        """One run of `study` as `spec` says: {seconds, outcome, value, dofs}. `own`: the
        preset's own run, whose time is measured now (--force)."""
        return self.start(study, spec, own).result()

    def start(self, study, spec, own):
        """The run's Future: started now on the pool (--jobs), or the one already started or
        done for the same inputs — a run is made once however many parts ask for it."""
        p = self.pipeline_for(study, spec)
        key = self.key_of(p)
        # a reference run that is also a preset's own run measured here is run as such
        own = own or (not spec.get("set") and spec["preset"] in self.args.presets
                      and study in self.studies)
        with self.lock:
            if key in self.results and (not own or key in self.forced):
                done = concurrent.futures.Future()
                done.set_result(self.results[key])
                return done
            earlier = self.pending.get(key, (None, False))
            if earlier[0] and (not own or earlier[1]):
                return earlier[0]
            # the same inputs still going as a reference: the forced run after it, not beside it
            # (one output folder); the pool starts in order, so `earlier` is ahead of it
            future = self.pool.submit(self.execute, study, spec, own, p, key, earlier[0])
            self.pending[key] = (future, own)
            return future

    def start_all(self, preset, studies):
        """--jobs above 1: starts every run the preset's figures need (each study's own run,
        then its references), so that the pool runs them N at a time (in the order started)."""
        for study in studies:
            for spec, own in self.runs_needed(study, preset):
                self.start(study, spec, own)

    def runs_needed(self, study, preset):
        """[(spec, own)]: the runs measure() will ask for (the same specs: the same keys)."""
        entry = self.plan["studies"][study]
        if entry["kind"] == "pipeline":
            return []
        needed = [({"preset": preset, "set": {}}, True)]
        if self.args.times_only:
            return needed
        ref = entry.get("reference") or {}
        if "recorded" in ref:
            _, _, cases = sweep_cases(study, entry, self.pipeline)
            return needed + [(value_spec(preset, v), False) for v, seq in cases
                             if seq is not None and not same_value(v, entry["value"])]
        for part in reference_parts(ref):
            runs = self.part_runs(study, part, preset)
            if runs is not None:
                of, richardson, finer = runs
                specs = ([of] if of else []) + richardson + ([finer] if finer else [])
                needed += [(s, False) for s in specs]
        return needed

    def wait_for_runs(self):
        """Waits for every run started (their failures are read where they are asked for)."""
        with self.lock:
            futures = [f for f, _ in self.pending.values()]
        concurrent.futures.wait(futures)

    def execute(self, study, spec, own, p, key, after=None):
        """Makes the run (on the pool's thread): run_pipeline on a generated file, once the
        Future `after` (the same run as a reference) is done."""
        if after is not None:
            concurrent.futures.wait([after])
        name = f"{study}-{spec['preset']}-{key}"
        p["run"] = name
        path = os.path.join(self.args.work, "pipelines", name + ".yaml")
        with open(path, "w") as f:
            json.dump(p, f, indent=1)
        cmd = [self.args.run_pipeline, path, "--build-dir", self.args.build_dir, "--jobs", "1"]
        if own:
            cmd.append("--force")
        if self.args.no_plots:
            cmd.append("--no-plots")
        say(f"  {'run  ' if own else 'ref  '} {study}, {self.describe(spec)}: {' '.join(cmd)}")
        # the run's own CPU time (its process and the children it waited for: the task) from
        # wait4, which other runs going on at once (--jobs) do not add to
        log = os.path.join(self.args.work, "pipelines", name + ".log")
        with open(log, "w") as out:
            child = subprocess.Popen(cmd, cwd=self.cwd, stdout=out, stderr=subprocess.STDOUT)
            _, status, usage = os.wait4(child.pid, 0)
        child.returncode = os.waitstatus_to_exitcode(status)
        cpu = usage.ru_utime + usage.ru_stime
        if child.returncode != 0:
            with open(log) as f:
                tail = f.read()[-3000:]
            raise MeasureError(f"run_pipeline failed ({child.returncode}) for {study}, "
                               f"{self.describe(spec)} (its log: {log}):\n{tail}")
        with open(os.path.join(self.args.work, "out", name, "pipeline_summary.json")) as f:
            summary = json.load(f)
        stage = {"fe_sweep": "fe_stage", "impact": "fe_impact", "impact_deformable": "fe_impact",
                 "rolling": "fe_rolling"}[
            self.plan["studies"][study]["kind"]]
        tasks = [t for t in summary["tasks"] if t["stage"] == stage]
        if len(tasks) != 1:
            raise MeasureError(f"{name}: expected one {stage} task, found {len(tasks)}")
        t = tasks[0]
        try:
            result = {"seconds": cpu if self.args.cpu_time else t["wall_time"]["value"],
                      "wall": t["wall_time"]["value"], "cpu": cpu, "outcome": t["outcome"],
                      "value": self.quantity(study, t["output_dir"]),
                      "dofs": self.dofs(t["output_dir"]), "name": name,
                      "out": t["output_dir"]}
        except (OSError, ValueError, KeyError, IndexError, TypeError) as e:
            raise MeasureError(f"{name}: cannot read the result in {t['output_dir']}: {e!r}")
        say(f"        {name}: {t['outcome']} in {result['wall']:.1f} s (run_pipeline's CPU "
            f"{cpu:.1f} s): {result['value']!r}" + (f", {result['dofs']} DoFs" if result["dofs"] else ""))
        with self.lock:
            self.results[key] = result
            if own:
                self.forced.add(key)
        return result

    def quantity(self, study, out):
        entry = self.plan["studies"][study]
        q = entry["quantity"]
        if q == "force_at_delta_max":
            head, rows = read_csv(os.path.join(out, "force_penetration.csv"))
            return float(rows[-1][head.index("force")])
        if q == "peak_force":
            head, rows = read_csv(os.path.join(out, "impact_sweep.csv"))
            v = float(entry["velocity"])
            for r in rows:
                if abs(float(r[head.index("v_in_m_per_s")]) - v) <= 1e-9 * max(1.0, abs(v)):
                    return float(r[head.index("peak_force_N")])
            raise MeasureError(f"{out}/impact_sweep.csv has no velocity {v} m/s")
        if q == "plastic_dissipation":
            head, rows = read_csv(os.path.join(out, "rolling_history.csv"))
            return float(rows[-1][head.index("plastic_dissipation")])
        raise MeasureError(f"study '{study}': unknown quantity '{q}'")

    @staticmethod
    def dofs(out):
        try:
            with open(os.path.join(out, "manifest.json")) as f:
                m = json.load(f)
        except (OSError, ValueError):
            return None
        if "n_dofs" in m.get("extra", {}):
            return int(m["extra"]["n_dofs"])
        for o in m.get("outputs", []):  # a sweep: its cases' manifests ({path, sha256})
            o = o.get("path", "") if isinstance(o, dict) else o
            if o.endswith("manifest.json") and os.path.isfile(o):
                with open(o) as f:
                    n = json.load(f).get("extra", {}).get("n_dofs")
                if n:
                    return int(n)
        return None

    def spec(self, s, preset):
        return {"preset": (s or {}).get("preset", preset), "set": dict((s or {}).get("set") or {})}

    def part_runs(self, study, part, preset):
        """(of, richardson, finer): the runs one part of a reference compares, as specs — `of`
        (None: the preset's own run), the Richardson runs ([] if none), the finer run (None if
        none) — or None for a part whose `of` and finer run are one run (the finest preset
        against the finest reference of that part, e.g. the accurate preset's mesh part): it
        would say 0 %, so it is left out, and no run is made for it. error() and runs_needed()
        both read the parts here, so --jobs starts exactly the runs error() asks for."""
        of = self.spec(part["of"], preset) if "of" in part else None
        finer = self.spec(part["run"], preset) if "run" in part else None
        if of is not None and finer is not None and \
                self.run_key(study, of) == self.run_key(study, finer):
            return None
        return of, [self.spec(s, preset) for s in part.get("richardson") or []], finer

    def error(self, study, preset, own_value):
        """(percent or None, where)"""
        entry = self.plan["studies"][study]
        what, unit = QUANTITY_TEXT[entry["quantity"]]
        case = ""
        if entry["kind"] == "fe_sweep":
            s = [x for x in fe_sweeps(self.pipeline) if x["name"] == study][0]
            case = f"{s['parameter']['name']} = {entry['value']} {s['parameter']['unit']}, "
        elif entry["kind"] == "impact":
            case = f"v = {entry['velocity']} m/s, "
        elif entry["kind"] == "impact_deformable":
            case = f"deformable journal, v = {entry['velocity']} m/s, "
        total, texts = 0.0, []
        for part in reference_parts(entry["reference"]):
            runs = self.part_runs(study, part, preset)
            if runs is None:
                texts.append(f"{part.get('name') or 'a part'} not included (its reference is "
                             f"this preset's own run: nothing finer measured)")
                continue
            of_spec, richardson_specs, finer = runs
            of = self.run(study, of_spec, False)["value"] if of_spec else own_value
            try:
                if richardson_specs:
                    values = [self.run(study, s, False)["value"] for s in richardson_specs]
                    ratio = float(part.get("ratio", 2))
                    r, order = richardson(values, ratio)
                    how = (f"the Richardson value over {'; '.join(self.describe(s) for s in richardson_specs)} "
                           f"({', '.join(f'{v:.6g}' for v in values)} {unit}; p = {order:.3g})")
                elif finer:
                    r = self.run(study, finer, False)["value"]
                    how = f"the finer run {self.describe(finer)}"
                else:
                    raise MeasureError(f"study '{study}': a reference needs richardson, run or parts")
            except MeasureError as e:
                return None, (f"{what}, {case}preset {preset}: not measurable — {e}; "
                              f"bench/measure_presets.py, {self.date}")
            e = 100.0 * abs(of - r) / abs(r)
            total += e
            name = f"{significant(e)} % from {part['name']}: " if part.get("name") else ""
            of_text = f" ({self.describe(of_spec)})" if of_spec else ""
            texts.append(f"{name}{of:.6g} {unit}{of_text} against {r:.6g} {unit}, {how}")
        if total >= 100.0:
            return None, (f"{what}, {case}preset {preset}: {total:.3g} % — 100 % or more is no "
                          f"estimate; " + "; ".join(texts))
        return significant(total), (f"{what}, {case}preset {preset}: " + " plus ".join(texts) +
                                    f"; bench/measure_presets.py, {self.date}")

    def recorded_error(self, study, preset, own):
        """(percent, where): the largest error over the sweep values with a recorded reference
        interval [F_low, F_high] (plan: reference.recorded), each the preset's own run at that
        value against the interval — the upper figure against the far end, the lower against
        the near end (0 inside it) — as the figure quoted is the largest over the sweep."""
        entry = self.plan["studies"][study]
        rec, _, cases = sweep_cases(study, entry, self.pipeline)
        sweep = [x for x in fe_sweeps(self.pipeline) if x["name"] == study][0]
        pname, punit = sweep["parameter"]["name"], sweep["parameter"]["unit"]
        what, unit = QUANTITY_TEXT[entry["quantity"]]
        rows, missing, scenes = [], [], []
        for v, seq in cases:
            if seq is None:
                missing.append(value_text(v, punit))
                continue
            r = own if same_value(v, entry["value"]) else \
                self.run(study, value_spec(preset, v), False)
            scene = self.run_scene(study, r, rec)
            scenes.append(scene)
            resolved = scene
            for k in str(sweep["parameter"].get("key", "")).split("."):  # e.g. theta_max's degrees
                resolved = resolved.get(k) if isinstance(resolved, dict) else None
            q, (lo, hi) = r["value"], seq["reference"]
            e_lo, e_hi = 100.0 * abs(q - lo) / abs(lo), 100.0 * abs(q - hi) / abs(hi)
            lower = 0.0 if lo <= q <= hi else min(e_lo, e_hi)
            rows.append({"text": value_text(v, punit, resolved), "short": value_text(v, punit),
                         "q": q, "lo": lo, "hi": hi,
                         "lower": lower, "upper": max(e_lo, e_hi), "name": seq["name"]})
        if not rows:
            raise MeasureError(f"studies.{study}: none of the values measured has a sequence in "
                               f"reference.recorded.sequences")
        worst = max(rows, key=lambda x: x["upper"])
        journal = scenes[0].get("loading", {}).get("journal")
        mu = scenes[0].get("contact", {}).get("mu")
        text = (f"{what}, preset {preset}, the largest over {pname} (at {worst['short']}): "
                + ", ".join(f"{significant(x['lower']) or 0}-{significant(x['upper'])} % at {x['text']} "
                            f"({x['q']:.6g} {unit})" for x in rows)
                + (f"; {pname} = {', '.join(missing)}: no reference (not measured)" if missing else "")
                + f"; against each value's reference interval [F_low, F_high] in {rec['file']} "
                  f"(the lower figure against its near end, 0 inside it; the upper, the one quoted, "
                  f"against its far end): "
                + "; ".join(f"{x['short']} [{x['lo']:.6g}, {x['hi']:.6g}] {unit} \"{x['name']}\""
                            for x in rows)
                + f"; the preset's own run at each value, loading.journal {journal}, contact.mu {mu}; "
                  f"{self.command}, {self.date}")
        if worst["upper"] >= 100.0:
            return None, f"{worst['upper']:.3g} % — 100 % or more is no estimate; " + text
        return significant(worst["upper"]), text

    def run_scene(self, study, result, rec):
        """The scene a run used (its manifest's extra.scene), checked against the journal and
        mu the recorded sequences were run with: another journal's interval is another
        quantity's (the end-face-loaded journal's F is not the core-loaded one's)."""
        try:
            with open(os.path.join(result["out"], "manifest.json")) as f:
                scene = json.load(f)["extra"]["scene"]
        except (OSError, ValueError, KeyError, TypeError) as e:
            raise MeasureError(f"{result['name']}: no extra.scene in its manifest ({e!r}): cannot "
                               f"check its journal against reference.recorded.journal")
        journal = (scene.get("loading") or {}).get("journal")
        if journal != rec["journal"]:
            raise MeasureError(f"studies.{study}.reference.recorded.journal is {rec['journal']}, but "
                               f"the run {result['name']} loaded its journal by '{journal}' (its "
                               f"manifest's extra.scene.loading.journal): the recorded sequences "
                               f"are of another journal")
        mu = (scene.get("contact") or {}).get("mu")
        if "mu" in rec and not (isinstance(mu, (int, float)) and same_value(float(mu), float(rec["mu"]))):
            raise MeasureError(f"studies.{study}.reference.recorded.mu is {rec['mu']}, but the run "
                               f"{result['name']} has contact.mu {mu} (its manifest's extra.scene)")
        return scene

    def measure(self, preset, study, block, wrote):
        entry = self.plan["studies"][study]
        say(f"{preset} / {study}")
        if entry["kind"] == "pipeline":
            seconds = self.whole_pipeline(preset)
            set_key(block, entry["time_key"], significant(seconds))
            wrote.append(entry["time_key"])
            return
        own = self.run(study, {"preset": preset, "set": {}}, True)
        set_key(block, entry["time_key"], significant(own["seconds"]))
        wrote.append(entry["time_key"])
        if own["dofs"] and entry.get("dofs_key"):
            set_key(block, entry["dofs_key"], own["dofs"])
            wrote.append(entry["dofs_key"])
        if not self.args.times_only:
            if "recorded" in (entry.get("reference") or {}):
                percent, where = self.recorded_error(study, preset, own)
            else:
                percent, where = self.error(study, preset, own["value"])
            block.setdefault("error_F_max", {})[study] = {"percent": percent, "where": where}
            wrote.append("error_F_max." + study)

    def whole_pipeline(self, preset):
        self.wait_for_runs()  # the whole pipeline's time is its own: nothing else running
        path = os.path.abspath(self.args.pipeline)
        if "presets" in self.plan:  # the tiny presets: a copy of the pipeline with them
            p = yaml.safe_load(open(path))
            p["presets"] = self.presets_block()
            path = os.path.join(self.args.work, "pipelines", f"whole-{preset}.yaml")
            with open(path, "w") as f:
                json.dump(p, f, indent=1)
        out = os.path.join(self.args.work, f"pipeline-{preset}")
        cmd = [self.args.run_pipeline, path, "--preset", preset, "--force", "--build-dir",
               self.args.build_dir, "--output-root", out]
        if self.args.no_plots:
            cmd.append("--no-plots")
        print("  run   " + " ".join(cmd), flush=True)
        start = time.monotonic()
        done = subprocess.run(cmd, cwd=self.cwd, capture_output=True, text=True)
        seconds = time.monotonic() - start
        if done.returncode != 0:
            raise MeasureError(f"the whole pipeline failed ({done.returncode}):\n{done.stderr[-3000:]}")
        print(f"        ran in {seconds:.1f} s", flush=True)
        return seconds


def set_key(block, dotted, value):
    keys = dotted.split(".")
    d = block
    for k in keys[:-1]:
        if not isinstance(d.get(k), dict):
            d[k] = {}
        d = d[k]
    d[keys[-1]] = value


# --- writing the measured blocks into the pipeline file's text ------------------------------

def scalar(v):
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    return json.dumps(v, ensure_ascii=False)  # a YAML double-quoted scalar


def flow(d):
    return "{" + ", ".join(f"{k}: {flow(v) if isinstance(v, dict) else scalar(v)}"
                           for k, v in d.items()) + "}"


def block_text(block, indent, comments=None):
    """The block's lines; a key in `comments` keeps that comment (a figure this run did not
    measure keeps what was said of it), the others get the unit's."""
    comments = comments or {}
    pad = " " * indent
    lines = [pad + "measured:  # written by bench/measure_presets.py (docs/benchmarks.md "
                   "\"Preset figures\"): do not edit by hand"]
    keys = [k for k in ORDER if k in block] + [k for k in block if k not in ORDER]
    for k in keys:
        v = block[k]
        if k == "error_F_max":
            lines.append(f"{pad}  error_F_max:")
            for study, e in v.items():
                lines.append(f"{pad}    {study}: {flow(e)}")
            continue
        text = f"{pad}  {k}: {flow(v) if isinstance(v, dict) else scalar(v)}"
        if k in comments:
            text = text.ljust(indent + 30) + "  # " + comments[k]
        elif k in UNITS:
            text = text.ljust(indent + 30) + "  # " + UNITS[k]
        lines.append(text)
    return lines


def find_block(lines, preset):
    """(start, end, indent) of presets.<preset>.measured in the file's lines, end exclusive;
    start None when the preset has no measured block (then end is where one goes)."""
    def indent_of(line):
        return len(line) - len(line.lstrip(" "))

    def content(line):
        s = line.strip()
        return s and not s.startswith("#")

    top = next((i for i, l in enumerate(lines) if l.startswith("presets:")), None)
    if top is None:
        raise MeasureError("no top-level 'presets:' block (a block mapping) in the pipeline file")
    i, child = top + 1, None
    while i < len(lines) and not (content(lines[i]) and indent_of(lines[i]) == 0):
        if content(lines[i]):
            child = indent_of(lines[i]) if child is None else child
            if indent_of(lines[i]) == child and lines[i].strip().startswith(preset + ":"):
                break
        i += 1
    else:
        raise MeasureError(f"no 'presets: {preset}:' block mapping in the pipeline file")
    p_indent = indent_of(lines[i])
    if lines[i].strip() != preset + ":":
        raise MeasureError(f"presets.{preset} is not a block mapping ('{preset}:' on a line of its own)")
    j, last = i + 1, i
    while j < len(lines) and not (content(lines[j]) and indent_of(lines[j]) <= p_indent):
        if content(lines[j]):
            last = j
            if lines[j].strip().startswith("measured:"):
                m_indent = indent_of(lines[j])
                k, end = j + 1, j + 1
                while k < len(lines) and not (content(lines[k]) and indent_of(lines[k]) <= m_indent):
                    if content(lines[k]):
                        end = k + 1
                    k += 1
                return j, end, m_indent
        j += 1
    return None, last + 1, p_indent + 2


def old_comments(lines, indent, keys):
    """The comments beside the block's top-level `keys` in its old lines (`key: value  # text`;
    the last "  # " on the line, as this command writes them)."""
    out = {}
    for line in lines:
        stripped = line.strip()
        if len(line) - len(line.lstrip(" ")) != indent + 2 or "  # " not in line:
            continue
        key = stripped.split(":", 1)[0]
        if key in keys:
            out[key] = line.rsplit("  # ", 1)[1].strip()
    return out


def write_blocks(path, blocks, dry_run, kept=None):
    """Writes each preset's block in place; `kept`: per preset, the top-level keys whose figures
    this run did not measure (their comments stay)."""
    kept = kept or {}
    with open(path) as f:
        lines = f.read().split("\n")
    for preset in PRESETS:  # in the file's order, one at a time (line numbers move)
        if preset not in blocks:
            continue
        start, end, indent = find_block(lines, preset)
        comments = old_comments(lines[start:end], indent, kept.get(preset, ())) \
            if start is not None else {}
        new = block_text(blocks[preset], indent, comments)
        if start is None:
            lines[end:end] = new
        else:
            lines[start:end] = new
        if dry_run:
            print("\n".join(new))
    text = "\n".join(lines)
    parsed = yaml.safe_load(text)  # read back: the blocks must be what was meant
    for preset, block in blocks.items():
        back = parsed["presets"][preset]["measured"]
        if json.loads(json.dumps(back, default=str)) != json.loads(json.dumps(block, default=str)):
            raise MeasureError(f"presets.{preset}.measured does not read back as written")
    if not dry_run:
        tmp = path + ".measure.tmp"
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, path)


def parse_set(items):
    out = {}
    for item in items:
        if "=" not in item:
            raise SystemExit(f"--set {item}: expected KEY=VALUE")
        k, v = item.split("=", 1)
        out[k] = yaml.safe_load(v)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pipeline", default=os.path.join(ROOT, "pipeline.yaml"))
    ap.add_argument("--plan", default=None, help="default bench/measure_presets.yaml")
    ap.add_argument("--presets", nargs="+", choices=PRESETS, default=PRESETS)
    ap.add_argument("--studies", nargs="+", default=None,
                    help="default: every study of the plan (a smoke plan: all but pipeline)")
    ap.add_argument("--times-only", action="store_true",
                    help="times and DoFs only; keep the error entries (no reference runs)")
    ap.add_argument("--tiny", action="store_true", help="the smoke plan bench/measure_presets_tiny.yaml")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a scene key for every run (YAML value)")
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    ap.add_argument("--run-pipeline", default=None, help="default BUILD_DIR/pipeline/run_pipeline")
    ap.add_argument("--work", default="/tmp/clearjoint-measure")
    ap.add_argument("--no-plots", action="store_true", help="tasks without their plots (not what a default run does)")
    ap.add_argument("--dry-run", action="store_true", help="print the blocks, write nothing")
    ap.add_argument("--no-check", action="store_true", help="skip run_pipeline --check afterwards")
    ap.add_argument("--cpu-time", action="store_true",
                    help="a task's time is the CPU time of its run_pipeline run, not the task's "
                         "wall time (a shared machine; one-rank tasks)")
    ap.add_argument("--jobs", type=int, default=1, metavar="N",
                    help="up to N runs at once, of every preset asked for (each one run_pipeline "
                         "task); above 1 needs --cpu-time")
    args = ap.parse_args(argv)
    if args.jobs < 1:
        raise SystemExit(f"measure_presets: --jobs {args.jobs}: the number of runs at once must be 1 or more")
    if args.jobs > 1 and not args.cpu_time:
        raise SystemExit(f"measure_presets: --jobs {args.jobs} runs beside each other, where a wall "
                         f"time is not what a run takes alone: add --cpu-time (each run's own CPU "
                         f"time), or use --jobs 1")
    args.set = parse_set(args.set)
    args.build_dir = os.path.abspath(args.build_dir)
    args.work = os.path.abspath(args.work)
    args.run_pipeline = os.path.abspath(args.run_pipeline or os.path.join(args.build_dir, "pipeline", "run_pipeline"))
    plan_path = args.plan or os.path.join(ROOT, "bench", "measure_presets_tiny.yaml" if args.tiny
                                          else "measure_presets.yaml")
    with open(plan_path) as f:
        plan = yaml.safe_load(f)
    for entry in (plan.get("studies") or {}).values():  # the kind's name before issue 29
        if entry.get("kind") == "fe_study":
            entry["kind"] = "fe_sweep"
    smoke = bool(plan.get("smoke"))
    pipeline_path = os.path.abspath(args.pipeline)
    if smoke and not args.dry_run and pipeline_path == os.path.join(ROOT, "pipeline.yaml"):
        raise SystemExit("measure_presets: --tiny figures are not the presets'; it does not write "
                         "the repository's pipeline.yaml: give a copy with --pipeline")
    with open(pipeline_path) as f:
        pipeline = yaml.safe_load(f)
    if args.studies:  # the thickness study runs fe_stage's radial scene
        args.studies = ["thickness" if s == "radial" and "radial" not in plan["studies"] else s
                        for s in args.studies]
    studies = args.studies or [s for s in plan["studies"] if not (smoke and s == "pipeline")]
    for s in studies:
        if s not in plan["studies"]:
            raise SystemExit(f"measure_presets: --studies {s}: not in {plan_path} "
                             f"({', '.join(plan['studies'])})")
        kind = plan["studies"][s]["kind"]
        present = {"fe_sweep": any(x["name"] == s for x in fe_sweeps(pipeline)),
                   "impact": "impact" in pipeline, "rolling": "rolling" in pipeline,
                   "impact_deformable": "deformable" in (pipeline.get("impact") or {}),
                   "pipeline": True}[kind]
        if not present and args.studies:
            raise SystemExit(f"measure_presets: --studies {s}: {pipeline_path} has no such study")
    studies = [s for s in studies if plan["studies"][s]["kind"] == "pipeline"
               or (plan["studies"][s]["kind"] == "fe_sweep"
                   and any(x["name"] == s for x in fe_sweeps(pipeline)))
               or (plan["studies"][s]["kind"] == "impact_deformable"
                   and "deformable" in (pipeline.get("impact") or {}))
               or (plan["studies"][s]["kind"] != "fe_sweep" and plan["studies"][s]["kind"] in pipeline)]

    for s in studies:  # a recorded reference's plan, checked before any run
        try:
            sweep_cases(s, plan["studies"][s], pipeline)
        except MeasureError as e:
            raise SystemExit(f"measure_presets: {plan_path}: {e}")

    m = Measurer(args, pipeline, plan)
    m.studies = studies
    # the command, as a recorded error's `where` quotes it (how to measure it again)
    m.command = " ".join(["bench/measure_presets.py"] + [shlex.quote(a) for a in
                                                         (sys.argv[1:] if argv is None else argv)])
    now = datetime.datetime.now(datetime.timezone.utc)
    m.date = now.strftime("%Y-%m-%d %H:%M UTC")
    where_machine = machine()
    load_before = load_average()
    blocks, failures, kept_keys = {}, [], {}
    for preset in args.presets if m.jobs > 1 else []:  # every preset's runs at once: no core idles
        try:                                             # between one preset's last run and the next's
            m.start_all(preset, studies)
        except MeasureError as e:  # a plan that names no runnable case: measure() says it again
            print(f"  (not started at once: {e})", file=sys.stderr, flush=True)
    for preset in args.presets:
        old = ((pipeline["presets"].get(preset) or {}).get("measured")) or {}
        block = json.loads(json.dumps(old, default=str))
        block.setdefault("error_F_max", {})
        wrote = []
        for study in studies:
            try:
                m.measure(preset, study, block, wrote)
            except MeasureError as e:
                failures.append(f"{preset} / {study}: {e}")
                print(f"  FAILED: {e}", file=sys.stderr, flush=True)
        if not wrote:
            continue
        load_after = load_average()
        block["date"] = m.date
        block["machine"] = where_machine
        kept = sorted(k for k in old if k not in ("note", "date", "machine", "error_F_max")
                      and not any(w == k or w.startswith(k + ".") for w in wrote))
        kept += sorted("error_F_max." + s for s in old.get("error_F_max") or {}
                       if "error_F_max." + s not in wrote)
        note = (f"bench/measure_presets.py{' --tiny (smoke run: NOT the presets figures)' if smoke else ''}"
                f"{' --cpu-time (task times are CPU times: a shared machine)' if args.cpu_time else ''}"
                f" on {m.date}, load average {load_before:.1f} before and {load_after:.1f} after: "
                f"{', '.join(wrote)}")
        if kept:
            note += f"; from earlier: {', '.join(kept)}"
            # what the last note said of them (where they came from), one note back: the note
            # before that is not carried, or the notes would grow with every run
            earlier = str(old.get("note", "")).split(EARLIER_NOTE)[0].strip()
            if earlier:
                note += EARLIER_NOTE + earlier
        block["note"] = note
        blocks[preset] = block
        kept_keys[preset] = {k.split(".")[0] for k in kept}
    if blocks:
        write_blocks(pipeline_path, blocks, args.dry_run, kept_keys)
        print(("would write" if args.dry_run else "wrote") + f" presets {', '.join(blocks)} of {pipeline_path}")
        if not args.dry_run and not args.no_check:
            check = subprocess.run([args.run_pipeline, pipeline_path, "--check", "--build-dir",
                                    args.build_dir], cwd=os.path.dirname(pipeline_path),
                                   capture_output=True, text=True)
            if check.returncode != 0:
                failures.append(f"run_pipeline --check of the written file failed:\n{check.stderr[-3000:]}")
    m.pool.shutdown(wait=True)
    for f in failures:
        print("measure_presets: " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
