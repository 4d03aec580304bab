#!/usr/bin/python3
"""Figures of a granjet analysis file (model §6-§7: F5.3-F5.7, T5.1, F6.3-F6.7).

    /usr/bin/python3 scripts/plot_analysis.py run.h5 [--out DIR] [--restitution E]

Reads the /fields and /analysis groups written by analysis/field_writer.cpp and writes
<stem>_<figure>.png into DIR (default: the file's directory). Prints the paths written on
stdout, one per line; a figure or panel whose fields are absent or all NaN (e.g. no contact
stress when only stored frames were analysed) is skipped with a note on stderr. Exit code 2
when the file cannot be read or holds no analysis.

Units as in the model: length d, mass m, velocity u0; stresses in m u0^2/d^D. Error bars are
the standard deviation over seeds. Needs Debian's python3-h5py, -matplotlib and -numpy.
"""
import argparse
import configparser
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# granjet's Python module (bash scripts/setup.sh builds it into build/python): the formulas
# below are the analysis' own (analysis/kinetic_theory.cpp, analysis/fits.cpp), not copies.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "build", "python"))
try:
    import granjet  # noqa: E402
    from granjet import fits, theory  # noqa: E402
except ImportError as missing:
    sys.exit(f"{os.path.basename(__file__)}: the granjet Python module is not built ({missing}); "
             "bash scripts/setup.sh builds it into build/python")

PHI_F, PHI_C = theory.PHI_FREEZING, theory.PHI_CLOSE_PACKING  # [5.3]
chi_5_3 = theory.chi  # [5.3]
pressure_ratio_5_2 = theory.pressure_ratio  # [5.2], also P_alpha/(n T_alpha)
effective_restitution_2_55 = theory.effective_restitution  # [2.55]
packing_6_2_6_3 = fits.packing_law  # [6.2], [6.3]
friction_6_9 = fits.friction_saturating  # [6.9]
friction_linear_3d = fits.friction_linear  # 3D mu* = a I (F5.7)


def friction_6_10(i_s, b, beta):
    """[6.10] with mu_s = 0, as the study fits it (model §6)."""
    return fits.friction_power(i_s, 0.0, b, beta)


def unit_gaussian(c):
    """Density of a unit-variance Gaussian, reference of the scaled velocities (T5.1)."""
    return np.exp(-np.asarray(c) ** 2 / 2) / np.sqrt(2 * np.pi)


# Fit groups /analysis/fits/<law> (fits.hpp): model, legend label, whether x must be > 0.
FIT_LAWS = {"mu_linear": (friction_linear_3d, r"$\mu^* = a I$", False),
            "6.2": (packing_6_2_6_3, "[6.2]", True), "6.3": (packing_6_2_6_3, "[6.3]", True),
            "6.9": (friction_6_9, "[6.9]", True), "6.10": (friction_6_10, "[6.10]", True)}
TEX = {"t": r"\theta", "mu_s": r"\mu_s", "mu_max": r"\mu_{max}", "phi_T": r"\phi_T",
       "phi_s": r"\phi_s", "alpha_T": r"\alpha_T", "alpha_s": r"\alpha_s", "beta": r"\beta"}
MARKERS = "osD^v<>ph*"


class NotAnalysisFile(Exception):
    pass


def note(message):
    print(f"plot_analysis: note: {message}", file=sys.stderr)


def text(value):
    """HDF5 fixed-length strings come back as bytes."""
    if isinstance(value, np.ndarray):
        return [text(v) for v in value.ravel()]
    return value.decode() if isinstance(value, (bytes, np.bytes_)) else str(value)


def tex(name):
    return TEX.get(name, name)


