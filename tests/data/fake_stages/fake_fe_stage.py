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
- manifest.json carries extra.scene (the fit stage embeds it in the law file), with the
  geometry, loading.journal, contact.mu and material.yield_stress filled in as fe_stage does.
Environment: CLEARJOINT_FAKE_SLEEP=<s> sleeps before writing (to be interrupted);
scene key fail: true exits 2 with a message (a failing stage).
CLEARJOINT_FAKE_FIELDS=1 also writes fields/solution.pvd with one VTU (needs python3-vtk9), for
the report's tests: a quarter of the bearing ring (x >= 0, z >= 0: symmetry factor 4), von Mises
peaking at 600 MPa at the bottom of the bore (above the 168.2 MPa yield stress near the contact),
and contact fields in fe_stage's (Abaqus's) meaning — pressure, active, status 0 open / 1 slip /
2 stick, shear within Coulomb's cone (zero without friction), slip only where in contact. Scene
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


if check:
    sys.exit(0)
time.sleep(float(os.environ.get("CLEARJOINT_FAKE_SLEEP", "0")))
os.makedirs(out, exist_ok=True)
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
if os.environ.get("CLEARJOINT_FAKE_FIELDS") == "1":
    write_fields(out, g, scene.get("contact", {}).get("mu", 0.0), scene.get("fake_old_contact_fields", False))
    extra["symmetry_factor"] = 4
with open(os.path.join(out, "manifest.json"), "w") as f:
    json.dump({"status": "complete", "outputs": [os.path.join(out, "force_penetration.csv")],
               "extra": extra}, f)
