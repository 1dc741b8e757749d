"""What the VTU read-back checks share (check_contact_fields.py, check_plastic_fields.py): a
named check that prints ok/FAIL and remembers the failures, and the last written state of a
run's fields/solution.pvd read with VTK (Debian's python3-vtk9)."""
import os
import xml.etree.ElementTree as ET

import numpy as np
from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def finish():
    """The script's exit code: 1 and the count when a check failed."""
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("all checks passed")
    return 0


def last_grid(out):
    """The unstructured grid of the last state listed in <out>/fields/solution.pvd."""
    pvd = ET.parse(os.path.join(out, "fields", "solution.pvd")).getroot()
    files = [d.get("file") for d in pvd.iter("DataSet")]
    reader = vtkXMLPUnstructuredGridReader()
    reader.SetFileName(os.path.join(out, "fields", files[-1]))
    reader.Update()
    return reader.GetOutput()


def arrays(data):
    """{name: numpy array} of a vtkPointData / vtkCellData."""
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}
