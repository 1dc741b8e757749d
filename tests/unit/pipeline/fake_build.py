"""A build directory of stand-in stages for the tests of bench/measure_presets.py: fe_stage and
mbd_stage are tests/data/fake_stages' scripts, fit_stage and msh_check the real ones (their
paths passed to the test), impact_compare does nothing."""
import json
import os

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))


def make_fake_build(d, fit_stage, msh_check):
    """The build directory under `d`, its executables linked; returns its path."""
    build = os.path.join(d, "build")
    fakes = os.path.join(ROOT, "tests", "data", "fake_stages")
    for link, target in [("fe_stage/fe_stage", os.path.join(fakes, "fake_fe_stage.py")),
                         ("mbd_stage/mbd_stage", os.path.join(fakes, "fake_mbd_stage.py")),
                         ("mbd_stage/impact_compare", "/bin/true"),
                         ("fit_stage/fit_stage", fit_stage),
                         ("geometry/msh_check", msh_check)]:
        os.makedirs(os.path.dirname(os.path.join(build, link)), exist_ok=True)
        os.symlink(target, os.path.join(build, link))
    return build


def write_scenes(d, scenes):
    """Each scene (name -> dict) written as JSON into `d`."""
    for name, scene in scenes.items():
        with open(os.path.join(d, name), "w") as f:
            json.dump(scene, f)
