#!/usr/bin/python3
"""A stand-in for fe_stage in the pipeline's own tests (reuse, invalidation, interrupts):
writes force_penetration.csv from F = K·(t_B/4 mm)·δ^n without any FE. Not a physics model.

    fake_fe_stage.py SCENE.yaml --output DIR
Environment: CLEARJOINT_FAKE_SLEEP=<s> sleeps before writing (to be interrupted);
scene key fail: true exits 2 with a message (a failing stage)."""
import json, os, sys, time

scene_path, out = sys.argv[1], sys.argv[3]
with open(scene_path) as f:
    text = "".join(l for l in f if not l.lstrip().startswith("#"))
scene = json.loads(text)
if scene.get("fail"):
    print("fake fe_stage: increment 3 did not converge (requested by the test)", file=sys.stderr)
    sys.exit(2)
time.sleep(float(os.environ.get("CLEARJOINT_FAKE_SLEEP", "0")))
t_B = scene["geometry"]["t_B"]
K, n = 3.65952708e8 * t_B / 0.004, 1.0114
os.makedirs(out, exist_ok=True)
with open(os.path.join(out, "force_penetration.csv"), "w") as f:
    f.write("# units: m,N\ndelta,force\n0,0\n")
    for i in range(1, 11):
        d = 5e-6 * i
        f.write(f"{d!r},{K * d ** n!r}\n")
with open(os.path.join(out, "manifest.json"), "w") as f:
    json.dump({"status": "complete", "outputs": [os.path.join(out, "force_penetration.csv")]}, f)