class Analysis:
    """The layout of field_writer.cpp: /fields/<path>/{mean,std,...} [layers][lateral]."""

    def __init__(self, path):
        if not os.path.isfile(path):
            raise NotAnalysisFile(f"'{path}': no such file")
        try:
            self.h5 = h5py.File(path, "r")
        except OSError as err:
            raise NotAnalysisFile(f"'{path}' cannot be read as HDF5 ({err})") from None
        fields = self.h5.get("fields")
        self.dim = int(fields.attrs.get("dimension", 0)) if isinstance(fields, h5py.Group) else 0
        lateral = "r" if self.dim == 3 else "y"
        key = f"layout/{lateral}_over_R_tar"
        if self.dim not in (2, 3) or "analysis" not in self.h5 or key not in fields or \
                "mesh/height" not in fields:
            self.h5.close()
            raise NotAnalysisFile(f"'{path}' holds no analysis (/fields with attribute dimension,"
                                  f" /fields/{key}, mesh/height and /analysis): analyse the run")
        self.name = os.path.basename(path)
        self.seeds = int(fields.attrs.get("seeds", 0))
        self.axes = ("r", "t", "z") if self.dim == 3 else ("x", "y")
        self.x = fields[key][()]  # [layers][lateral] bin centres over R_tar
        self.x_label = f"${lateral}/R_{{tar}}$"
        h = fields["mesh/height"][()]
        normal = "z" if self.dim == 3 else "x"
        self.layers = [f"({chr(97 + k)}) ${h[k]:g} < {normal} \\leq {h[k + 1]:g}$ d"
                       for k in range(len(h) - 1)]
        self.title = f"{self.name}: {self.dim}D, {self.seeds} seed{'s' * (self.seeds != 1)}"

    def _spread(self, group, name):
        node = self.h5.get(f"{group}/{name.replace('.', '/')}")
        if not isinstance(node, h5py.Group) or "mean" not in node:
            return None
        mean = node["mean"][()].astype(float)
        std = node["std"][()].astype(float) if "std" in node else np.full_like(mean, np.nan)
        return mean, std

    def field(self, name, quiet=False):
        """(mean, std) per bin, or None with a note when absent or all NaN."""
        spread = self._spread("/fields", name)
        if spread is None or not np.isfinite(spread[0]).any():
            if not quiet:
                note(f"field {name} is {'absent' if spread is None else 'all NaN'}: skipped")
            return None
        return spread

    def global_value(self, name):
        spread = self._spread("/analysis/global", name)
        return None if spread is None else (float(spread[0]), float(spread[1]))

    def fit(self, law, quiet=False):
        node = self.h5.get(f"/analysis/fits/{law}")
        if node is None:
            if not quiet:
                note(f"fit {law} is absent: not drawn")
            return None
        value = node["value"][()]
        points = int(node.attrs.get("points", len(value)))
        if points < len(value) or not np.isfinite(value).all():  # fits.cpp: no fit was made
            if not quiet:
                note(f"fit {law} has {points} points for {len(value)} parameters: not drawn")
            return None
        return dict(names=text(node.attrs["parameters"]), value=value, error=node["error"][()],
                    converged=float(node.attrs.get("converged", 1.0)) > 0)

    def scene_restitution(self):
        """The e that the analysis used (run_analysis.cpp): e-bar [2.55] for frictional grains,
        from the scene a granjet run file stores; None when there is none."""
        scene = self.h5.get("/parameters/granjet/scene")
        if scene is None:
            return None
        try:
            ini = configparser.ConfigParser(interpolation=None, strict=False)
            ini.read_string(text(scene[()]))
            e = ini.getfloat("contact", "restitution")
            mu_p = ini.getfloat("contact", "friction", fallback=0.0)
        except (configparser.Error, ValueError) as err:
            note(f"stored scene has no usable contact.restitution ({err})")
            return None
        if mu_p == 0:
            return e, "stored scene"
        return effective_restitution_2_55(e, mu_p), f"$\\bar e$ [2.55], e={e:g}, $\\mu_p$={mu_p:g}"


# ---- Plot helpers -----------------------------------------------------------------------------
def errorbar(ax, x, y, xerr=None, yerr=None, positive=False, **style):
    """Draws the finite points (positive ones on log axes); missing spreads as no bar."""
    x, y = np.ravel(x), np.ravel(y)
    keep = np.isfinite(x) & np.isfinite(y) & ((y > 0) if positive else True)
    err = [None if e is None else np.nan_to_num(np.ravel(e)[keep]) for e in (xerr, yerr)]
    if keep.any():
        ax.errorbar(x[keep], y[keep], xerr=err[0], yerr=err[1], capsize=2, ls=style.pop("ls", ""),
                    **style)


