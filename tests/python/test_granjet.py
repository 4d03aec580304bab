"""The Python module: scenes with the CLI's keys and errors, simulators on both backends whose
trajectories and files are the CLI's bit for bit, NumPy views without copies, Ctrl-C, kinetic
theory.

Run by ctest (label python) with pytest from Debian and PYTHONPATH at the built module;
GRANJET_BINARY and GRANJET_SCENES_DIR name the command and the shipped scenes."""
import math
import os
import signal
import subprocess
import threading

import h5py
import numpy as np
import pytest

import granjet

SCENES = os.environ["GRANJET_SCENES_DIR"]
BINARY = os.environ["GRANJET_BINARY"]
SMALL_JET2D = ["jet.grains=600", "run.t_end=6", "analysis.window_start=3",
               "analysis.window_end=6"]


def scene_file(name):
    return os.path.join(SCENES, name)


def test_scene_from_file_round_trips_through_its_ini(tmp_path):
    scene = granjet.Scene.from_file(scene_file("jet2d.ini"), ["contact.friction=0.4"])
    assert scene.dimension == 2
    text = scene.to_ini()
    assert "friction = 0.4" in text
    path = tmp_path / "roundtrip.ini"
    path.write_text(text)
    assert granjet.Scene.from_file(str(path)).to_ini() == text


def test_scene_from_dict_flat_or_nested_and_set():
    flat = granjet.Scene.from_dict({"scene.kind": "binary", "scene.dimension": 2,
                                    "contact.clamp_normal": True})
    nested = granjet.Scene.from_dict({"scene": {"kind": "binary", "dimension": 2},
                                      "contact": {"clamp_normal": True}})
    assert flat.to_ini() == nested.to_ini()
    flat.set("run.t_end", 0.75)
    assert "t_end = 0.75" in flat.to_ini()
    flat.set("output.fields", ["position", "velocity", "radius", "id", "force"])
    assert "force" in flat.to_ini()


def test_bad_key_raises_scene_error_with_the_clis_message():
    with pytest.raises(granjet.SceneError) as raised:
        granjet.Scene.from_file(scene_file("jet2d.ini"), ["run.tend=5"])
    cli = subprocess.run([BINARY, "run", scene_file("jet2d.ini"), "--set", "run.tend=5"],
                         capture_output=True, text=True)
    assert cli.returncode == 2
    assert cli.stderr.strip() == "granjet: " + str(raised.value)
    scene = granjet.Scene.from_file(scene_file("jet2d.ini"))
    with pytest.raises(granjet.SceneError, match="contact.restitution"):
        scene.set("contact.restitution", 1.5)
    assert "restitution = 0.75" in scene.to_ini()  # a refused value changes nothing


def final_frame_by_id(h5_path):
    with h5py.File(h5_path, "r") as f:
        ids = f["particles/all/id/value"][-1]
        pos = f["particles/all/position/value"][-1]
        vel = f["particles/all/velocity/value"][-1]
    keep = ids >= 0
    order = np.argsort(ids[keep])
    return ids[keep][order], pos[keep][order], vel[keep][order]


@pytest.mark.parametrize("backend", ["soft_dem", "event_driven"])
def test_simulator_trajectory_is_the_clis_bit_for_bit(backend, tmp_path):
    overrides = SMALL_JET2D + ["output.interval=6"]
    out = tmp_path / "cli.h5"
    subprocess.run([BINARY, "run", scene_file("jet2d.ini"), "--backend", backend, "--quiet",
                    "--no-log", "--out", str(out)] + sum((["--set", o] for o in overrides), []),
                   check=True, capture_output=True)
    sim = granjet.Simulator(granjet.Scene.from_file(scene_file("jet2d.ini"), overrides), backend)
    for t in np.arange(0.5, 6.01, 0.5):  # many stops: advancing in steps changes nothing
        sim.advance_to(t)
    assert sim.time == pytest.approx(6.0, abs=1e-3)
    ids, pos, vel = final_frame_by_id(out)
    order = np.argsort(sim.ids)
    assert np.array_equal(sim.ids[order], ids)
    assert np.array_equal(sim.positions[order], pos)
    assert np.array_equal(sim.velocities[order], vel)


SMALL_GAS3D = ["gas.grains=500", "gas.equilibration=1", "run.t_end=3"]


@pytest.mark.parametrize("backend", ["soft_dem", "event_driven"])
@pytest.mark.parametrize("name, overrides", [("jet2d.ini", SMALL_JET2D),
                                             ("gas3d.ini", SMALL_GAS3D)])
