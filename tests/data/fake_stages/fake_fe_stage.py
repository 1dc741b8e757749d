#!/usr/bin/python3
"""A stand-in for fe_stage in the pipeline's own tests (reuse, invalidation, interrupts, the
misalignment and geometry-swap contracts): writes force_penetration.csv from a power law
F = K·δ^n without any FE. Not a physics model.

    fake_fe_stage.py SCENE.yaml --output DIR
    fake_fe_stage.py SCENE.yaml --check      (validates only, as below)

What it imitates of the FE stage contract (docs/pipeline.md, SPEC §2):
- study radial (default): K grows with geometry.t_B.
- study impact: accepted by --check (impact.steps_per_period checked); run only with scene key fake_discretisation: true (below),
  writing impact_sweep.csv (v_in_m_per_s, peak_force_N, delta_max_m) for sweep.velocity and a
  manifest (the impact tests run the real fe_stage).
- scene key fake_discretisation: true (for bench/measure_presets.py's test): the results carry a
  made-up discretisation error that converges with order 1 — F and the peak force scale by
  1 + 0.1 h with h = 2^-(mesh.global_refinements + mesh.contact_refinements) (defaults 0, 1),
  the peak force also by 1 - 4 / impact.steps_per_period (default 40), the rolling plastic
  dissipation by (1 + 1 / rolling.n_steps)(1 + 0.2 h) — so Richardson over levels that double
  finds the exact value; manifest.json then has extra.n_dofs = 1000 / h (per case for impacts);
  CLEARJOINT_FAKE_SECONDS=<s> sleeps that long per case (a task's time for the test).
- study rolling: rolling.n_steps (default 8) must be >= 4, as fe_stage checks it; writes
  rolling_history.csv (fe_stage's columns, n_steps rows after t = 0: the journal spins up to
  near the rolling rate, a small plastic strain, a closed energy balance),
  rolling_strain_profile.csv and manifest.json with extra.rolling shaped as fe_stage writes it
  (fe_stage/rolling_output.cc). Scene key fake_rolling_fail: true writes half the steps, both
  CSVs and the manifest marked incomplete with a message, and exits 2, as fe_stage does when a
  time step fails.
- study misalignment: needs misalignment.theta_deg [deg] and loading.journal rigid (the
  default) or core, as fe_stage (end_faces and axis_line are input errors); rejects θ > θ_max
  (paper Eq. 3, the closed form of docs/geometry.md) with exit 1, as fe_stage does (only
  round-off, 1e-12 relative, is forgiven). K falls with θ; the core journal's K is 0.7 times the
  rigid one's (a made-up factor: another journal, another law).
- geometry.mesh: must be an absolute path of an existing .msh (run_pipeline meshes a .geo
  first); K is scaled by a factor from the mesh file's sha256, so another mesh gives another law.
- missing geometry keys take the FE defaults (R_B 10, t_B 4, L_B 20, c_r 0.5, c_a 1 mm).
- mesh.adaptive_cycles > 0 (radial): manifest.json's extra.adaptive as fe_stage writes it, one
  made-up mesh per cycle and the estimate of the error of F(delta_max) 0.02 / 2^cycles,
  extrapolated from 2 cycles on, else the change in the last cycle (not extrapolated).
- manifest.json carries extra.scene (the fit stage embeds it in the law file), with the
  geometry, loading.journal, contact.mu and material.yield_stress filled in as fe_stage does.
Environment: CLEARJOINT_FAKE_SLEEP=<s> sleeps before writing (to be interrupted);
CLEARJOINT_FAKE_TRACE=<file> appends "start|end <output folder name> <pid> <time>" lines (the
tests of tasks at once see which runs overlapped); CLEARJOINT_FAKE_CHILD=1 starts a child
(`sleep 600`, like fe_stage's plot.py) before sleeping and appends "child <name> <pid> <time>";
CLEARJOINT_FAKE_FAIL_MATCH=<text> fails (exit 2) when the output folder's path contains <text>.
Under mpirun (OMPI_COMM_WORLD_RANK set) every rank prints "fake fe_stage: rank r of n" (with
the Slurm job id and task count when in a job) and only rank 0 goes on;
scene key fail: true exits 2 with a message (a failing stage).
CLEARJOINT_FAKE_FIELDS=1 also writes fields/solution.pvd with one VTU (needs python3-vtk9), for
the report's tests: a quarter of the bearing ring (x >= 0, z >= 0: symmetry factor 4), von Mises
peaking at 600 MPa at the bottom of the bore (above the 168.2 MPa yield stress near the contact),
and contact fields in fe_stage's (Abaqus's) meaning — pressure, active, status 0 open / 1 slip /
2 stick, shear within Coulomb's cone (zero without friction), slip only where in contact, and
the 9-component `stress` (row by row, as fe_stage writes it): uniaxial along the point's radial
direction from the bore's axis, σ = −vm·n⊗n, so its von Mises stress is the von Mises field
and its radial normal stress −vm (compression). Scene
key fake_old_contact_fields: true writes them as fe_stage did before issue 15 (shear 1.96 x the
pressure and 'stick' in a frictionless run, slip off contact), which the report must flag."""
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
    journal = scene.get("loading", {}).get("journal", "rigid")
    if journal not in ("rigid", "core"):
        input_error("loading.journal", journal, "rigid|core (misalignment study)")
    if journal == "core":
        K *= 0.7
    theta = scene["misalignment"]["theta_deg"]
    R_J, L_J, c = g["R_B"] - g["c_r"], g["L_B"] - 2 * g["c_a"], g["c_r"]
    theta_max = math.degrees(2 * math.atan(2 * c / (L_J + math.sqrt(L_J ** 2 - 4 * c * (c + 2 * R_J)))))
    if not 0 <= theta <= theta_max * (1 + 1e-12):
        input_error("misalignment.theta_deg", theta, f"0 <= theta <= theta_max = {theta_max!r} deg")
    K *= 1.0 - 0.2 * theta / theta_max