def missing(ax, what):
    ax.text(0.5, 0.5, f"{what}\nnot available", ha="center", va="center", transform=ax.transAxes)


def draw_fit(ax, analysis, law, x, style):
    fit = analysis.fit(law)
    if fit is None:
        return
    model, label, positive = FIT_LAWS[law]
    x = np.ravel(x)
    x = x[np.isfinite(x) & ((x > 0) if positive else True)]
    if x.size == 0:
        return
    grid = np.linspace(x.min() if positive else min(0.0, x.min()), x.max(), 200)
    terms = [f"${tex(n)}$={v:.3g}±{e:.2g}" for n, v, e in
             zip(fit["names"], fit["value"], fit["error"])]
    label = f"{label}: {', '.join(terms)}" + ("" if fit["converged"] else " (not converged)")
    ax.plot(grid, model(grid, *fit["value"]), style, lw=1, label=label)


def per_layer(ax, analysis, x, y, **style):
    """One series per layer from (mean, std) pairs x, y of shape [layers][lateral]."""
    for k, layer in enumerate(analysis.layers):
        errorbar(ax, x[0][k], y[0][k], xerr=None if x[1] is None else x[1][k], yerr=y[1][k],
                 marker=MARKERS[k], label=layer if len(analysis.layers) > 1 else None, **style)


