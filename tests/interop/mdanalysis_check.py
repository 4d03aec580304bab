#!/usr/bin/python3
"""MDAnalysis reads a granjet run as its users would, without flags:

    /usr/bin/python3 tests/interop/mdanalysis_check.py RUN.h5 [--periodic] [--removed]

Universe.empty(N, trajectory=True).load_new(RUN.h5, format="H5MD") must load; at every frame
each atom's position and velocity equal h5py's for the grain of that id (atom k is grain k;
a removed grain's row is NaN with id -1), the frame times and dt are granjet's (no unit
conversion), and a periodic run has its box. Exits 1 naming the first mismatch."""
import argparse
import sys
import warnings

import h5py
import numpy as np

warnings.filterwarnings("ignore")  # MDAnalysis's deprecation chatter
import MDAnalysis as mda  # noqa: E402


def fail(message):
    print(f"mdanalysis_check: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("run")
    parser.add_argument("--periodic", action="store_true", help="the run has a periodic box")
    parser.add_argument("--removed", action="store_true",
                        help="grains were removed during the run (their rows must stay theirs)")
    args = parser.parse_args()
    with h5py.File(args.run, "r") as f:
        grains = f["particles/all"]
        rows = grains["position/value"].shape[1]
        ids = grains["id/value"][()]
        x = grains["position/value"][()]
        v = grains["velocity/value"][()]
        times = grains["position/time"][()]
        dt = f["observables/dt/value"][0]
        edges = grains["box/edges/value"][()] if "edges" in grains["box"] else None
    u = mda.Universe.empty(rows, trajectory=True).load_new(args.run, format="H5MD")
    trajectory = u.trajectory
    if trajectory.n_frames != len(times):
        fail(f"{trajectory.n_frames} frames, h5py has {len(times)}")
    if trajectory.dt != dt:
        fail(f"dt {trajectory.dt}, the file's frame interval is {dt}")
    removed = 0
    for ts in trajectory:
        k = ts.frame
        if ts.time != np.float32(times[k]) and ts.time != times[k]:
            fail(f"frame {k}: time {ts.time}, h5py {times[k]}")
        present = ids[k] >= 0
        if not np.array_equal(np.nonzero(present)[0], ids[k][present]):
            fail(f"frame {k}: a row does not hold the grain of its index")
        removed = max(removed, int((~present).sum()))
        for name, mine, theirs in (("position", ts.positions, x[k]), ("velocity", ts.velocities, v[k])):
            if not np.array_equal(mine[present], theirs[present].astype(np.float32)):
                fail(f"frame {k}: {name}s differ from h5py's for the same grain ids")
            if not np.isnan(mine[~present]).all():
                fail(f"frame {k}: a removed grain's {name} is not the fill value NaN")
        if args.periodic:
            if ts.dimensions is None or not np.allclose(ts.dimensions[:3], np.diag(edges[k])):
                fail(f"frame {k}: box {ts.dimensions}, the file's edges {np.diag(edges[k])}")
        elif ts.dimensions is not None:
            fail(f"frame {k}: a box {ts.dimensions} for a run without one")
    if args.removed and removed == 0:
        fail("no grain was removed: the run does not test the rows of removed grains")
    print(f"mdanalysis_check: {args.run}: {trajectory.n_frames} frames of {rows} grains "
          f"(up to {removed} removed) match h5py; dt {trajectory.dt}; units {trajectory.units}")


if __name__ == "__main__":
    main()
