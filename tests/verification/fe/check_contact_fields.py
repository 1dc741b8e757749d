#!/usr/bin/env python3
"""The VTU contact fields mean what an Abaqus user reads into CPRESS/CSTATUS/CSHEAR/CSLIP
(issue 15): runs fe_stage on a small radial case without and with friction, reads the last
increment's fields back with VTK and checks them node by node.

usage: check_contact_fields.py FE_STAGE WORKDIR
"""
import json
import os
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from vtu_readback import arrays, check, finish, last_grid

MU = 0.1
SCENE = """schema: clearjoint.fe/1
study: radial
geometry: {{t_B: 0.004}}
contact: {{mu: {mu}}}
loading: {{delta_max: 5.0e-5, n_increments: 2}}
mesh: {{n_circumferential: 8, n_axial: 2, n_radial: 1, contact_refinements: 1, global_refinements: 0}}
"""

def last_fields(out):
    grid = last_grid(out)
    point, cell = arrays(grid.GetPointData()), arrays(grid.GetCellData())
    point["xyz"] = vtk_to_numpy(grid.GetPoints().GetData())
    return point, cell


def run(fe_stage, work, mu):
    name = "frictionless" if mu == 0 else "mu_%g" % mu
    scene = os.path.join(work, name + ".yaml")
    with open(scene, "w") as f:
        f.write(SCENE.format(mu=mu))
    out = os.path.join(work, name)
    subprocess.run([fe_stage, scene, "--output", out, "--no-plots", "-q"], check=True)
    with open(os.path.join(out, "manifest.json")) as f:
        manifest = json.load(f)
    return last_fields(out), manifest


def main():
    fe_stage, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    for mu in (0.0, MU):
        (p, c), manifest = run(fe_stage, work, mu)
        tag = "mu = %g: " % mu
        active = p["contact_active"] > 0.5
        status, shear, slip, pressure = (p["contact_status"], p["contact_shear"],
                                          p["contact_slip"], p["contact_pressure"])
        check(active.sum() > 0, tag + "some nodes are in contact (%d points)" % active.sum())
        check(set(np.unique(status)) <= {0.0, 1.0, 2.0}, tag + "status takes 0, 1, 2 only")
        check(np.array_equal(status > 0, active), tag + "status > 0 exactly where in contact")
        check(np.all(shear[~active] == 0) and np.all(slip[~active] == 0),
              tag + "no shear and no slip off contact")
        if mu == 0:
            check(np.all(shear == 0), tag + "frictionless: zero shear everywhere")
            check(np.all(status[active] == 1), tag + "frictionless: every contact point slips (1)")
        else:
            # Coulomb's cone |t_T| <= mu*p at every contact point, equality where slipping,
            # on the symmetry planes too (there the plane's reaction is not friction and is
            # left out). 1e-4 relative: the semi-smooth Newton loop ends when the slip law
            # holds to 1e-6 of the largest nodal force (1e-5 of mu*lambda_max, more at the
            # small forces of the zone's edge; measured ~1e-7), the linear solves to 1e-10;
            # the nodal values are exact at the VTU points (Q2 patches subdivided twice = the
            # support points).
            ratio = shear[active] / (MU * pressure[active])
            check(np.all(ratio <= 1 + 1e-4), tag + "|t_T| <= mu p at every contact point "
                  "(max ratio %.8f)" % ratio.max())
            slipping = status[active] == 1
            xyz = p["xyz"][active]
            on_planes = (np.abs(xyz[:, 0]) < 1e-9) | (np.abs(xyz[:, 2]) < 1e-9)
            check(slipping.any(), tag + "some contact points slip")
            if slipping.any():
                check(np.all(np.abs(ratio[slipping] - 1) <= 1e-4),
                      tag + "|t_T| = mu p where slipping (%d points, %d on symmetry planes, "
                      "ratio %.8f..%.8f)" % (slipping.sum(), (slipping & on_planes).sum(),
                                             ratio[slipping].min(), ratio[slipping].max()))
        # deal.II 9.4 writes cell data as point data (constant over each cell's patch)
        zone = p["plastic_zone"] if "plastic_zone" in p else c["plastic_zone"]
        check(np.all((zone >= 0) & (zone <= 1)), tag + "plastic_zone is a volume fraction")
        y = manifest["extra"].get("yield_check")
        check(y is not None and y["yield_stress"]["unit"] == "Pa"
              and y["exceeded"] == bool((zone > 0).any()),
              tag + "manifest yield_check agrees with the plastic_zone field")
    sys.exit(finish())


if __name__ == "__main__":
    main()