class Output:
    """Writes <dir>/<stem>_<key>.png and remembers the paths."""

    def __init__(self, directory, stem):
        self.directory, self.stem, self.written = directory, stem, []

    def save(self, fig, analysis, key, title):
        fig.suptitle(f"{analysis.title}: {title}")
        fig.tight_layout()
        path = os.path.join(self.directory, f"{self.stem}_{key}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        self.written.append(path)


# ---- The figures --------------------------------------------------------------------------
def plot_stress(a, out):
    """F5.3 (3D sigma_rr, zz, tt, rz vs r) and F6.4 (2D sigma_xx, yy, xy per layer)."""
    pairs = ("rr", "zz", "tt", "rz") if a.dim == 3 else ("xx", "yy", "xy")
    kind = "stress"
    if all(a.field(f"stress.{p}", quiet=True) is None for p in pairs):
        note("total stress absent or all NaN (no contact stress?): plotting the kinetic part")
        kind = "stress_kinetic"
    fields = {p: a.field(f"{kind}.{p}") for p in pairs}
    if all(f is None for f in fields.values()):
        note("stress figure skipped")
        return
    fig, axes = plt.subplots(1, len(a.layers), figsize=(5.5 * len(a.layers), 4.2), sharey=True,
                             squeeze=False)
    for k, ax in enumerate(axes[0]):
        for j, p in enumerate(pairs):
            if fields[p] is not None:
                sym = f"\\sigma_{{{tex(p[0])}{tex(p[1])}}}"
                errorbar(ax, a.x[k], fields[p][0][k], yerr=fields[p][1][k], marker=MARKERS[j],
                         ls="-", label=f"${sym}$")
        ax.axhline(0, color="0.7", lw=0.8)
        ax.set(xlabel=a.x_label, title=a.layers[k])
        ax.legend(fontsize=8)
    part = "" if kind == "stress" else " (kinetic part only)"
    axes[0][0].set_ylabel(f"stress{part} [m $u_0^2$/d$^{a.dim}$]")
    if a.dim == 3 and fields["rz"] is not None and fields["zz"] is not None:
        inner = int(np.argmin(np.abs(a.x[0] - 0.1)))  # F5.3: the ratio at r/R_tar = 0.1
        ratio = fields["rz"][0][0][inner] / fields["zz"][0][0][inner]
        axes[0][0].text(0.03, 0.03, f"$\\sigma_{{rz}}/\\sigma_{{zz}}$ at $r/R_{{tar}}$ = "
                        f"{a.x[0][inner]:.2g}: {ratio:.3g}", transform=axes[0][0].transAxes)
    out.save(fig, a, "stress", f"stress profiles ({'F5.3' if a.dim == 3 else 'F6.4'})")


def plot_profiles(a, out):
    """F5.4 (3D phi, T_g, v_r, sqrt(T_g/m) vs r) and F6.3 (2D T_g and phi per layer)."""
    t_g = a.field("T_g")
    panels = [("phi", r"$\phi$", a.field("phi")), ("T_g", "$T_g$ [m $u_0^2$]", t_g)]
    if a.dim == 3:
        sqrt_t = None if t_g is None else \
            (np.sqrt(t_g[0]), t_g[1] / (2 * np.sqrt(np.where(t_g[0] > 0, t_g[0], np.nan))))
        panels += [("v.r", "$v_r$ [$u_0$]", a.field("v.r")),
                   ("sqrt(T_g/m)", r"$\sqrt{T_g/m}$ [$u_0$]", sqrt_t)]
    if all(p[2] is None for p in panels):
        note("profile figure skipped")
        return
    rows = (len(panels) + 1) // 2
    fig, axes = plt.subplots(rows, 2, figsize=(10, 3.8 * rows), squeeze=False)
    for ax, (name, label, field) in zip(axes.ravel(), panels):
        ax.set(xlabel=a.x_label, ylabel=label)
        if field is None:
            missing(ax, name)
            continue
        per_layer(ax, a, (a.x, None), field, ls="-")
        if len(a.layers) > 1:
            ax.legend(fontsize=8)
    out.save(fig, a, "profiles", f"profiles ({'F5.4' if a.dim == 3 else 'F6.3'})")


def plot_eos(a, restitution, out):
    """F5.5 P/(n T_g) vs phi against [5.2]+[5.3]; F5.6 P_alpha/(n T_alpha) vs phi."""
    phi, total = a.field("phi"), a.field("P_over_nT")
    directional = {ax: a.field(f"P_over_nT_alpha.{ax}") for ax in a.axes}
    if phi is None or (total is None and all(d is None for d in directional.values())):
        note("equation-of-state figure skipped")
        return
    e, source = restitution
    grid = np.linspace(0.0, PHI_C - 0.01, 300)
    phi_max = max(PHI_C, np.nanmax(phi[0] + np.nan_to_num(phi[1])) + 0.02)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.3), sharey=True)
    if total is None:
        missing(left, "P/(n T_g)")
    else:
        per_layer(left, a, phi, total, positive=True)
    for j, (ax_name, field) in enumerate(directional.items()):
        if field is not None:
            errorbar(right, phi[0], field[0], xerr=phi[1], yerr=field[1], positive=True,
                     marker=MARKERS[j], label=f"$\\alpha = {tex(ax_name)}$")
    for ax in (left, right):
        if a.dim == 3:  # [5.2] is the hard-sphere law (model §6, kinetic theory in 3D)
            ax.plot(grid, pressure_ratio_5_2(grid, e), "k-", lw=1,
                    label=f"[5.2]+[5.3], e = {e:.3g} ({source})")
            ax.set(yscale="log", xlim=(0, phi_max))
        ax.set_xlabel(r"$\phi$")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
    left.set_ylabel(r"$P/(n T_g)$")
    right.set_ylabel(r"$P_\alpha/(n T_\alpha)$")
    right.yaxis.set_tick_params(labelleft=True)
    out.save(fig, a, "eos", "equation of state (F5.5, F5.6)")


def plot_scatter_fits(a, panels, out, key, title):
    """Panels (x field, y field, fit laws, x label, y label) of bin means over all layers."""
    data = [(a.field(x), a.field(y)) for x, y, *_ in panels]
    if all(x is None or y is None for x, y in data):
        note(f"{key} figure skipped")
        return
    fig, axes = plt.subplots(1, len(panels), figsize=(5.5 * len(panels), 4.3), squeeze=False)
    for ax, (x, y), (xn, yn, laws, xlabel, ylabel) in zip(axes[0], data, panels):
        ax.set(xlabel=xlabel, ylabel=ylabel)
        if x is None or y is None:
            missing(ax, f"{yn} vs {xn}")
            continue
        per_layer(ax, a, x, y)
        for law, style in zip(laws, ("k-", "k--")):
            draw_fit(ax, a, law, x[0], style)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    out.save(fig, a, key, title)