def test_run_writes_the_clis_file(name, overrides, backend, tmp_path):
    # The files record the build (/h5md/creator version): the module and the command must be one.
    version = subprocess.run([BINARY, "--version"], capture_output=True, text=True).stdout
    commit = granjet.__version__.split("+")[1]
    assert f"(commit {commit})" in version, (
        f"the module ({granjet.__version__}) and the command ({version.strip()}) come from "
        "different builds: build both (cmake --build build)")
    cli, py = tmp_path / "cli.h5", tmp_path / "py.h5"
    subprocess.run([BINARY, "run", scene_file(name), "--backend", backend, "--quiet", "--no-log",
                    "--out", str(cli)] + sum((["--set", o] for o in overrides), []),
                   check=True, capture_output=True)
    sim = granjet.Simulator(granjet.Scene.from_file(scene_file(name), overrides), backend)
    summary = sim.run(str(py))
    assert summary["status"] == "complete" and summary["output"] == str(py)
    # Every dataset and attribute alike (h5diff exits 1 on a difference).
    diff = subprocess.run(["h5diff", str(cli), str(py)], capture_output=True, text=True)
    assert diff.returncode == 0, diff.stdout
    assert sim.time == pytest.approx(summary["time"])
    with pytest.raises(ValueError, match="from t = 0"):
        sim.run(str(tmp_path / "again.h5"))
    sim.advance_to(sim.time + 0.5)  # the simulator goes on after its run


def test_ctrl_c_in_run_keeps_a_resumable_partial(tmp_path):
    out = tmp_path / "run.h5"
    sim = granjet.Simulator(granjet.Scene.from_file(scene_file("jet3d.ini"),
                                                    ["jet.grains=4000", "run.t_end=1000",
                                                     "run.checkpoint_interval=0.5"]))
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt, match="granjet resume"):
        sim.run(str(out))
    timer.join()
    assert not out.exists()
    info = subprocess.run([BINARY, "info", str(out) + ".partial"], capture_output=True,
                          text=True, check=True).stdout
    assert "granjet resume continues from it" in info


def test_arrays_are_read_only_views_without_copies():
    sim = granjet.Simulator(granjet.Scene.from_file(scene_file("jet3d.ini"),
                                                    ["jet.grains=2000"]))
    sim.advance_to(0.2)
    positions = sim.positions
    assert positions.shape == (len(sim.ids), 3)
    assert not positions.flags.owndata and positions.base is not None
    assert not positions.flags.writeable
    assert sim.spins.shape == (len(sim.ids), 3)
    assert sim.radii.shape == (len(sim.ids),)
    with pytest.raises(ValueError):
        positions[0, 0] = 1.0
    e = sim.energies()
    assert e["total"] == pytest.approx(e["kinetic"] + e["rotational"] + e["elastic"])
    assert sim.stats()["steps"] > 0


def test_a_million_grains_are_read_without_a_copy():
    sim = granjet.Simulator(granjet.Scene.from_file(
        scene_file("jet3d.ini"), ["jet.grains=1000000", "jet.diameter=100", "wall.diameter=220",
                                  "region.radius=440"]))
    first, second = sim.positions, sim.positions
    assert first.shape[0] > 1_000_000 and first.shape[1] == 3
    assert not first.flags.owndata and first.base is not None  # owned by the simulator
    assert np.shares_memory(first, second)  # the same memory, read twice


def test_contact_forces_of_the_soft_dem():
    sim = granjet.Simulator(granjet.Scene.from_file(scene_file("jet2d.ini"), SMALL_JET2D))
    sim.advance_to(4.0)
    forces = sim.forces()
    pairs = forces["pairs"]
    assert pairs.shape[1] == 2 and len(pairs) > 0
    assert forces["normal"].shape == (len(pairs), 2)
    assert (forces["overlap"] > 0).all()
    # Each jet grain's total force is its contacts' (Newton's third law for the partner); the
    # target grains feel their tethers besides.
    index = {grain: k for k, grain in enumerate(sim.ids)}
    expected = np.zeros_like(forces["total"])
    for (i, j), f in zip(pairs, forces["normal"] + forces["tangential"]):
        expected[index[i]] += f
        if j >= 0:
            expected[index[j]] -= f
    jet = sim.ids < 600
    scale = np.abs(expected).max()
    assert np.abs(forces["total"][jet] - expected[jet]).max() <= 1e-12 * scale


def test_ctrl_c_raises_keyboard_interrupt_and_the_simulator_goes_on():
    sim = granjet.Simulator(granjet.Scene.from_file(scene_file("jet3d.ini"),
                                                    ["jet.grains=4000", "run.t_end=1000"]))
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.advance_to(1000.0)
    timer.join()
    stopped = sim.time
    assert 0.0 < stopped < 1000.0
    sim.advance_to(stopped + 0.5)
    assert sim.time == pytest.approx(stopped + 0.5, abs=0.01)


