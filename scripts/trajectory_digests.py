#!/usr/bin/python3
"""Bit-identity of a refactoring: runs 20 short scene variants (both jets, plate, fixed and
tethered targets, both integrators, friction on and off, mono- and bidisperse, periodic gases
and cooling, binary collisions, 1 and 2 threads, both backends) with one granjet binary and
prints one SHA-256 per variant over everything the run computed: every dataset of /particles,
/observables, /connectivity, /contacts, /fields and /analysis, and the summary minus timings.

    /usr/bin/python3 scripts/trajectory_digests.py build/app/granjet > before.txt
    ... change the code, rebuild ...
    /usr/bin/python3 scripts/trajectory_digests.py build/app/granjet > after.txt
    diff before.txt after.txt    # no output: every trajectory is bit-identical

Digests are of one machine and compiler: compare runs made on the same one."""
import hashlib
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
JET3D = ["--set", "jet.grains=3000", "--set", "run.t_end=12", "--set", "output.interval=2",
         "--set", "analysis.window_start=6", "--set", "analysis.window_end=12"]
JET2D = ["--set", "jet.grains=1500", "--set", "run.t_end=12", "--set", "output.interval=2",
         "--set", "analysis.window_start=6", "--set", "analysis.window_end=12"]
GAS = ["--set", "gas.grains=1000", "--set", "run.t_end=4", "--set", "gas.equilibration=1",
       "--set", "output.interval=1"]
CHAINS = ["--set", "output.fields=position,velocity,radius,id,omega,force,contacts"]

# name: (scene, backend, extra arguments)
VARIANTS = {
    "jet3d": ("jet3d.ini", "soft_dem", JET3D + CHAINS),
    "jet3d_frictionless": ("jet3d.ini", "soft_dem", JET3D + ["--set", "contact.friction=0"]),
    "jet3d_verlet": ("jet3d.ini", "soft_dem", JET3D + ["--set", "run.integrator=verlet"]),
    "jet3d_plate": ("jet3d.ini", "soft_dem", JET3D + ["--set", "wall.kind=plate"]),
    "jet3d_fixed": ("jet3d.ini", "soft_dem", JET3D + ["--set", "wall.kind=fixed"]),
    "jet3d_bidisperse": ("jet3d.ini", "soft_dem", JET3D + ["--set", "jet.dispersity=bi"]),
    "jet3d_threads2": ("jet3d.ini", "soft_dem", JET3D + ["--set", "run.threads=2"]),
    "jet2d": ("jet2d.ini", "soft_dem", JET2D),
    "jet2d_friction": ("jet2d.ini", "soft_dem", JET2D + ["--set", "contact.friction=0.4",
                                                         "--set", "contact.contact_time=0.05"]),
    "jet2d_verlet": ("jet2d.ini", "soft_dem", JET2D + ["--set", "run.integrator=verlet"]),
    "jet2d_plate": ("jet2d.ini", "soft_dem", JET2D + ["--set", "wall.kind=plate"]),
    "jet2d_threads2": ("jet2d.ini", "soft_dem", JET2D + ["--set", "run.threads=2"]),
    "gas3d": ("gas3d.ini", "soft_dem", GAS),
    "hcs2d": ("hcs2d.ini", "soft_dem", GAS),
    "binary3d": ("binary.ini", "soft_dem", []),
    "binary2d_verlet": ("binary.ini", "soft_dem", ["--set", "scene.dimension=2",
                                                   "--set", "run.integrator=verlet"]),
    "ed_jet3d": ("jet3d.ini", "event_driven", JET3D),
    "ed_jet2d": ("jet2d.ini", "event_driven", JET2D),
    "ed_gas3d": ("gas3d.ini", "event_driven", GAS),
    "ed_hcs2d": ("hcs2d.ini", "event_driven", GAS),
}
GROUPS = ("particles", "observables", "connectivity", "contacts", "fields", "analysis")
# Left out of the summary's digest: timings and paths, and the record of what the backend
# adapted in the scene (a description of the run, not a result of it).
TIMINGS = ("wall_seconds", "cpu_seconds", "particle_steps_per_second", "collisions_per_second",
           "output", "seconds", "adaptations")


def digest_of(h5, summary):
    sha = hashlib.sha256()
    with h5py.File(h5, "r") as f:
        def add(name, item):
            if isinstance(item, h5py.Dataset):
                sha.update(name.encode())
                sha.update(np.ascontiguousarray(item[()]).tobytes())
        for group in GROUPS:
            if group in f:
                f[group].visititems(lambda name, item, g=group: add(f"{g}/{name}", item))

    def strip(node):
        if isinstance(node, dict):
            return {k: strip(v) for k, v in node.items() if k not in TIMINGS}
        return node
    with open(summary) as s:
        sha.update(json.dumps(strip(json.load(s)), sort_keys=True).encode())
    return sha.hexdigest()


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    granjet = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        for name, (scene, backend, extra) in VARIANTS.items():
            h5, summary = os.path.join(tmp, name + ".h5"), os.path.join(tmp, name + ".json")
            command = [granjet, "run", os.path.join(ROOT, "scenes", scene), "--quiet", "--no-log",
                       "--backend", backend, "--out", h5, "--summary", summary] + extra
            done = subprocess.run(command, capture_output=True, text=True)
            if done.returncode != 0:
                sys.exit(f"{name}: exit {done.returncode}\n{done.stderr}")
            print(name, digest_of(h5, summary), flush=True)


if __name__ == "__main__":
    main()
