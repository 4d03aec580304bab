#!/usr/bin/python3
"""Tests of scripts/plot_analysis.py on small synthetic analysis files.

    /usr/bin/python3 tests/scripts/test_plot_analysis.py

The files follow analysis/field_writer.cpp exactly: /fields (int attributes dimension, seeds;
fixed-length string coordinates), mesh/{lateral,height}, layout/<name> [layers][lateral],
<path>/{mean,std,sem (double), count (int)}; /analysis/global scalars, vdf, azimuth (3D),
fits/<law>/{value,error} with attributes parameters (fixed-length string array), ssr, points,
converged. Prints "N passed, M failed" last; exit code 0 only when all pass.
"""
import os
import subprocess
import sys

import h5py
import matplotlib.pyplot as plt
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "plot_analysis.py")
sys.dont_write_bytecode = True  # no __pycache__ in scripts/
sys.path.insert(0, os.path.dirname(SCRIPT))
import plot_analysis  # noqa: E402  (its formulas, to make data that follow the laws)
import script_tests  # noqa: E402

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


# ---- Writing like field_writer.cpp ----------------------------------------------------------
def string_attribute(obj, name, values):
    """H5T_C_S1 of size len+1 (NUL-terminated), scalar or 1D, as GroupWriter::attribute."""
    values_list = [values] if isinstance(values, str) else list(values)
    width = max(1, max(len(v) + 1 for v in values_list))
    tid = h5py.h5t.C_S1.copy()
    tid.set_size(width)
    space = h5py.h5s.create(h5py.h5s.SCALAR) if isinstance(values, str) else \
        h5py.h5s.create_simple((len(values_list),))
    attr = h5py.h5a.create(obj.id, name.encode(), tid, space)
    data = np.array([v.encode() for v in values_list], dtype=f"S{width}")
    attr.write(data.reshape(()) if isinstance(values, str) else data, mtype=tid)


def spreads(group, name, mean, std):
    base = group.require_group(name.replace(".", "/"))
    mean = np.asarray(mean, dtype=np.float64)
    base["mean"] = mean
    base["std"] = np.asarray(std, dtype=np.float64)
    base["sem"] = np.asarray(std, dtype=np.float64) / np.sqrt(3)
    base["count"] = np.where(np.isfinite(mean), 3, 0).astype(np.int32)


def write_analysis(path, dim, fields, glob, fits, scene=None, drop=()):
    """fields: name -> mean [layers][lateral] (std 5 % of it); drop: field names left out."""
    rng = np.random.default_rng(7)
    layers, lateral = fields["phi"].shape
    r_tar = 11.0 if dim == 3 else 33.0
    with h5py.File(path, "w") as f:
        if scene is not None:  # as the H5MD writer stores it
            f.create_group("h5md")
            f["parameters/granjet/scene"] = np.array(scene.encode(), dtype=f"S{len(scene) + 1}")
        g = f.create_group("fields")
        g.attrs.create("dimension", dim, dtype=np.int32)
        g.attrs.create("seeds", 3, dtype=np.int32)
        string_attribute(g, "coordinates", "cylindrical" if dim == 3 else "cartesian")
        lo = 0.0 if dim == 3 else -r_tar
        edges = np.linspace(lo, r_tar, lateral + 1)
        g["mesh/lateral"] = edges
        g["mesh/height"] = np.linspace(0, 5.0 * layers, layers + 1)
        centre = np.tile(0.5 * (edges[1:] + edges[:-1]), (layers, 1))
        name = "r" if dim == 3 else "y"
        layout = {"layer": np.repeat(np.arange(layers), lateral).reshape(layers, lateral),
                  "lateral_index": np.tile(np.arange(lateral), (layers, 1)), name: centre,
                  f"{name}_over_R_tar": centre / r_tar,
                  "h": np.repeat(2.5 + 5.0 * np.arange(layers), lateral).reshape(layers, lateral),
                  "volume": np.full((layers, lateral), 10.0)}
        for key, value in layout.items():
            g[f"layout/{key}"] = np.asarray(value, dtype=np.float64)
        for key, mean in fields.items():
            if key not in drop:
                spreads(g, key, mean, np.abs(mean) * (0.05 + 0.02 * rng.random(mean.shape)))
        a = f.create_group("analysis")
        for key, value in glob.items():
            spreads(a, f"global/{key}", np.float64(value), np.float64(0.1))
        c = 6.0 * (np.arange(48) + 0.5) / 24 - 6.0
        a["vdf/c"] = c
        for axis in ("r", "t", "z") if dim == 3 else ("x", "y"):
            density = 0.5 * plot_analysis.unit_gaussian(c) + 0.25 * np.exp(-np.abs(c) * 1.4)
            density[np.abs(c) > 5] = 0.0  # empty intervals: not drawable on a log axis
            spreads(a, f"vdf/density/{axis}", density, 0.1 * density)
            del a[f"vdf/density/{axis}/count"]  # write_distribution has no count
        if dim == 3:
            a["azimuth/phi"] = 2 * np.pi * (np.arange(36) + 0.5) / 36
            spreads(a, "azimuth/dN_dphi", np.ones(36), np.full(36, 0.1))
        for law, (names, value, points) in fits.items():
            fit = a.create_group(f"fits/{law}")
            fit["value"] = np.asarray(value, dtype=np.float64)
            fit["error"] = np.abs(fit["value"][()]) * 0.05 if points > len(names) else \
                np.full(len(names), np.nan)
            string_attribute(fit, "parameters", names)
            fit.attrs.create("ssr", 1e-3 if points >= len(names) else np.nan, dtype=np.float64)
            fit.attrs.create("points", points, dtype=np.int32)
            fit.attrs.create("converged", 1.0 if points > len(names) else 0.0, dtype=np.float64)