def test_theory_returns_what_the_library_computes():
    t = granjet.theory
    phi, e = 0.3, 0.75
    chi = (1 - phi / 2) / (1 - phi) ** 3  # [5.3] below phi_f
    assert t.chi(phi) == pytest.approx(chi, rel=1e-12)
    assert t.pressure_ratio(phi, e) == pytest.approx(1 + 2 * phi * (1 + e) * chi, rel=1e-12)
    assert t.effective_restitution(0.75, 0.2) == pytest.approx(
        0.75 - math.pi / 2 * 0.2 + 4.5 * 0.04, rel=1e-12)
    a2 = 16 * (1 - e) * (1 - 2 * e ** 2) / (81 - 17 * e + 30 * e ** 2 * (1 - e))  # [2.37]
    assert t.sonine_a2(e) == pytest.approx(a2, rel=1e-12)
    assert t.viscosity_star(0.3, 0.75) == pytest.approx(3.430280, abs=2e-6)
    c = granjet.contact.coefficients(0.75, 0.1)  # T4.1's row e = 0.75, t_c = 0.1
    assert c["k_n"] == pytest.approx(4.98e2, rel=5e-3)
    assert c["eta_n"] == pytest.approx(2.88, rel=5e-3)
    back = granjet.contact.collision(c["k_n"], c["eta_n"])
    assert back["e"] == pytest.approx(0.75, rel=1e-13)
    assert back["t_c"] == pytest.approx(0.1, rel=1e-13)


def test_theory_and_laws_take_arrays_element_by_element():
    phi = np.array([0.1, 0.3, 0.55, 0.64])
    chi = granjet.theory.chi(phi)
    assert chi.shape == phi.shape
    assert chi[1] == granjet.theory.chi(0.3) and np.isinf(chi[3])
    i = np.array([0.01, 0.1, 1.0])
    assert np.allclose(granjet.fits.packing_law(i, 0.8, 0.5, 1.5), 0.8 - 0.5 * i ** (2 / 1.5),
                       rtol=1e-14)


def test_fits_recover_the_laws_they_fit():
    i_s = np.linspace(0.01, 1.0, 40)
    mu = granjet.fits.friction_saturating(i_s, 0.25, 0.6, 0.3)
    fit = granjet.fits.mu_saturating(i_s, mu)
    assert fit["law"] == "6.9" and fit["converged"] and fit["points"] == 40
    for name, value in {"mu_s": 0.25, "mu_max": 0.6, "I_0": 0.3}.items():
        assert fit["parameters"][name][0] == pytest.approx(value, rel=1e-6)
    with pytest.raises(ValueError):
        granjet.fits.mu_linear([1.0, 2.0], [1.0])


def test_open_reads_back_what_the_cli_wrote(tmp_path):
    out = tmp_path / "run.h5"
    subprocess.run([BINARY, "run", scene_file("jet2d.ini"), "--quiet", "--no-log", "--out",
                    str(out)] + sum((["--set", o] for o in SMALL_JET2D + ["output.interval=2"]),
                                    []), check=True, capture_output=True)
    f = granjet.open(str(out))
    assert f.summary["status"] == "complete" and f.summary["dimension"] == 2
    assert f.summary["frames"] == 4  # t = 0, 2, 4, 6
    info = subprocess.run([BINARY, "info", str(out), "--scene"], capture_output=True, text=True,
                          check=True).stdout
    assert f.scene.to_ini().strip() == info.strip()  # the resolved scene, as the run stored it
    ids, pos, vel = final_frame_by_id(out)
    last = f.frame(3)
    assert last["time"] == pytest.approx(6.0)
    assert np.array_equal(last["ids"], ids) and np.array_equal(last["positions"], pos)
    with h5py.File(out, "r") as h5:
        kinetic = h5["observables/kinetic_energy/value"][()]
        t_g = h5["fields/T_g/mean"][()]
    assert np.array_equal(f.dataset("/observables/kinetic_energy/value"), kinetic)
    assert np.isfinite(t_g).any()
    assert np.array_equal(f.dataset("/fields/T_g/mean"), t_g, equal_nan=True)  # shape kept
    # By name: the fields as the JSON summary names them, the observables with their times.
    fields = f.fields
    assert "mesh" not in fields and "layout" not in fields
    assert set(fields["T_g"]) == {"mean", "std", "sem", "count"}
    assert np.array_equal(fields["T_g"]["mean"], t_g, equal_nan=True)
    assert fields["stress.xy"]["mean"].shape == t_g.shape
    energy = f.observables["kinetic_energy"]
    assert np.array_equal(energy["value"], kinetic) and energy["time"][-1] == pytest.approx(6.0)
    with pytest.raises(Exception):
        f.dataset("/fields/no_such_field/mean")


def test_the_example_compares_the_backends_in_layer_a(tmp_path):
    example = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "jet2d_layer_a.py")
    subprocess.run(["/usr/bin/python3", example, str(tmp_path)], check=True, capture_output=True,
                   env=dict(os.environ))
    assert (tmp_path / "jet2d_layer_a.png").stat().st_size > 0
    soft, hard = (granjet.open(str(tmp_path / f"jet2d_{b}.h5")).fields["phi"]["mean"][0]
                  for b in ("soft_dem", "event_driven"))
    # Soft and hard grains of one restitution pack alike on the target (within 0.05; the
    # docs/python.md figure: 0.65-0.76 across the jet).
    assert np.all(np.abs(soft - hard) < 0.05) and np.all((soft > 0.5) & (soft < 0.85))
