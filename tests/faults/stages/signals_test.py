#!/usr/bin/python3
"""Signals inside a long step (issue 33 item 5): fe_stage on the radial scene at its own mesh
(no preset: 1923 cells, 56 925 DoFs, a setup of 3-11 s on 2 cores) interrupted during its setup, on one rank (SIGINT to fe_stage: exit 130) and on two
(SIGINT to mpirun, which sends its ranks SIGCONT, then SIGTERM 1 s later, then SIGKILL 1 s after
that, and exits 1 itself). Either way the stage must end within about a second of the signal
its ranks receive, print one line, and leave nothing: no DIR.tmp.<pid>, no DIR.

    signals_test.py FE_STAGE SOURCE_DIR SCRATCH_DIR
"""
import glob
import os
import shutil
import signal
import subprocess
import sys
import time

FE, SOURCE, SCRATCH = sys.argv[1:4]
failures = []


def interrupt(case, cmd, out, delay, expect_code, limit_s):
    for p in glob.glob(out + "*"):
        shutil.rmtree(p, ignore_errors=True)
    log = os.path.join(SCRATCH, case + ".log")
    with open(log, "w") as f:
        p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=SCRATCH)
    # the work folder exists once MPI has started and the scene is read: the setup is under way
    for _ in range(600):
        if glob.glob(out + ".tmp.*") or p.poll() is not None:
            break
        time.sleep(0.1)
    time.sleep(delay)
    t = time.time()
    p.send_signal(signal.SIGINT)
    rc = p.wait()
    seconds = time.time() - t
    time.sleep(0.5)
    left = sorted(glob.glob(out + "*"))
    text = open(log).read()
    errors = [l for l in text.splitlines() if l.startswith("error:")]
    problems = []
    if rc != expect_code:
        problems.append(f"exit {rc}, expected {expect_code}")
    if seconds > limit_s:
        problems.append(f"ended {seconds:.2f} s after the signal, limit {limit_s} s")
    if left:
        problems.append(f"left behind: {left}")
    if len(errors) != 1 or "interrupted by SIG" not in errors[0]:
        problems.append(f"expected one 'interrupted by' error line, got {errors}")
    print(f"[{case}] SIGINT {delay} s into the setup: exit {rc} {seconds:.2f} s after the signal; "
          f"{errors[0] if errors else 'no error line'}\n  " +
          ("ok" if not problems else "FAILED: " + "; ".join(problems)), flush=True)
    if problems:
        print(text[-3000:])
        failures.append(case)


CHILD = r"""
import importlib.util, os, sys, time
spec = importlib.util.spec_from_file_location("plot", sys.argv[1])
plot = importlib.util.module_from_spec(spec)
spec.loader.exec_module(plot)
plot.end_with_parent()  # what plot.py does first
time.sleep(60)
"""
PARENT = r"""
import os, subprocess, sys, time
env = dict(os.environ, CLEARJOINT_PLOT_PARENT=str(os.getpid()))
child = subprocess.Popen([sys.executable, "-c", sys.argv[2], sys.argv[1]], env=env)
print(child.pid, flush=True)
time.sleep(60)
"""


def plot_ends_with_its_stage():
    """A stage killed with SIGKILL: its plot.py ends too, also where run_pipeline's kill of
    the stage's process group does not reach it (an MPI rank has a group of its own)."""
    plot_py = os.path.join(SOURCE, "scripts", "plot.py")
    parent = subprocess.Popen([sys.executable, "-c", PARENT, plot_py, CHILD],
                              stdout=subprocess.PIPE, text=True)
    child = int(parent.stdout.readline())
    time.sleep(1.0)  # the child has asked for its SIGTERM
    parent.kill()
    parent.wait()
    gone = False
    for _ in range(50):
        try:
            with open(f"/proc/{child}/stat") as f:
                gone = f.read().split(") ")[1].startswith("Z")  # ended, not yet reaped
        except FileNotFoundError:
            gone = True
        if gone:
            break
        time.sleep(0.1)
    print(f"[plot_ends_with_its_stage] plot.py {'ended' if gone else 'STILL RUNNING'} after its "
          f"stage was killed with SIGKILL\n  {'ok' if gone else 'FAILED'}", flush=True)
    if not gone:
        os.kill(child, signal.SIGKILL)
        failures.append("plot_ends_with_its_stage")


def main():
    os.makedirs(SCRATCH, exist_ok=True)
    scene = os.path.join(SOURCE, "fe_stage", "scenes", "radial.yaml")
    out = os.path.join(SCRATCH, "out")
    # one rank: SIGINT reaches fe_stage, which stops within its 0.3 s grace (+ cleanup)
    interrupt("np1_setup", [FE, scene, "--output", out, "--no-plots"], out, 1.0, 130, 1.5)
    # two ranks: mpirun's SIGTERM comes 1 s after the SIGINT; rank 0 cleans up 0.3 s later,
    # before mpirun's SIGKILL; mpirun itself exits 1 (Open MPI 4.1) whatever its ranks return
    mpirun = shutil.which("mpirun")
    interrupt("np2_setup", [mpirun, "--allow-run-as-root", "--oversubscribe", "-np", "2",
                            FE, scene, "--output", out, "--no-plots"], out, 1.0, 1, 2.5)
    plot_ends_with_its_stage()
    print("signals: " + ("all cases pass" if not failures else "FAILED: " + ", ".join(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