def tensor(fields, name, axes, values):
    for a in axes:
        for b in axes:
            fields[f"{name}.{a}{b}"] = values(a, b)


def jet3d(path, scene=True):
    r = np.array([[0.1, 0.3, 0.5, 0.7, 0.9]])
    phi = 0.55 - 0.2 * r
    t_g = 0.002 + 0.03 * r
    n = phi * 6 / np.pi
    i = 0.02 + 0.3 * r
    p = n * t_g * plot_analysis.pressure_ratio_5_2(phi, 0.616)
    mu = 0.45 * i
    diag = {"r": 1.0, "t": 0.9, "z": 1.1}
    f = {"n": n, "phi": phi, "T_g": t_g, "P": p, "P_over_nT": p / (n * t_g), "I": i,
         "mu_star": mu, "D": i * np.sqrt(p), "eta": mu * p / i, "eta_star": 1 + 0 * r,
         "sigma_Y": 0.01 + 0 * r}
    for a in diag:
        f[f"v.{a}"] = (0.8 * r if a == "r" else -0.3 * (1 - r) if a == "z" else 0 * r + 1e-3)
        f[f"T_alpha.{a}"] = t_g * diag[a]
        f[f"P_over_nT_alpha.{a}"] = p * diag[a] / (n * t_g * diag[a]) * (1 + 0.05 * (a == "z"))
        f[f"flatness.{a}"] = 3.5 + 0 * r

    def kin(a, b):
        return n * t_g * diag[a] if a == b else 0.02 * n * t_g

    def con(a, b):  # the shear stress of mu* = -sigma_rz/P
        return (p - n * t_g) * diag[a] if a == b else -mu * p if a + b in ("rz", "zr") else 0 * r

    tensor(f, "stress_kinetic", "rtz", kin)
    tensor(f, "stress_contact", "rtz", con)
    tensor(f, "stress", "rtz", lambda a, b: kin(a, b) + con(a, b))
    tensor(f, "stress_xyz", "xyz", lambda a, b: p if a == b else 0 * r)
    glob = {"flatness_bin.r": 3.4, "flatness_bin.t": 3.2, "flatness_bin.z": 4.1,
            "flatness_region.r": 3.9, "flatness_region.t": 3.3, "flatness_region.z": 4.6,
            "psi0": 1.2, "v2": 0.01,
            "scattered": 900, "samples": 101, "transfer_time": 50, "window_start": 50,
            "window_end": 100}
    ini = ("[scene]\nname = jet3d\nkind = jet\ndimension = 3\n\n[contact]\nrestitution = 0.75\n"
           "contact_time = 0.1\nfriction = 0.2\n") if scene else None
    write_analysis(path, 3, f, glob, {"mu_linear": (["a"], [0.45], 5)}, scene=ini)