elif study == "impact":
    steps = scene.get("impact", {}).get("steps_per_period", 40)
    if not (isinstance(steps, int) and 10 <= steps <= 100000):  # the real stage's range
        input_error("impact.steps_per_period", steps, "an integer in [10, 100000]")
    if check:  # only its scene is checked here (the impact tests run the real fe_stage)
        sys.exit(0)
    if not scene.get("fake_discretisation"):
        input_error("study", study, "radial|misalignment (the fake stage runs impacts only with "
                                    "fake_discretisation: true)")
elif study == "rolling":
    n_steps = scene.get("rolling", {}).get("n_steps", 8)
    if not (isinstance(n_steps, int) and n_steps >= 4):
        input_error("rolling.n_steps", n_steps, "an integer in [4, 1000000]")
    if check:
        sys.exit(0)
elif study != "radial":
    input_error("study", study, "radial|misalignment|impact|rolling")

mesh = scene.get("geometry", {}).get("mesh")
if mesh is not None:
    if not (mesh.startswith("/") and mesh.endswith(".msh") and os.path.isfile(mesh)):
        input_error("geometry.mesh", mesh, "an absolute path of an existing .msh file")
    with open(mesh, "rb") as f:
        K *= 1.0 + hashlib.sha256(f.read()).digest()[0] / 1000.0



