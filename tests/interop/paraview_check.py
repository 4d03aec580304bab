#!/usr/bin/env python3
"""Checks that ParaView's three XDMF readers show a granjet run as its .h5 holds it.

    python3 tests/interop/paraview_check.py RUN.h5 [--png-dir DIR] [--picture FILE]

RUN.xmf (the frames) and RUN.fields.xmf (the analysed fields) must lie beside RUN.h5; a sidecar
that is missing is skipped with a note. For each of XDMFReader (Xdmf2), Xdmf3ReaderS and
Xdmf3ReaderT, at the last stored frame:

  frames  the time steps are the frames' times; the grains are one vertex per present grain, at
          the .h5 positions (so no removed grain shows, at NaN or elsewhere) with the .h5
          velocities, and the data bounds are finite and within a grain radius of the grains'
          extent; with contacts, one line per contact between the right grains, with the .h5
          normal forces.
  fields  one cell per sector of every bin, with the bin's corners at its edges (lateral r or y;
          height above the origin, at z in 3D and x in 2D) and every field's ensemble mean.

and each renders to a non-blank 800x600 image: the grains (Point Gaussian, coloured by speed),
the contacts (lines, coloured by |normal_force|) and the fields (coloured by phi). --png-dir
keeps those images; --picture draws the last frame's grains and force chains into FILE.

What to expect is read with h5py and numpy; the checks then run under pvpython (which needs
only numpy), started by this script, on a private Xvfb server when there is no display. Exits 1
with a line per failed check, naming the reader and the sidecar.
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")
VTK_POLY_VERTEX, VTK_POLY_LINE, VTK_HEXAHEDRON = 2, 4, 12
IMAGE_SIZE = (800, 600)
# Fractions of an image that must differ from the background: the grains and the fields fill a
# good part of it, a sparse set of force chains much less.
MIN_COVER = {"grains": 0.01, "contacts": 0.001, "fields": 0.01}


# ---------------------------------------------------------------------------------------------
# What the .h5 holds (h5py)


def expectations(h5_path, npz_path):
    """Writes what the readers must show to npz_path; returns the sidecars to check."""
    import h5py

    with h5py.File(h5_path, "r") as f:
        out = {}
        sidecars = []
        base = os.path.splitext(h5_path)[0]
        if "particles/all/present/value" in f and os.path.exists(base + ".xmf"):
            sidecars.append("frames")
            present = f["particles/all/present/value"]
            counts = (present[()] >= 0).sum(axis=1)
            times = f["particles/all/position/time"][()]
            shown = np.flatnonzero(counts > 0)
            k = shown[-1]
            rows = present[k, : counts[k]]
            out["times"] = times[shown]
            out["dimension"] = np.array(f["particles/all/position/value"].shape[2])
            out["rows"] = rows
            out["position"] = f["particles/all/position/value"][k][rows]
            out["velocity"] = f["particles/all/velocity/value"][k][rows]
            out["radius"] = f["particles/all/radius/value"][k][rows]
            if "connectivity/contacts/value" in f:
                pairs = f["connectivity/contacts/value"][k]
                valid = pairs[:, 0] >= 0
                out["pairs"] = pairs[valid]
                out["normal_force"] = f["contacts/normal_force/value"][k][valid]
        if "fields/mesh/points" in f and os.path.exists(base + ".fields.xmf"):
            sidecars.append("fields")
            g = f["fields"]
            out["dimension"] = np.array(int(g.attrs["dimension"]))
            out["height_origin"] = np.array(float(g.attrs.get("height_origin", 0.0)))
            out["lateral"] = g["mesh/lateral"][()]
            out["height"] = g["mesh/height"][()]
            out["sectors"] = np.array(g["mesh/points"].shape[0] - 1)
            names = []
            g.visit(lambda p: names.append(p[: -len("/mean")]) if p.endswith("/mean") else None)
            for path in names:
                out["mean:" + path.replace("/", ".")] = g[path + "/mean"][()]
    np.savez(npz_path, **out)
    return sidecars


# ---------------------------------------------------------------------------------------------
# What ParaView shows (pvpython)


class Checks:
    def __init__(self):
        self.failures = []

    def expect(self, ok, where, what):
        if not ok:
            self.failures.append(f"{where}: {what}")
        return ok


def leaves(data):
    """The datasets of a reader's output, multiblock or not."""
    if not data.IsA("vtkCompositeDataSet"):
        return [data]
    found = []
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        found.append(it.GetCurrentDataObject())
        it.GoToNextItem()
    return found