def jet2d(path, frames_only=False):
    """frames_only: no transfers stored, so the contact stress and all that needs P are NaN
    (field_accumulator.cpp), the fits have no points (fits.cpp) and T_g is left out."""
    y = np.linspace(-0.9, 0.9, 10)[None, :] + np.zeros((2, 1))
    layer = np.array([[0.0], [1.0]])
    i_t = 0.03 + 0.2 * np.abs(y) + 0.05 * layer
    i_s = 0.01 + 0.4 * np.abs(y) + 0.05 * layer
    phi = plot_analysis.packing_6_2_6_3(i_t, 0.82, 0.5, 1.5)
    t_g = 0.001 + 0.01 * np.abs(y)
    n = phi * 4 / np.pi
    p = 4 * n * t_g
    mu = plot_analysis.friction_6_9(i_s, 0.25, 0.6, 0.3)
    nan = np.full_like(y, np.nan) if frames_only else 0 * y
    f = {"n": n, "phi": phi, "T_g": t_g, "P": p + nan, "P_over_nT": p / (n * t_g) + nan,
         "I_s": i_s + nan, "I_T": i_t + nan, "mu_star": mu + nan, "D": i_s + nan,
         "eta": mu + nan, "eta_star": 1 + nan}
    for a in "xy":
        f[f"v.{a}"] = -0.5 * (1 - np.abs(y)) if a == "x" else 0.8 * y
        f[f"T_alpha.{a}"] = t_g * (1.2 if a == "x" else 0.8)
        f[f"P_over_nT_alpha.{a}"] = 4.0 + 0.2 * (a == "x") + nan
        f[f"flatness.{a}"] = 3.3 + 0 * y

    def kin(a, b):
        return n * f[f"T_alpha.{a}"] if a == b else 0.01 * y * n * t_g

    def con(a, b):  # NaN without transfers
        return ((p - n * t_g) if a == b else -np.sign(y) * mu * p) + nan

    tensor(f, "stress_kinetic", "xy", kin)
    tensor(f, "stress_contact", "xy", con)
    tensor(f, "stress", "xy", lambda a, b: kin(a, b) + con(a, b))
    glob = {"flatness_bin.x": 3.6, "flatness_bin.y": 3.1, "flatness_region.x": 4.2,
            "flatness_region.y": 3.5, "psi0": 1.0, "scattered": 300, "samples": 241,
            "transfer_time": 0 if frames_only else 120, "window_start": 180, "window_end": 300}
    points = 0 if frames_only else 20
    fits = {"6.2": (["phi_T", "a_T", "alpha_T"], [0.82, 0.5, 1.5], points),
            "6.3": (["phi_s", "a_s", "alpha_s"], [0.8, 0.3, 1.2], points),
            "6.9": (["mu_s", "mu_max", "I_0"], [0.25, 0.6, 0.3], points),
            "6.10": (["b", "beta"], [0.5, 0.8], points)}  # mu_s = 0 fixed (fits.cpp)
    if frames_only:  # fits.cpp returns the initial guess, unfitted
        fits = {law: (names, [0.0] * (len(names) - 1) + [2.0], 0)
                for law, (names, _, _) in fits.items()}
    write_analysis(path, 2, f, glob, fits, drop=("T_g",) if frames_only else ())


# ---- Running and checking -------------------------------------------------------------------
def run(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True,
                          timeout=300)


def check_png(path):
    assert os.path.isfile(path), f"{path} was not written"
    with open(path, "rb") as png:
        head = png.read(24)
    assert head[:8] == PNG_SIGNATURE, f"{path} is not a PNG"
    assert os.path.getsize(path) > 5000, f"{path} is suspiciously small"
    image = plt.imread(path)
    assert image.shape[0] > 200 and image.shape[1] > 200, f"{path}: {image.shape}"
    assert image.std() > 0.01, f"{path} looks blank"


def check_outputs(result, out, stem, figures):
    assert result.returncode == 0, f"exit {result.returncode}\n{result.stderr}"
    expected = [os.path.join(out, f"{stem}_{f}.png") for f in figures]
    listed = result.stdout.split()
    assert listed == expected, f"listed {listed}, expected {expected}"
    for path in expected:
        check_png(path)
    assert "Traceback" not in result.stderr and "Warning" not in result.stderr, result.stderr


def test_3d_all_figures(tmp):
    jet3d(os.path.join(tmp, "jet3d.h5"))
    out = os.path.join(tmp, "out3d")
    result = run(os.path.join(tmp, "jet3d.h5"), "--out", out)
    check_outputs(result, out, "jet3d", ["stress", "profiles", "eos", "friction", "vdf"])
    assert "plot_analysis: note" not in result.stderr, result.stderr


def test_3d_restitution_from_the_stored_scene(tmp):
    jet3d(os.path.join(tmp, "scene.h5"))
    a = plot_analysis.Analysis(os.path.join(tmp, "scene.h5"))
    e, source = a.scene_restitution()
    assert abs(e - 0.616) < 5e-4, (e, source)  # e-bar [2.55], e = 0.75, mu_p = 0.2
    jet3d(os.path.join(tmp, "bare.h5"), scene=False)
    assert plot_analysis.Analysis(os.path.join(tmp, "bare.h5")).scene_restitution() is None


def test_3d_default_out_is_the_file_directory(tmp):
    jet3d(os.path.join(tmp, "run.h5"), scene=False)
    result = run(os.path.join(tmp, "run.h5"), "--restitution", "0.9")
    check_outputs(result, tmp, "run", ["stress", "profiles", "eos", "friction", "vdf"])