def write_fields(out, g, mu, old):
    """A quarter ring of hexahedra with made-up fields (see the module's text)."""
    import numpy as np
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk
    n_phi, n_r, n_z = 12, 2, 4
    phis = np.linspace(0.0, math.pi, n_phi + 1)  # 0 at the bottom of the bore (0, -R_B)
    rs = np.linspace(g["R_B"], g["R_B"] + g["t_B"], n_r + 1)
    zs = np.linspace(0.0, g["L_B"] / 2, n_z + 1)
    pts, index = vtk.vtkPoints(), {}
    fields = {k: [] for k in ("von_mises_stress", "contact_pressure", "contact_active",
                              "contact_status", "contact_shear", "contact_slip")}
    for i, phi in enumerate(phis):
        for j, r in enumerate(rs):
            for k, z in enumerate(zs):
                index[i, j, k] = pts.InsertNextPoint(r * math.sin(phi), -r * math.cos(phi), z)
                dist = math.hypot(r * math.sin(phi), g["R_B"] - r * math.cos(phi))
                fields["von_mises_stress"].append(600e6 * math.exp(-(dist / 2e-3) ** 2))
                active = j == 0 and phi < math.radians(40)
                p = 300e6 * math.cos(phi * 90 / 40) if active else 0.0
                stick = active and phi < math.radians(10)
                if old:  # fe_stage before issue 15
                    status, shear, slip = 2.0 if active else 0.0, 1.96 * p, 1e-7 if j == 0 else 0.0
                elif not active:
                    status, shear, slip = 0.0, 0.0, 0.0
                elif mu == 0:
                    status, shear, slip = 1.0, 0.0, 1e-7
                else:
                    status = 2.0 if stick else 1.0
                    shear = mu * p * (0.5 if stick else 1.0)
                    slip = 0.0 if stick else 1e-7
                for name, v in (("contact_pressure", p), ("contact_active", float(active)),
                                ("contact_status", status), ("contact_shear", shear),
                                ("contact_slip", slip)):
                    fields[name].append(v)
    grid = vtk.vtkUnstructuredGrid()
    grid.SetPoints(pts)
    for i in range(n_phi):
        for j in range(n_r):
            for k in range(n_z):
                hexa = vtk.vtkHexahedron()
                corners = [(i, j, k), (i, j + 1, k), (i + 1, j + 1, k), (i + 1, j, k),
                           (i, j, k + 1), (i, j + 1, k + 1), (i + 1, j + 1, k + 1), (i + 1, j, k + 1)]
                for c, ijk in enumerate(corners):
                    hexa.GetPointIds().SetId(c, index[ijk])
                grid.InsertNextCell(hexa.GetCellType(), hexa.GetPointIds())
    for name, values in fields.items():
        a = numpy_to_vtk(np.array(values, dtype=np.float32), deep=True)
        a.SetName(name)
        grid.GetPointData().AddArray(a)
    xyz = np.array([pts.GetPoint(i) for i in range(pts.GetNumberOfPoints())])
    n = xyz[:, :2] / np.hypot(xyz[:, 0], xyz[:, 1])[:, None]
    sig = np.zeros((len(xyz), 3, 3))
    sig[:, :2, :2] = -np.array(fields["von_mises_stress"])[:, None, None] * n[:, :, None] * n[:, None, :]
    a = numpy_to_vtk(sig.reshape(-1, 9), deep=True)
    a.SetName("stress")
    grid.GetPointData().AddArray(a)
    os.makedirs(os.path.join(out, "fields"), exist_ok=True)
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(os.path.join(out, "fields", "solution_0001.vtu"))
    w.SetInputData(grid)
    if not w.Write():
        sys.exit(2)
    with open(os.path.join(out, "fields", "solution.pvd"), "w") as f:
        f.write('<?xml version="1.0"?><VTKFile type="Collection" version="0.1"><Collection>'
                '<DataSet timestep="5e-05" group="" part="0" file="solution_0001.vtu"/>'
                '</Collection></VTKFile>')