def cell_types(data):
    return {data.GetCellType(c) for c in range(data.GetNumberOfCells())}


def cell_points(data):
    """Point ids of every cell, [cells][points per cell] (all cells have as many)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkIdList

    if data.IsA("vtkUnstructuredGrid"):
        ids = vtk_to_numpy(data.GetCells().GetConnectivityArray())
        return ids.reshape(data.GetNumberOfCells(), -1).astype(np.int64)
    ids = vtkIdList()
    out = []
    for c in range(data.GetNumberOfCells()):
        data.GetCellPoints(c, ids)
        out.append([ids.GetId(i) for i in range(ids.GetNumberOfIds())])
    return np.array(out, dtype=np.int64)


def array(data, name, cells):
    from vtkmodules.util.numpy_support import vtk_to_numpy

    found = (data.GetCellData() if cells else data.GetPointData()).GetArray(name)
    return None if found is None else vtk_to_numpy(found)


def points(data):
    from vtkmodules.util.numpy_support import vtk_to_numpy

    return vtk_to_numpy(data.GetPoints().GetData())


def padded(values, width):
    """2D vectors as ParaView may hold them, with a zero third component."""
    values = np.asarray(values, dtype=float)
    if values.ndim == 1 or values.shape[1] >= width:
        return values
    return np.hstack([values, np.zeros((values.shape[0], width - values.shape[1]))])


def open_reader(name, path):
    from paraview import simple

    if name == "XDMFReader":
        return simple.XDMFReader(FileNames=[path])
    return getattr(simple, name)(FileName=[path])


def check_frames(checks, where, reader, exp):
    from paraview import servermanager

    times = list(reader.TimestepValues or [])
    want = [float(t) for t in exp["times"]]
    checks.expect(times == want, where, f"time steps {times[:3]}... (of {len(times)}), "
                  f"the frames' {want[:3]}... (of {len(want)})")
    reader.UpdatePipeline(want[-1])
    data = servermanager.Fetch(reader)
    blocks = [b for b in leaves(data) if b is not None and b.GetNumberOfCells() > 0]
    grains = [b for b in blocks if cell_types(b) == {VTK_POLY_VERTEX}]
    lines = [b for b in blocks if cell_types(b) == {VTK_POLY_LINE}]
    if not checks.expect(len(grains) == 1, where, f"{len(grains)} grids of vertices, not 1"):
        return
    g = grains[0]
    n = len(exp["rows"])
    if not checks.expect(g.GetNumberOfCells() == n, where,
                         f"{g.GetNumberOfCells()} grain vertices, {n} present grains in the .h5"):
        return
    vertex = cell_points(g)
    checks.expect(vertex.shape[1] == 1, where, "a grain cell with more than one point")
    ids = vertex[:, 0]
    if not checks.expect(np.array_equal(np.sort(ids), np.sort(exp["rows"])), where,
                         "the vertices are not the present grains' rows"):
        return
    if not checks.expect(g.GetNumberOfPoints() > ids.max(), where,
                         f"{g.GetNumberOfPoints()} points, the rows go up to {ids.max()}"):
        return
    xyz = points(g)[ids]
    checks.expect(np.isfinite(xyz).all(), where, "a present grain at a non-finite position")
    order = np.argsort(exp["rows"])
    by_row = np.argsort(ids)
    want_xyz = padded(exp["position"], 3)[order]
    checks.expect(np.allclose(xyz[by_row], want_xyz, rtol=0, atol=1e-9), where,
                  "grain positions differ from the .h5")
    velocity = array(g, "velocity", cells=False)
    if checks.expect(velocity is not None, where, "no point array velocity"):
        got = padded(velocity[ids], 3)[by_row]
        checks.expect(np.allclose(got, padded(exp["velocity"], 3)[order], rtol=0, atol=1e-9),
                      where, "grain velocities differ from the .h5")
    bounds = np.array(g.GetBounds())
    lo, hi = want_xyz.min(axis=0), want_xyz.max(axis=0)
    slack = float(np.nanmax(exp["radius"])) + 1e-9
    checks.expect(np.isfinite(bounds).all(), where, f"non-finite bounds {bounds}")
    near = np.all(np.abs(bounds[0::2] - lo) <= slack) and np.all(np.abs(bounds[1::2] - hi) <= slack)
    checks.expect(near, where, f"bounds {bounds.round(3)}, the grains' extent {lo.round(3)} to "
                  f"{hi.round(3)}")

    pairs = exp["pairs"] if "pairs" in exp else np.zeros((0, 2), dtype=np.int64)
    if len(pairs) == 0:
        checks.expect(not lines, where, "contact lines in a frame without contacts")
        return
    if not checks.expect(len(lines) == 1, where, f"{len(lines)} grids of lines, not 1"):
        return
    c = lines[0]
    if not checks.expect(c.GetNumberOfCells() == len(pairs), where,
                         f"{c.GetNumberOfCells()} contact lines, {len(pairs)} contacts in the .h5"):
        return
    if not checks.expect(np.array_equal(cell_points(c), pairs), where,
                         "the contact lines join other grains than the .h5 pairs"):
        return
    ends = points(c)[np.unique(pairs)]
    checks.expect(np.isfinite(ends).all(), where, "a contact ends at a non-finite position")
    force = array(c, "normal_force", cells=True)
    if checks.expect(force is not None, where, "no cell array normal_force"):
        checks.expect(np.allclose(padded(force, 3), padded(exp["normal_force"], 3), rtol=0,
                                  atol=1e-9), where, "normal forces differ from the .h5")


def check_fields(checks, where, reader, exp):
    from paraview import servermanager

    reader.UpdatePipeline()
    blocks = [b for b in leaves(servermanager.Fetch(reader)) if b is not None]
    if not checks.expect(len(blocks) == 1 and blocks[0].IsA("vtkStructuredGrid"), where,
                         "not one structured grid"):
        return
    g = blocks[0]
    dim = int(exp["dimension"])
    lateral, height = exp["lateral"], exp["height"] + float(exp["height_origin"])
    sectors, layers, bins = int(exp["sectors"]), len(height) - 1, len(lateral) - 1
    cells = sectors * layers * bins
    if not checks.expect(g.GetNumberOfCells() == cells and cell_types(g) == {VTK_HEXAHEDRON},
                         where, f"{g.GetNumberOfCells()} cells, want {cells} hexahedra"):
        return
    xyz = points(g)
    checks.expect(np.isfinite(xyz).all(), where, "a non-finite mesh point")
    # Where a point lies in the bins' coordinates: (lateral, height, azimuth or z).
    if dim == 3:
        across, up = np.hypot(xyz[:, 0], xyz[:, 1]), xyz[:, 2]
        around = np.round(np.degrees(np.arctan2(xyz[:, 1], xyz[:, 0])), 6) % 360
        extent = [-lateral[-1], lateral[-1], -lateral[-1], lateral[-1], height[0], height[-1]]
    else:
        across, up, around = xyz[:, 1], xyz[:, 0], xyz[:, 2]
        extent = [height[0], height[-1], lateral[0], lateral[-1], -0.5, 0.5]
    bounds = np.array(g.GetBounds())
    checks.expect(np.allclose(bounds, extent, rtol=0, atol=1e-9), where,
                  f"bounds {bounds.round(3)}, want the mesh's {np.round(extent, 3)}")
    checks.expect(len(np.unique(around)) == (sectors if dim == 3 else 2), where,
                  "the cells do not go round the axis (3D) or through -1/2..1/2 in z (2D)")
    corners = cell_points(g)
    # VTK numbers a structured grid's cells with the lateral index fastest, then the layer.
    for cell, ids in enumerate(corners):
        k, l = cell % bins, (cell // bins) % layers
        ok_lateral = np.allclose(np.sort(np.unique(np.round(across[ids], 9))),
                                 [lateral[k], lateral[k + 1]], atol=1e-9)
        ok_height = np.allclose(np.sort(np.unique(np.round(up[ids], 9))),
                                [height[l], height[l + 1]], atol=1e-9)
        if not checks.expect(ok_lateral and ok_height, where,
                             f"cell {cell} is not bin (layer {l}, lateral {k})"):
            return
    names = [key[len("mean:"):] for key in exp if key.startswith("mean:")]
    for name in names:
        got = array(g, name, cells=True)
        if not checks.expect(got is not None, where, f"no cell array {name}"):
            continue
        want = np.tile(np.asarray(exp["mean:" + name]).reshape(-1), sectors)
        checks.expect(np.allclose(got, want, rtol=0, atol=0, equal_nan=True), where,
                      f"{name} differs from its ensemble means")


def cover(png):
    """The fraction of an image's pixels that differ from its corner (the background)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader

    r = vtkPNGReader()
    r.SetFileName(png)
    r.Update()
    image = r.GetOutput()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(int)
    return float(np.mean(np.any(pixels != pixels[0], axis=1)))


