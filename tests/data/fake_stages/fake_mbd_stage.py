#!/usr/bin/python3
"""A stand-in for mbd_stage in the pipeline's own tests: copies the scene it was given to
DIR/scene_used.json so the test can see which law it got. Not a physics model."""
import json, os, sys

if "--check" in sys.argv:  # the real stage validates the scene; the stand-in accepts it
    sys.exit(0)
scene_path, out = sys.argv[1], sys.argv[3]
with open(scene_path) as f:
    text = "".join(l for l in f if not l.lstrip().startswith("#"))
os.makedirs(out, exist_ok=True)
with open(os.path.join(out, "scene_used.json"), "w") as f:
    f.write(text)
