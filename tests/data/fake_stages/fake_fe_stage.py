#!/usr/bin/python3
"""A stand-in for fe_stage in the pipeline's own tests (reuse, invalidation, interrupts, the
misalignment and geometry-swap contracts): writes force_penetration.csv from a power law
F = K·δ^n without any FE. Not a physics model.

    fake_fe_stage.py SCENE.yaml --output DIR
    fake_fe_stage.py SCENE.yaml --check      (validates only, as below)

What it imitates of the FE stage contract (docs/pipeline.md, SPEC §2):
- study radial (default): K grows with geometry.t_B.
- study impact: accepted by --check only (the impact study runs with the real fe_stage).
- study misalignment: needs misalignment.theta_deg [deg] and loading.journal: rigid; rejects
  θ > θ_max (paper Eq. 3, the closed form of docs/geometry.md) with exit 1, as fe_stage does
  (only round-off, 1e-12 relative, is forgiven). K falls with θ.
- geometry.mesh: must be an absolute path of an existing .msh (run_pipeline meshes a .geo
  first); K is scaled by a factor from the mesh file's sha256, so another mesh gives another law.
- missing geometry keys take the FE defaults (R_B 10, t_B 4, L_B 20, c_r 0.5, c_a 1 mm).
- manifest.json carries extra.scene (the fit stage embeds it in the law file).
Environment: CLEARJOINT_FAKE_SLEEP=<s> sleeps before writing (to be interrupted);
scene key fail: true exits 2 with a message (a failing stage)."""
import hashlib, json, math, os, sys, time

# --check: validate the scene as below and exit, like the real stage (writes nothing).
check = "--check" in sys.argv
scene_path, out = sys.argv[1], (None if check else sys.argv[3])
with open(scene_path) as f:
    text = "".join(l for l in f if not l.lstrip().startswith("#"))
scene = json.loads(text)


def input_error(key, value, allowed):
    print(f"fake fe_stage: {scene_path}: key '{key}' has value '{value}'; allowed: {allowed}",
          file=sys.stderr)
    sys.exit(1)


if scene.get("fail") and not check:
    print("fake fe_stage: increment 3 did not converge (requested by the test)", file=sys.stderr)
    sys.exit(2)
g = {"R_B": 0.010, "t_B": 0.004, "L_B": 0.020, "c_r": 0.0005, "c_a": 0.001}
g.update({k: v for k, v in scene.get("geometry", {}).items() if k in g})
K, n = 3.65952708e8 * g["t_B"] / 0.004, 1.0114

study = scene.get("study", "radial")
if study == "misalignment":
    if scene.get("loading", {}).get("journal") != "rigid":
        input_error("loading.journal", scene.get("loading", {}).get("journal"), "rigid (misalignment study)")
    theta = scene["misalignment"]["theta_deg"]
    R_J, L_J, c = g["R_B"] - g["c_r"], g["L_B"] - 2 * g["c_a"], g["c_r"]
    theta_max = math.degrees(2 * math.atan(2 * c / (L_J + math.sqrt(L_J ** 2 - 4 * c * (c + 2 * R_J)))))
    if not 0 <= theta <= theta_max * (1 + 1e-12):
        input_error("misalignment.theta_deg", theta, f"0 <= theta <= theta_max = {theta_max!r} deg")
    K *= 1.0 - 0.2 * theta / theta_max
elif study == "impact":
    if check:  # only its scene is checked here (the impact tests run the real fe_stage)
        sys.exit(0)
    input_error("study", study, "radial|misalignment (the fake stage does not run impacts)")
elif study != "radial":
    input_error("study", study, "radial|misalignment|impact")

mesh = scene.get("geometry", {}).get("mesh")
if mesh is not None:
    if not (mesh.startswith("/") and mesh.endswith(".msh") and os.path.isfile(mesh)):
        input_error("geometry.mesh", mesh, "an absolute path of an existing .msh file")
    with open(mesh, "rb") as f:
        K *= 1.0 + hashlib.sha256(f.read()).digest()[0] / 1000.0

if check:
    sys.exit(0)
time.sleep(float(os.environ.get("CLEARJOINT_FAKE_SLEEP", "0")))
os.makedirs(out, exist_ok=True)
with open(os.path.join(out, "force_penetration.csv"), "w") as f:
    f.write("# units: m,N\ndelta,force\n0,0\n")
    for i in range(1, 11):
        d = 5e-6 * i
        f.write(f"{d!r},{K * d ** n!r}\n")
with open(os.path.join(out, "manifest.json"), "w") as f:
    json.dump({"status": "complete", "outputs": [os.path.join(out, "force_penetration.csv")],
               "extra": {"scene": scene}}, f)