def new_view(time, dimension):
    """A white 800x600 view with the jet falling down the screen: 3D runs seen from the side and a
    little above, 2D runs face on."""
    from paraview import simple

    view = simple.CreateRenderView()
    view.ViewSize = list(IMAGE_SIZE)
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    if time is not None:
        view.ViewTime = time
    if dimension == 3:
        view.CameraPosition = [0.0, -1.0, 0.4]
        view.CameraViewUp = [0.0, 0.0, 1.0]
    else:
        view.CameraPosition = [0.0, 0.0, 1.0]
        view.CameraViewUp = [1.0, 0.0, 0.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    return view


def show(source, view, what):
    """Grains as Point Gaussian spheres coloured by speed, contacts as lines coloured by
    |normal_force|, fields as cells coloured by phi."""
    from paraview import simple

    shown = simple.Show(source, view)
    if what == "grains":
        shown.SetRepresentationType("Point Gaussian")
        shown.GaussianRadius = 0.5
        simple.ColorBy(shown, ("POINTS", "velocity", "Magnitude"))
    else:
        shown.SetRepresentationType("Surface")
        if what == "contacts":
            shown.LineWidth = 2.0
            simple.ColorBy(shown, ("CELLS", "normal_force", "Magnitude"))
        else:
            simple.ColorBy(shown, ("CELLS", "phi"))
    shown.RescaleTransferFunctionToDataRange(True, False)
    return shown


def part_of(reader, what):
    """The grains' or the contacts' grid of a frames sidecar (by cell type: the Xdmf3 Reader S
    does not keep the grids' names), or the fields sidecar whole."""
    from paraview import simple

    if what == "fields":
        return reader
    kind = "Polyvertex" if what == "grains" else "Polyline"
    return simple.ExtractCellsByType(Input=reader, CellTypes=[kind])


def render(reader, what, time, dimension, png):
    from paraview import simple

    view = new_view(time, dimension)
    source = part_of(reader, what)
    show(source, view, what)
    view.ResetCamera()
    simple.SaveScreenshot(png, view, ImageResolution=list(IMAGE_SIZE))
    simple.Delete(view)
    if source is not reader:
        simple.Delete(source)


def strong_chains(contacts, time):
    """The bounds of the contacts that bear more than a tenth of the largest normal force (the
    impact zone, not the touching grains of the incoming jet), a few diameters wider."""
    from paraview import servermanager

    contacts.UpdatePipeline(time)
    lines = [b for b in leaves(servermanager.Fetch(contacts)) if b and b.GetNumberOfCells()]
    ends = []
    for block in lines:
        force = np.linalg.norm(np.atleast_2d(array(block, "normal_force", cells=True)), axis=1)
        strong = cell_points(block)[force > 0.1 * force.max()]
        ends.append(points(block)[strong.ravel()])
    xyz = np.vstack(ends)
    lo, hi = xyz.min(axis=0) - 3.0, xyz.max(axis=0) + 3.0
    return [lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]


def picture(xmf, time, dimension, png):
    """The README's picture: the grains, faint, coloured by speed, and their force chains, framed,
    from faint (weak) to dark (strong), each with its colour bar."""
    from paraview import simple

    reader = simple.XDMFReader(FileNames=[xmf])
    view = new_view(time, dimension)
    grains = show(part_of(reader, "grains"), view, "grains")
    grains.Opacity = 0.12
    contacts = part_of(reader, "contacts")
    chains = show(contacts, view, "contacts")
    chains.LineWidth = 3.0
    force = simple.GetColorTransferFunction("normal_force")
    force.ApplyPreset("Inferno (matplotlib)", True)
    force.InvertTransferFunction()
    for shown, name, title in ((grains, "velocity", "speed"), (chains, "normal_force", "|F_n|")):
        shown.SetScalarBarVisibility(view, True)
        bar = simple.GetScalarBar(simple.GetColorTransferFunction(name), view)
        bar.Title = title
        bar.ComponentTitle = ""
        bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    view.ResetCamera(strong_chains(contacts, time))
    simple.SaveScreenshot(png, view, ImageResolution=list(IMAGE_SIZE))
    simple.Delete(view)  # before exit: a view left to the interpreter's teardown ends in an X error


def run_checks(h5_path, exp, sidecars, png_dir, picture_path):
    from paraview import simple

    checks = Checks()
    dimension = int(exp["dimension"])
    base = os.path.splitext(os.path.abspath(h5_path))[0]
    files = {"frames": base + ".xmf", "fields": base + ".fields.xmf"}
    for sidecar in sidecars:
        for name in READERS:
            where = f"{name} {os.path.basename(files[sidecar])}"
            reader = open_reader(name, files[sidecar])
            before = len(checks.failures)
            if sidecar == "frames":
                check_frames(checks, where, reader, exp)
                time = float(exp["times"][-1])
                parts = ["grains"] + (["contacts"] if len(exp.get("pairs", [])) else [])
            else:
                check_fields(checks, where, reader, exp)
                time, parts = None, ["fields"]
            if len(checks.failures) == before:  # draw only what reads right
                for part in parts:
                    with tempfile.TemporaryDirectory() as tmp:
                        png = os.path.join(png_dir or tmp, f"{sidecar}_{part}_{name}.png")
                        render(reader, part, time, dimension, png)
                        share = cover(png)
                        checks.expect(share >= MIN_COVER[part], where,
                                      f"the {part} image is blank ({share:.4%} drawn)")
            simple.Delete(reader)
            print(f"{'ok  ' if len(checks.failures) == before else 'FAIL'} {where}")
    if picture_path and "frames" in sidecars:
        picture(files["frames"], float(exp["times"][-1]), dimension, picture_path)
    for failure in checks.failures:
        print("FAIL " + failure, file=sys.stderr)
    return 1 if checks.failures else 0


# ---------------------------------------------------------------------------------------------


def run_with_display(command):
    """Runs command, on a private X server (Xvfb) when there is no display, and passes its
    output on. pvpython now and then fails to open even a steady display ("bad X server
    connection", about 1 start in 12 here) and aborts before it checks anything: then it is
    started again, twice at most."""
    env = dict(os.environ)
    server = None
    if not env.get("DISPLAY") and shutil.which("Xvfb"):
        read, write = os.pipe()
        server = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0",
                                   "1280x1024x24", "-nolisten", "tcp"], pass_fds=[write],
                                  stderr=subprocess.DEVNULL)
        os.close(write)
        with os.fdopen(read) as ready:  # the display's number, once it accepts clients
            env["DISPLAY"] = ":" + ready.readline().strip()
    try:
        for _ in range(3):
            done = subprocess.run(command, env=env, capture_output=True, text=True)
            if "bad X server connection" not in done.stderr:
                break
        print(done.stdout, end="")
        print(done.stderr, end="", file=sys.stderr)
        return done.returncode
    finally:
        if server:
            server.terminate()
            server.wait()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("h5", help="a granjet run file, with its .xmf and .fields.xmf beside it")
    parser.add_argument("--png-dir", help="keep the rendered images here")
    parser.add_argument("--picture", help="draw the last frame's grains and force chains here")
    parser.add_argument("--pvpython", default=shutil.which("pvpython"), help="pvpython to use")
    parser.add_argument("--expect", help=argparse.SUPPRESS)  # set when it starts itself
    parser.add_argument("--sidecars", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.png_dir:
        os.makedirs(args.png_dir, exist_ok=True)

    if args.expect:
        exp = dict(np.load(args.expect))
        return run_checks(args.h5, exp, args.sidecars.split(",") if args.sidecars else [],
                          args.png_dir, args.picture)

    with tempfile.TemporaryDirectory() as tmp:
        npz = os.path.join(tmp, "expected.npz")
        sidecars = expectations(args.h5, npz)
        if not sidecars:
            print(f"{args.h5}: no sidecar to check beside it", file=sys.stderr)
            return 1
        for missing in {"frames", "fields"} - set(sidecars):
            print(f"note: no {missing} sidecar (or its data) for {args.h5}; not checked")
        if not args.pvpython:
            print("pvpython not found; pass --pvpython", file=sys.stderr)
            return 1
        command = [args.pvpython, os.path.abspath(__file__), args.h5, "--expect", npz,
                   "--sidecars", ",".join(sidecars)]
        for flag, value in (("--png-dir", args.png_dir), ("--picture", args.picture)):
            if value:
                command += [flag, os.path.abspath(value)]
        return run_with_display(command)


if __name__ == "__main__":
    sys.exit(main())