def flatness_label(a, name):
    """T5.1's flatness of component `name` under both readings of the study's scaling
    (run_analysis.cpp): each bin's own T_a ("bin") and one T_a for the region ("region")."""
    terms = []
    for scaling in ("bin", "region"):
        flat = a.global_value(f"flatness_{scaling}.{name}")
        if flat is not None:
            spread = f" ± {flat[1]:.2g}" if flat[1] >= 0 else ""  # one seed: NaN, no spread
            terms.append(f"{scaling} {flat[0]:.3g}{spread}")
    return f"flatness {', '.join(terms)}" if terms else None


def plot_vdf(a, out):
    """T5.1: scaled velocity distributions per component (each bin's own scaling), flatness
    under both scalings in the legend."""
    c = a.h5.get("/analysis/vdf/c")
    densities = {ax: a._spread("/analysis/vdf/density", ax) for ax in a.axes}
    values = np.concatenate([np.ravel(d[0]) for d in densities.values() if d is not None] or [[]])
    positive = values[np.isfinite(values) & (values > 0)]
    if c is None or positive.size == 0:
        note("velocity distributions absent or empty: figure skipped")
        return
    c = c[()]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for j, (name, density) in enumerate(densities.items()):
        if density is None:
            note(f"velocity distribution {name} absent")
            continue
        flatness = flatness_label(a, name)
        label = f"$c_{{{tex(name)}}}$" + (f", {flatness}" if flatness else "")
        errorbar(ax, c, density[0], yerr=density[1], positive=True, marker=MARKERS[j], ms=4,
                 label=label)
    grid = np.linspace(c.min(), c.max(), 300)
    ax.plot(grid, unit_gaussian(grid), "k-", lw=1, label="unit Gaussian (flatness 3)")
    ax.set(yscale="log", xlabel=r"scaled velocity $c = u_\alpha/\sqrt{\langle u_\alpha^2\rangle}$",
           ylabel="probability density")
    ax.set_ylim(max(1e-7, 0.3 * positive.min()), 1.0)
    ax.legend(fontsize=8)
    out.save(fig, a, "vdf", "scaled velocity distributions (T5.1)")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("file", help="HDF5 file holding /fields and /analysis")
    parser.add_argument("--out", help="directory of the PNGs (default: the file's directory)")
    parser.add_argument("--restitution", type=float,
                        help="e of the [5.2] curve (default: from the stored scene, else 0.75)")
    args = parser.parse_args(argv)
    try:
        a = Analysis(args.file)
    except NotAnalysisFile as err:
        print(f"plot_analysis: error: {err}", file=sys.stderr)
        return 2
    if args.restitution is not None:
        restitution = (args.restitution, "--restitution")
    else:
        restitution = a.scene_restitution() or (0.75, "default")
    directory = args.out or os.path.dirname(os.path.abspath(args.file))
    os.makedirs(directory, exist_ok=True)
    out = Output(directory, os.path.splitext(os.path.basename(args.file))[0])
    with a.h5:
        plot_stress(a, out)
        plot_profiles(a, out)
        plot_eos(a, restitution, out)
        if a.dim == 3:
            plot_scatter_fits(a, [("I", "mu_star", ["mu_linear"], "$I$", r"$\mu^*$")], out,
                              "friction", "friction law (F5.7)")
        else:
            plot_scatter_fits(a, [("I_s", "mu_star", ["6.9", "6.10"], "$I_s$", r"$\mu^*$")], out,
                              "friction", "friction law (F6.7)")
            plot_scatter_fits(a, [("I_T", "phi", ["6.2"], "$I_T$", r"$\phi$"),
                                  ("I_s", "phi", ["6.3"], "$I_s$", r"$\phi$")], out,
                              "packing", "packing fraction (F6.5)")
        plot_vdf(a, out)
    if not out.written:
        print(f"plot_analysis: error: nothing to draw: every field of '{args.file}' is absent or "
              "all NaN (did the analysis window ever start?)", file=sys.stderr)
        return 1
    print("\n".join(out.written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