def test_2d_all_figures(tmp):
    jet2d(os.path.join(tmp, "jet2d.h5"))
    out = os.path.join(tmp, "out2d")
    result = run(os.path.join(tmp, "jet2d.h5"), "--out", out)
    check_outputs(result, out, "jet2d",
                  ["stress", "profiles", "eos", "friction", "packing", "vdf"])
    assert "plot_analysis: note" not in result.stderr, result.stderr


def test_vdf_legend_shows_flatness_under_both_scalings(tmp):
    jet3d(os.path.join(tmp, "jet3d.h5"))
    a = plot_analysis.Analysis(os.path.join(tmp, "jet3d.h5"))
    with a.h5:
        label = plot_analysis.flatness_label(a, "z")
    assert label == "flatness bin 4.1 ± 0.1, region 4.6 ± 0.1", label


def test_2d_without_contact_stress_skips_with_notes(tmp):
    jet2d(os.path.join(tmp, "frames.h5"), frames_only=True)
    out = os.path.join(tmp, "frames")
    result = run(os.path.join(tmp, "frames.h5"), "--out", out)
    check_outputs(result, out, "frames", ["stress", "profiles", "vdf"])
    for expected in ("kinetic part", "field T_g is absent", "field P_over_nT is all NaN",
                     "equation-of-state figure skipped", "friction figure skipped",
                     "packing figure skipped"):
        assert expected in result.stderr, f"no note '{expected}' in:\n{result.stderr}"


def test_a_run_file_without_analysis_is_refused(tmp):
    path = os.path.join(tmp, "plain.h5")
    with h5py.File(path, "w") as f:
        f.create_group("h5md")
        f["particles/all/position/value"] = np.zeros((1, 4, 3))
    result = run(path, "--out", os.path.join(tmp, "none"))
    assert result.returncode == 2, (result.returncode, result.stderr)
    assert "holds no analysis" in result.stderr and "Traceback" not in result.stderr, \
        result.stderr
    assert not os.path.exists(os.path.join(tmp, "none")) or not os.listdir(
        os.path.join(tmp, "none"))


def test_nothing_to_draw_exits_non_zero_and_writes_no_figure(tmp):
    """An analysis whose every value is NaN (a window that never started, written by an older
    granjet) has nothing to draw: exit 1, no PNG, and the reason on stderr."""
    path = os.path.join(tmp, "empty.h5")
    jet2d(path)
    with h5py.File(path, "r+") as f:
        def blank(name, node):
            if isinstance(node, h5py.Dataset) and name.endswith("/mean"):
                node[...] = np.nan
        f["fields"].visititems(blank)
        f["analysis"].visititems(blank)
    out = os.path.join(tmp, "empty")
    result = run(path, "--out", out)
    assert result.returncode == 1, (result.returncode, result.stderr)
    assert "nothing to draw" in result.stderr and "Traceback" not in result.stderr, \
        result.stderr
    assert not os.path.isdir(out) or not [p for p in os.listdir(out) if p.endswith(".png")]


def test_a_file_that_is_not_hdf5_is_refused(tmp):
    for path in (os.path.join(tmp, "notes.txt"), os.path.join(tmp, "missing.h5")):
        if path.endswith(".txt"):
            with open(path, "w") as f:
                f.write("not an HDF5 file\n")
        result = run(path)
        assert result.returncode == 2, (path, result.returncode, result.stderr)
        expected = "cannot be read as HDF5" if path.endswith(".txt") else "no such file"
        assert expected in result.stderr and "Traceback" not in result.stderr, result.stderr


def test_formulas_match_the_spec(tmp):
    f = plot_analysis
    assert abs(f.effective_restitution_2_55(0.75, 0.2) - 0.616) < 5e-4  # model §6
    assert abs(f.chi_5_3(0.3) - (1 - 0.15) / 0.7 ** 3) < 1e-12  # [5.3] dilute branch
    below, above = f.chi_5_3(0.49 - 1e-9), f.chi_5_3(0.49 + 1e-9)
    assert abs(below - above) < 1e-6 * below  # continuous at phi_f
    assert np.isinf(f.chi_5_3(0.64))
    assert abs(f.pressure_ratio_5_2(0.0, 0.75) - 1.0) < 1e-12
    assert abs(f.friction_6_9(1e9, 0.2, 0.6, 0.3) - 0.6) < 1e-6  # saturates at mu_max
    # [6.10] with mu_s = 0 (fits.cpp's two parameters b, beta): b at I_s = 1, zero at I_s = 0
    assert abs(f.friction_6_10(1.0, 0.5, 0.8) - 0.5) < 1e-12
    assert f.friction_6_10(0.0, 0.5, 0.8) == 0.0
    assert abs(f.friction_6_10(0.25, 0.5, 0.5) - 0.25) < 1e-12


if __name__ == "__main__":
    sys.exit(script_tests.run(globals()))
