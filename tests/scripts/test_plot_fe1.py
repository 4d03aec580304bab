#!/usr/bin/python3
"""Tests of scripts/plot_fe1.py on synthetic logs in the format of
tests/stability/burst_test.cpp (`[stability] fe1.tc<t_c>.seed<N>.series: from <t0> every <dt>:
<values>`, with and without the "<n>: " that ctest -V puts in front).

    /usr/bin/python3 tests/scripts/test_plot_fe1.py
"""
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "plot_fe1.py")
sys.dont_write_bytecode = True  # no __pycache__ in scripts/
sys.path.insert(0, os.path.dirname(SCRIPT))
import plot_fe1  # noqa: E402
import script_tests  # noqa: E402

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

LOG = """\
[ RUN      ] Fe1Bursts.FE1_LayerATemperatureBurstsForSoftGrainsAndCalmsForStiffOnes
[stability] fe1.tc0.1.seed1: <T_g> = 0.002, CV = 0.5, max/median = 3, block CV = 0.4
[stability] fe1.tc0.1.seed1.series: from 30 every 0.25: 0.001 0.003 0.002 0.002
1: [stability] fe1.tc0.01.seed1.series: from 30 every 0.25: 0.0005 0.0005 0.001 0.0002
[stability] fe1.tc0.1.seed2.series: from 30 every 0.25: 0.004 0.004 0.004 0.004
[stability] fe1.tc0.1: 2000 grains, mean +- std over seeds 1-3: <T_g> = 0.002 +- 0.0003
"""


def run_script(tmp, *args, stdin=None):
    return subprocess.run([sys.executable, "-B", SCRIPT, *args], input=stdin, cwd=tmp,
                          capture_output=True, text=True, check=False)


def test_reads_every_series_with_its_times(tmp):
    series = plot_fe1.read_series(LOG.splitlines())
    assert sorted(series) == [(0.01, 1), (0.1, 1), (0.1, 2)]
    times, tg = series[(0.01, 1)]  # the line with the ctest prefix
    assert np.allclose(times, [30.0, 30.25, 30.5, 30.75])
    assert np.allclose(tg, [0.0005, 0.0005, 0.001, 0.0002])


def test_coefficient_of_variation_is_the_sample_one(tmp):
    x = np.array([1.0, 2.0, 3.0])
    assert abs(plot_fe1.coefficient_of_variation(x) - 0.5) < 1e-12  # std (n - 1) = 1, mean 2


def test_draws_the_figure_from_stdin(tmp):
    out = os.path.join(tmp, "fe1.png")
    result = run_script(tmp, "-", "--out", out, stdin=LOG)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == out
    with open(out, "rb") as png:
        assert png.read(8) == PNG_SIGNATURE


def test_draws_a_chosen_seed_from_a_file(tmp):
    log = os.path.join(tmp, "fe1.log")
    with open(log, "w", encoding="utf-8") as f:
        f.write(LOG)
    out = os.path.join(tmp, "seed2.png")
    result = run_script(tmp, log, "--seed", "2", "--out", out)
    assert result.returncode == 0, result.stderr
    assert os.path.getsize(out) > 0


def test_a_log_without_the_seed_is_refused_and_writes_nothing(tmp):
    out = os.path.join(tmp, "none.png")
    result = run_script(tmp, "-", "--seed", "7", "--out", out, stdin=LOG)
    assert result.returncode == 2
    assert "no fe1 series of seed 7" in result.stderr and "[1, 2]" in result.stderr
    assert not os.path.exists(out)
    result = run_script(tmp, "-", "--out", out, stdin="nothing here\n")
    assert result.returncode == 2 and "seeds found: none" in result.stderr


if __name__ == "__main__":
    sys.exit(script_tests.run(globals()))
