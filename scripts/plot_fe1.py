#!/usr/bin/python3
"""Figure FE.1 (model §7) from the stability test's output: T_g(t) in layer (a), -dy < y < 0,
of the 2D jet at mu_p = 1.0 for several contact times t_c.

    GRANJET_STABILITY_FE1_FULL=1 build/tests/granjet_stability_tests --gtest_filter="Fe1*" > fe1.log
    /usr/bin/python3 scripts/plot_fe1.py fe1.log [--seed N] [--out docs/fe1_layer_a_temperature.png]

(LOG may be - for standard input.) Reads the lines

    [stability] fe1.tc<t_c>.seed<N>.series: from <t0> every <dt>: <T_g> <T_g> ...

that tests/stability/burst_test.cpp prints (ctest -V puts "<test number>: " in front; that is
skipped), and draws for one seed (default: the smallest in the log) T_g(t) for every t_c on
common axes, as the study's figure, and below it T_g(t)/<T_g>, the relative fluctuation that
the test's burst measures (CV, max/median) are made of. The legend gives each run's CV.
Prints the path written; exit code 2 when the log holds no series (of that seed).
Needs Debian's python3-matplotlib and -numpy (hence /usr/bin/python3).
"""
import argparse
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SERIES = re.compile(r"\[stability\] fe1\.tc([0-9.eE+-]+)\.seed(\d+)\.series: "
                    r"from ([0-9.eE+-]+) every ([0-9.eE+-]+):((?: \S+)*)\s*$")


def read_series(lines):
    """{(t_c, seed): (times, T_g)} of every series line."""
    series = {}
    for line in lines:
        match = SERIES.search(line)
        if not match:
            continue
        tc, seed, start, step, values = match.groups()
        tg = np.array([float(v) for v in values.split()])
        times = float(start) + float(step) * np.arange(len(tg))
        series[(float(tc), int(seed))] = (times, tg)
    return series


def coefficient_of_variation(x):
    return np.std(x, ddof=1) / np.mean(x)


def plot(series, seed, out):
    runs = sorted(((tc, data) for (tc, s), data in series.items() if s == seed), reverse=True)
    fig, (absolute, relative) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for tc, (times, tg) in runs:
        label = f"$t_c$ = {tc:g} (CV {coefficient_of_variation(tg):.2f})"
        absolute.plot(times, tg, lw=0.8, label=label)
        relative.plot(times, tg / np.mean(tg), lw=0.8, label=label)
    absolute.set_ylabel(r"$T_g$  [$m u_0^2$]")
    absolute.set_title(rf"FE.1: layer (a), $-dy < y < 0$, $\mu_p$ = 1.0, seed {seed}")
    absolute.legend()
    relative.set_ylabel(r"$T_g / \langle T_g \rangle$")
    relative.set_xlabel(r"$t$  [$d/u_0$]")
    relative.axhline(1.0, color="grey", lw=0.5)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("log", help="output of the Fe1Bursts stability test, or - for stdin")
    parser.add_argument("--seed", type=int, help="the seed drawn (default: the smallest)")
    parser.add_argument("--out", default="docs/fe1_layer_a_temperature.png")
    args = parser.parse_args(argv)
    if args.log == "-":
        series = read_series(sys.stdin)
    else:
        with open(args.log, encoding="utf-8") as log:
            series = read_series(log)
    seeds = sorted({seed for _, seed in series})
    seed = args.seed if args.seed is not None else (seeds[0] if seeds else None)
    if seed not in seeds:
        print(f"plot_fe1: error: no fe1 series of seed {seed} in {args.log} "
              f"(seeds found: {seeds or 'none'})", file=sys.stderr)
        return 2
    plot(series, seed, args.out)
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