# fe_stage/rolling_output.cc: rolling_history_table(), strain_profile_table()
ROLLING_COLUMNS = [
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
PROFILE_COLUMNS = [("angle", "rad"), ("arc", "m"), ("strain_radial", "1"),
                   ("strain_tangential", "1"), ("strain_axial", "1"), ("plastic_strain", "1"),
                   ("von_mises", "Pa")]


def write_rolling(out, scene, g):
    """Made-up but self-consistent rolling outputs (see the module's text)."""
    r = scene.get("rolling", {})
    n_steps, omega_B, ramp = r.get("n_steps", 8), r.get("omega_B", 12.56), r.get("ramp_time", 0.25)
    delta_max = scene.get("loading", {}).get("delta_max", 1.0e-3)
    fail = scene.get("fake_rolling_fail", False)
    R_B, R_J = g["R_B"], g["R_B"] - g["c_r"]
    rows = [[0.0] * len(ROLLING_COLUMNS)]
    for k in range(1, (n_steps // 2 if fail else n_steps) + 1):
        t = ramp * k / n_steps
        d = delta_max * k / n_steps
        F = 4.0e4 * k / n_steps
        spin = omega_B * (R_B + d) / R_J * (1 - 0.5 ** k)
        slip = omega_B * (R_B + d) - spin * R_J
        w_push = 0.5 * F * d
        w_drive = 0.3 * F * 1e-4 * k
        kinetic = 0.5 * 1.8e-6 * spin ** 2
        plastic = 0.2 * w_push
        if scene.get("fake_discretisation"):
            m = scene.get("mesh", {})
            h = 2.0 ** -(m.get("global_refinements", 0) + m.get("contact_refinements", 1))
            plastic *= (1 + 1.0 / n_steps) * (1 + 0.2 * h)
        friction = w_drive - kinetic
        elastic = w_push - plastic
        eps_p = 0.01 * k / n_steps
        row = {"time": t, "delta": d, "force_normal": F, "force_tangential": 0.3 * F,
               "phi": omega_B * t, "gamma": spin * t, "phi_rate": omega_B, "gamma_rate": spin,
               "slip_speed": slip, "torque_drive": 0.3 * F * R_B, "torque_journal": 0.3 * F * R_J,
               "work_drive": w_drive, "work_push": w_push, "elastic_energy": elastic,
               "plastic_dissipation": plastic, "friction_dissipation": friction,
               "kinetic_energy": kinetic, "energy_balance_error": 0.0, "work_frame": w_push,
               "frame_balance_error": 0.0, "max_plastic_strain": eps_p,
               "max_strain": 2 * eps_p, "plastic_volume": 1e-9 * k, "active_contact_points": 6,
               "slipping_contact_points": 2, "spin_iterations": 3, "newton_iterations": 4, "line_search_steps": 1,
               "contact_iterations": 5, "linear_iterations": 50, "cuts": 0, "spin_coupled": 1,
               "phi_paper": 0.98 * omega_B * t, "gamma_paper": 0.97 * spin * t,
               "phi_rate_paper": 0.98 * omega_B, "gamma_rate_paper": 0.97 * spin,
               "wall_time": 0.01 * k}
        rows.append([row[c] for c, _ in ROLLING_COLUMNS])
    status = "incomplete" if fail else "complete"
    message = f"time step {len(rows)} (t = {ramp * len(rows) / n_steps!r} s) did not converge " \
              "after 10 cuts (requested by the test)" if fail else ""
    marker = f"# status: incomplete: {message}\n" if fail else "# status: complete\n"
    with open(os.path.join(out, "rolling_history.csv"), "w") as f:
        f.write("# fake fe_stage: rolling study\n# units: " + ",".join(u for _, u in ROLLING_COLUMNS) +
                "\n" + ",".join(c for c, _ in ROLLING_COLUMNS) + "\n")
        for row in rows:
            f.write(",".join(repr(float(v)) for v in row) + "\n")
        f.write(marker)
    with open(os.path.join(out, "rolling_strain_profile.csv"), "w") as f:
        f.write("# units: " + ",".join(u for _, u in PROFILE_COLUMNS) + "\n" +
                ",".join(c for c, _ in PROFILE_COLUMNS) + "\n")
        for i in range(-6, 7):
            a = math.radians(5 * i)
            bump = math.exp(-(i / 2.5) ** 2)
            f.write(",".join(repr(v) for v in (a, a * R_B, -0.004 * bump, 0.002 * bump, 0.0005 * bump,
                                               0.01 * bump, 3.0e8 * bump)) + "\n")
        f.write(marker)
    last = dict(zip((c for c, _ in ROLLING_COLUMNS), rows[-1]))
    rolling = {
        "journal_inertia": {"value": 1.8e-6, "unit": "kg m^2"},
        "rolling_rate": {"value": omega_B * (R_B + delta_max) / R_J, "unit": "rad/s"},
        "time_step": {"value": ramp / n_steps, "unit": "s"},
        "slip_stages": {"found": not fail,
                        "slip_speed_max": {"value": max(r[8] for r in rows), "unit": "m/s"},
                        "end_of_slip": {"value": 2 * ramp / n_steps, "unit": "s"},
                        "settled": {"value": 4 * ramp / n_steps, "unit": "s"},
                        "slip_speed_final": {"value": last["slip_speed"], "unit": "m/s"}},
        "max_plastic_strain": last["max_plastic_strain"],
        "max_strain": {"value": last["max_strain"]},
        "energy_balance_error": {"value": 0.0},
        "final": {k: last[k] for k in ("time", "force_normal", "gamma_rate", "phi_rate_paper",
                                        "gamma_rate_paper", "work_drive", "work_push",
                                        "elastic_energy", "plastic_dissipation",
                                        "friction_dissipation")}}
    used = json.loads(json.dumps(scene))
    used["geometry"] = {**used.get("geometry", {}), **g}
    used.setdefault("contact", {}).setdefault("mu", 0.3)
    used.setdefault("loading", {}).setdefault("delta_max", delta_max)
    used["rolling"] = {"omega_B": omega_B, "ramp_time": ramp, "end_time": ramp, "n_steps": n_steps}
    with open(os.path.join(out, "manifest.json"), "w") as f:
        json.dump({"status": status, "message": message,
                   "outputs": [os.path.join(out, n) for n in ("rolling_history.csv",
                                                              "rolling_strain_profile.csv")],
                   "extra": {"scene": used, "rolling": rolling,
                             **({"n_dofs": int(1000 / fake_h)} if fake_h else {})}}, f)
    if fail:
        print(f"fe_stage: {message}", file=sys.stderr)
        sys.exit(2)


if check:
    sys.exit(0)
if "OMPI_COMM_WORLD_RANK" in os.environ:
    rank, size = os.environ["OMPI_COMM_WORLD_RANK"], os.environ.get("OMPI_COMM_WORLD_SIZE")
    print(f"fake fe_stage: rank {rank} of {size} (Slurm job {os.environ.get('SLURM_JOB_ID')}, "
          f"{os.environ.get('SLURM_NTASKS')} tasks)", flush=True)
    if rank != "0":
        sys.exit(0)


def trace(event, pid=None):
    path = os.environ.get("CLEARJOINT_FAKE_TRACE")
    if path:
        with open(path, "a") as f:
            f.write(f"{event} {os.path.basename(out)} {pid or os.getpid()} {time.time()!r}\n")


trace("start")
if os.environ.get("CLEARJOINT_FAKE_CHILD") == "1":
    import subprocess
    trace("child", subprocess.Popen(["sleep", "600"]).pid)
time.sleep(float(os.environ.get("CLEARJOINT_FAKE_SLEEP", "0")))
if os.environ.get("CLEARJOINT_FAKE_FAIL_MATCH", "\0") in out:
    print("fake fe_stage: failing as asked (CLEARJOINT_FAKE_FAIL_MATCH)", file=sys.stderr)
    sys.exit(2)
os.makedirs(out, exist_ok=True)
fake_h = None
if scene.get("fake_discretisation"):
    m = scene.get("mesh", {})
    fake_h = 2.0 ** -(m.get("global_refinements", 0) + m.get("contact_refinements", 1))
    K *= 1 + 0.1 * fake_h
    time.sleep(float(os.environ.get("CLEARJOINT_FAKE_SECONDS", "0")))
if study == "rolling":
    write_rolling(out, scene, g)
    sys.exit(0)
if study == "impact":  # `steps`: impact.steps_per_period, read and checked above
    velocities = scene.get("sweep", {}).get("velocity") or [scene.get("impact", {}).get("velocity", 0.1)]
    cases = []
    with open(os.path.join(out, "impact_sweep.csv"), "w") as f:
        f.write("# fake fe_stage: impact sweep\n# units: m/s,N,m\nv_in_m_per_s,peak_force_N,delta_max_m\n")
        for i, v in enumerate(velocities):
            peak = 5.0e3 * v * (1 + 0.1 * fake_h) * (1 - 4.0 / steps)
            f.write(f"{v!r},{peak!r},{1e-5 * v!r}\n")
            case = os.path.join(out, f"v{i}")
            os.makedirs(case, exist_ok=True)
            with open(os.path.join(case, "manifest.json"), "w") as c:
                json.dump({"status": "complete", "outputs": [], "extra": {"n_dofs": int(1000 / fake_h)}}, c)
            cases.append(os.path.join(case, "manifest.json"))
        f.write("# status: complete\n")
    with open(os.path.join(out, "manifest.json"), "w") as f:
        json.dump({"status": "complete", "outputs": cases + [os.path.join(out, "impact_sweep.csv")],
                   "extra": {"scene": scene}}, f)
    sys.exit(0)
with open(os.path.join(out, "force_penetration.csv"), "w") as f:
    f.write("# units: m,N\ndelta,force\n0,0\n")
    for i in range(1, 11):
        d = 5e-6 * i
        f.write(f"{d!r},{K * d ** n!r}\n")
# like fe_stage, the manifest holds the scene as used: geometry and the keys the report reads
# with their defaults filled in
used = json.loads(json.dumps(scene))
used["geometry"] = {**used.get("geometry", {}), **g}
used.setdefault("loading", {}).setdefault("journal", "rigid" if study == "misalignment" else "end_faces")
used.setdefault("contact", {}).setdefault("mu", 0.0)
used.setdefault("material", {}).setdefault("yield_stress", 168.2e6)
extra = {"scene": used}
if fake_h:
    extra["n_dofs"] = int(1000 / fake_h)
cycles = scene.get("mesh", {}).get("adaptive_cycles", 0)
if cycles > 0:
    # as fe_stage/results/case_output.cc writes an adaptive case: its meshes and its own
    # estimate of the error of F(delta_max), extrapolated from three meshes on (made-up numbers)
    F_max = K * 5e-5 ** n
    extra["adaptive"] = {
        "cycles": [{"n_cells": 100 * 2 ** k, "n_dofs": 1000 * 2 ** k,
                    "force_at_delta_max": {"value": F_max * (1 + 0.02 / 2 ** k), "unit": "N"}}
                   for k in range(cycles + 1)],
        "fraction": 0.2, "marking_increments": 2,
        "estimated_error_F_max": {
            "value": 0.02 / 2 ** cycles, "unit": "1",
            "method": "change in the last cycle (not extrapolated; not a bound)" if cycles < 2 else
                      "last two cycles extrapolated with F = F_inf + C N^-q, q = 1"}}
if os.environ.get("CLEARJOINT_FAKE_FIELDS") == "1":
    write_fields(out, g, scene.get("contact", {}).get("mu", 0.0), scene.get("fake_old_contact_fields", False))
    extra["symmetry_factor"] = 4
with open(os.path.join(out, "manifest.json"), "w") as f:
    json.dump({"status": "complete", "outputs": [os.path.join(out, "force_penetration.csv")],
               "extra": extra}, f)
trace("end")
