#!/usr/bin/python3
"""The reproduction report: every result of the study (model §7) from a campaign
directory, as docs/reproduction.md, its figures and results.json.

    /usr/bin/python3 scripts/reproduction_report.py CAMPAIGN_DIR [--out DOCS_DIR]
        [--campaign FILE] [--text DIR]

CAMPAIGN_DIR is what `granjet campaign campaigns/thesis.ini --out CAMPAIGN_DIR` wrote. Writes
DOCS_DIR/reproduction.md (default DOCS_DIR: the repository's docs/), the figures
DOCS_DIR/reproduction/<id>*.png and DOCS_DIR/reproduction/results.json (every number of the
report by result id, [value, error] pairs, NaN as null); PNGs in that directory that the report
does not draw are removed. The campaign file (default: the one the
manifest names) says which groups feed which id (`results = ...`); an id whose ensembles are
missing says so and the report is still written.

Hand-written prose lives in --text DIR (default docs/reproduction/text/): intro.md at the top,
<id>.md in each section and Sensitivity.md. Each is included verbatim; the part from its first
line starting with "Verdict:" (or "**Verdict") on goes below the generated numbers, so the
verdict follows the evidence. The closing list collects those verdict lines.

Error bars: the standard deviation over seeds (model §5 "error bars are the spread over them")
unless a table says otherwise; with one seed (a --quick campaign) there is none ("–").
Deterministic: the same campaign gives the same Markdown and JSON. Needs Debian's
python3-h5py, -matplotlib and -numpy (hence /usr/bin/python3); no scipy.
"""
import argparse
import functools
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.dont_write_bytecode = True  # no __pycache__ in scripts/
import campaign_data as cd  # noqa: E402
import plot_analysis as pa  # noqa: E402
from campaign_data import NOT_MEASURED, Measured  # noqa: E402
from report_causes import section_causes  # noqa: E402
from report_readings import section_readings  # noqa: E402
from report_document import Figures, Section, Table, format_measured, format_number, \
    read_text, verdict_line  # noqa: E402
from report_published import section_published  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INNER_RING = 0.1  # F5.3: sigma_rz/sigma_zz at r/R_tar = 0.1
# The study's contact time for each mu_p of the 2D friction study (model §2).
STUDY_CONTACT_TIME = {0.0: 0.1, 0.2: 0.1, 0.4: 0.05, 1.0: 0.01}
# Spec §2's table of (e, t_c) -> (k_n, eta_n), the values T4.1 reproduces.
STUDY_T4_1 = {(0.75, 0.1): (4.98e2, 2.88), (0.8, 0.1): (4.96e2, 2.23), (0.9, 0.1): (4.94e2, 1.05),
             (0.99, 0.1): (4.93e2, 0.101), (0.75, 0.05): (1.99e3, 5.75)}
# Where the study's own numbers are: the Published section sets each beside granjet's.
PUBLISHED = "the study's published numbers stand beside these in section Published"
QUALITATIVE = ("the study gives a figure and a sentence, not a number (section Published "
               "states the criterion it is held to)")
NOT_PUBLISHED = "the study's numbers for this are not among its published values"
# Sections that study the open choices and causes rather than one of the study's results: not in
# the closing list of verdicts.
ANALYSES = ("Sensitivity", "Causes", "Readings")
COLOURS = ("C0", "C1", "C2", "C3", "C4", "C5")


# ---- The study's formulas, from granjet's module (through plot_analysis) --------------------
def contact_parameters_3_4_3_5(e, t_c):
    """(k_n, eta_n) from [3.4] and [3.5] for two unit grains (soft_dem/contact_coefficients)."""
    c = pa.granjet.contact.coefficients(e, t_c)
    return c["k_n"], c["eta_n"]


viscosity_star_5_6 = pa.theory.viscosity_star  # [5.4]-[5.11], [5.6]
scattering_fit_law = pa.fits.scattering_angle_law  # F4.2's psi0(X) interpolation


def restitution_for(point):
    """e of the kinetic theory: e-bar [2.55] for frictional grains (as run_analysis.cpp)."""
    e, mu_p = point.number("contact.restitution"), point.number("contact.friction")
    return pa.effective_restitution_2_55(e, mu_p) if mu_p > 0 else e


# ---- Fits: granjet's own (analysis/fits.hpp, Eigen's Levenberg-Marquardt) ------------------
def fitted(fit, x, y):
    """(values, standard errors) of one of granjet.fits' fits, in the order of its parameters;
    points where x or y is not finite are left out by the fit itself."""
    pairs = list(fit(np.ravel(x), np.ravel(y))["parameters"].values())
    return np.array([v for v, _ in pairs]), np.array([e for _, e in pairs])


def ensemble_field(point, name):
    """(mean, std) [layers][lateral] of an ensemble field, or None."""
    a = point.ensemble()
    return None if a is None else a.field(name, quiet=True)


def lateral_positions(point):
    """Bin centres over R_tar [layers][lateral] of the point's ensemble."""
    return point.ensemble().x


def field_cell(point, name, layer, index):
    field = ensemble_field(point, name)
    if field is None:
        return NOT_MEASURED
    return Measured(float(field[0][layer][index]), float(field[1][layer][index]))


def global_measured(point, name, scale=1.0):
    a = point.ensemble()
    value = None if a is None else a.global_value(name)
    if value is None:
        return NOT_MEASURED
    return Measured(value[0] * scale, value[1] * scale)


def nearest_bin(analysis, target):
    return int(np.argmin(np.abs(analysis.x[0] - target)))


def inner_ratio(analysis):
    """F5.3: sigma_rz/sigma_zz in the ring nearest r/R_tar = 0.1 of the layer (one run)."""
    rz, zz = analysis.field("stress.rz", quiet=True), analysis.field("stress.zz", quiet=True)
    if rz is None or zz is None:
        return math.nan
    k = nearest_bin(analysis, INNER_RING)
    return float(rz[0][0][k] / zz[0][0][k])


def abs_inner_ratio(analysis):
    return abs(inner_ratio(analysis))


@functools.lru_cache(maxsize=None)
def fit_parameter(law, name):
    """A metric: one parameter of a stored fit (fits.cpp) of one run, NaN when not fitted."""
    def metric(analysis):
        fit = analysis.fit(law, quiet=True)
        if fit is None or name not in fit["names"]:
            return math.nan
        return float(fit["value"][fit["names"].index(name)])
    return metric


def ensemble_fit(point, law):
    """{parameter: Measured(value, Levenberg-Marquardt standard error)} of the fit that granjet
    made to the ensemble's mean fields, {} when none."""
    a = point.ensemble()
    fit = None if a is None else a.fit(law, quiet=True)
    if fit is None:
        return {}
    return {n: Measured(float(v), float(e)) for n, v, e in
            zip(fit["names"], fit["value"], fit["error"])}


def fit_over_seeds(point, law, name):
    """The fit to the ensemble mean, with the spread over seeds of the seeds' own fits as its
    error bar."""
    value = ensemble_fit(point, law).get(name, NOT_MEASURED).value
    return Measured(value, point.over_seeds(fit_parameter(law, name)).error)


def friction_name(point):
    mu_p = point.number("contact.friction")
    return "frictionless" if mu_p == 0 else f"frictional (mu_p = {mu_p:g})"


def friction_key(point):
    return "frictionless" if point.number("contact.friction") == 0 else "frictional"


def by_keys(points, **wanted):
    """Points whose scene keys (dots written as __) have the wanted numeric values."""
    def matches(p):
        return all(math.isclose(p.number(k.replace("__", ".")), v) for k, v in wanted.items())
    return [p for p in points if matches(p)]


def present(points):
    return [p for p in points if p.state() != "missing"]


def radians_to_degrees(m):
    return Measured(math.degrees(m.value), math.degrees(m.error))


# ---- What ran ------------------------------------------------------------------------------
def describe_groups(section, campaign, groups):
    """The campaign groups of a section, their assumptions (the group comments), and how many
    ensembles are there; True when any is."""
    lines, points = ["**Campaign groups** (campaign file comments; what is assumed):"], []
    for g in groups:
        pts = campaign.points(g.name)
        points += pts
        states = [p.state() for p in pts]
        seeds = len(pts[0].seeds) if pts else 0
        lines.append(f"- `[{g.name}]`, {g.backend}, {len(pts)} point(s) x {seeds} seed(s); "
                     f"{states.count('complete')} complete, {states.count('partial')} partial. "
                     f"{g.comment}".rstrip())
    if not groups:
        lines.append("- none in the campaign file.")
    section.add("\n".join(lines))
    found = sum(p.state() != "missing" for p in points)
    complete = sum(p.state() == "complete" for p in points)
    section.results["ensembles"] = {"planned": len(points), "present": found,
                                    "complete": complete}
    if found == 0:
        section.add(f"**Not yet run** ({found} of {len(points)} ensembles present).")
        section.results["status"] = "not yet run"
        return False
    if complete < len(points):
        section.add(f"**Incomplete**: {found} of {len(points)} ensembles present, {complete} "
                    "with every planned seed; what is present is shown.")
    section.results["status"] = "complete" if complete == len(points) else "incomplete"
    return True


def seeds_note(points):
    counts = sorted({p.seeds_combined() if p.analysed() else len(p.seeds_done())
                     for p in present(points)})
    spread = "one seed: no error bars" if counts == [1] else "error bars: std over seeds"
    return f"Seeds per ensemble: {', '.join(map(str, counts))} ({spread})."


# ---- Sections ------------------------------------------------------------------------------
def section_t4_1(ctx):
    s = ctx.section("T4.1", "contact parameters from (e, t_c), checked on a binary collision")
    points = ctx.points_for("T4.1")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("T4.1")):
        return s
    table = Table("binary", ["e", "t_c", "k_n [3.4]-[3.5]", "eta_n [3.5]", "k_n (study, T4.1)",
                             "eta_n (study, T4.1)", "measured e", "measured t_c"],
                  "Binary head-on collision, one run per row (deterministic: no error bar).")
    for p in sorted(points, key=lambda q: (q.number("contact.contact_time"),
                                           q.number("contact.restitution"))):
        e, t_c = p.number("contact.restitution"), p.number("contact.contact_time")
        k_n, eta_n = contact_parameters_3_4_3_5(e, t_c)
        spec = STUDY_T4_1.get((e, t_c), (None, None))
        measured = binary_measured(p)
        table.add(e, t_c, k_n, eta_n, spec[0], spec[1], measured.get("restitution"),
                  measured.get("contact_time"))
    s.add_table(table)
    worst = max((abs(r["measured e"] - r["e"]) / r["e"] for r in table.json()
                 if r["measured e"] is not None), default=math.nan)
    s.compare(f"largest relative difference of the measured e from the requested: "
              f"{format_number(worst, 2)}. The study's table (T4.1) lists no value for t_c = 0.01 "
              "(the study's printed one does not satisfy [3.4]-[3.5]).")
    return s


def binary_measured(point):
    """measured.{restitution, contact_time} of the point's first finished run."""
    for seed in point.seeds_done():
        with open(point.seed_path(seed, "json"), encoding="utf-8") as f:
            return json.load(f).get("measured", {})
    return {}


def section_f4_2(ctx):
    s = ctx.section("F4.2", "scattering angle psi0 against X = D_tar/D_jet")
    points = ctx.points_for("F4.2")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F4.2")):
        return s
    s.add(seeds_note(points))
    by_e = {}
    for p in present(points):
        x = p.number("wall.diameter") / p.number("jet.diameter")
        by_e.setdefault(p.number("contact.restitution"), []).append(
            (x, radians_to_degrees(global_measured(p, "psi0"))))
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    table = Table("psi0", ["e", "X", "psi0 [deg]"], "Ensemble mean ± std over seeds.")
    fits = Table("fit", ["e", "C0 [deg]", "C1 [deg]", "C2 [deg]"],
                 "Interpolation fit to the ensemble means (granjet.fits.scattering_angle); error: "
                 "standard error of the fit.")
    for k, (e, rows) in enumerate(sorted(by_e.items())):
        rows.sort()
        xs = np.array([x for x, _ in rows])
        ys = np.array([m.value for _, m in rows])
        for x, m in rows:
            table.add(e, x, m)
        pa.errorbar(ax, xs, ys, yerr=[m.error for _, m in rows], marker=pa.MARKERS[k],
                    color=COLOURS[k], label=f"e = {e:g}")
        p, err = fitted(pa.fits.scattering_angle, xs, ys)
        fits.add(e, *(Measured(v, de) for v, de in zip(p, err)))
        if np.isfinite(p).all():
            grid = np.linspace(0, xs.max() * 1.05, 200)
            ax.plot(grid, scattering_fit_law(grid, *p), "-", color=COLOURS[k], lw=1)
    ax.set(xlabel="$X = D_{tar}/D_{jet}$", ylabel=r"$\psi_0$ [deg]")
    ax.legend(fontsize=8)
    s.add_figure(ctx.figures.save(fig, "F4_2_psi0"), "psi0 against X with the interpolation "
                 "fit (lines)")
    s.add_table(table)
    s.add_table(fits)
    s.results["fit"] = {f"e{r['e']:g}": {k: v for k, v in r.items() if k != "e"}
                        for r in fits.json()}
    s.compare(f"the fitted C0, C1, C2 are above; {PUBLISHED} (and section Readings, psi0 by "
              "the momentum balance).")
    return s


def section_f4_3(ctx):
    s = ctx.section("F4.3", "anisotropy v2 of the scattered grains against the eccentricity")
    points = ctx.points_for("F4.3")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F4.3")):
        return s
    s.add(seeds_note(points))
    table = Table("v2", ["l", "epsilon", "v2", "psi0 [deg]"], "Ensemble mean ± std over seeds.")
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    rows = sorted(present(points), key=lambda q: q.number("jet.aspect_ratio"))
    for k, p in enumerate(rows):
        aspect = p.number("jet.aspect_ratio")
        eps = (aspect ** 2 - 1) / (aspect ** 2 + 1)
        v2 = global_measured(p, "v2")
        table.add(aspect, eps, v2, radians_to_degrees(global_measured(p, "psi0")))
        pa.errorbar(left, [eps], [v2.value], yerr=[v2.error], marker="o", color="C0")
        draw_azimuth(right, p, f"l = {aspect:g}", pa.MARKERS[k % len(pa.MARKERS)])
    left.axhline(0, color="0.7", lw=0.8)
    left.set(xlabel=r"$\epsilon = (l^2-1)/(l^2+1)$", ylabel="$v_2$")
    right.set(xlabel=r"$\phi$ [rad] from the short side", ylabel=r"$dN/d\phi$ / mean")
    right.legend(fontsize=7)
    s.add_figure(ctx.figures.save(fig, "F4_3_v2"), "v2 against epsilon (left) and the "
                 "azimuthal distributions (right)")
    s.add_table(table)
    s.results["v2"] = {f"l{r['l']:g}": r["v2"] for r in table.json()}
    s.compare(f"for v2(epsilon) {QUALITATIVE}.")
    return s


def draw_azimuth(ax, point, label, marker):
    a = point.ensemble()
    phi = a.h5.get("/analysis/azimuth/phi")
    spread = a._spread("/analysis/azimuth", "dN_dphi")
    if phi is None or spread is None:
        return
    pa.errorbar(ax, phi[()], spread[0], yerr=spread[1], marker=marker, ms=3, ls="-", lw=0.6,
                label=label)


# ---- Chapter 5: the 3D rheology ------------------------------------------------------------
def rheology_points(ctx, result_id):
    """The present 3D points of an id measured from the default height origin (the wall grains'
    centres; the other origin has its own rows where a section lists it), by mu_p, phi~0."""
    pts = [p for p in present(ctx.points_for(result_id)) if p.group.dimension() == 3 and
           p.param("analysis.height_origin", "wall_centres") == "wall_centres"]
    return sorted(pts, key=lambda p: (p.number("contact.friction"), p.number("jet.phi_tilde")))


def by_friction(points):
    """[(mu_p, colour, points of that mu_p)], frictionless first."""
    frictions = sorted({p.number("contact.friction") for p in points})
    return [(mu_p, COLOURS[k % len(COLOURS)], by_keys(points, contact__friction=mu_p))
            for k, mu_p in enumerate(frictions)]


def reference_3d(ctx, result_id, phi_tilde=0.9):
    """The points of an id at phi~0 (each friction), frictionless first."""
    return by_keys(rheology_points(ctx, result_id), jet__phi_tilde=phi_tilde)


def ring_columns(point):
    return [f"r/R={x:.1f}" for x in lateral_positions(point)[0]]


def section_f5_3(ctx):
    s = ctx.section("F5.3", "3D stress profiles; sigma_rz/sigma_zz at r/R_tar = 0.1")
    points = ctx.points_for("F5.3")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F5.3")):
        return s
    s.add(seeds_note(points))
    reference = reference_3d(ctx, "F5.3")
    if reference:
        fig, axes = plt.subplots(1, len(reference), figsize=(5 * len(reference), 4),
                                 sharey=True, squeeze=False)
        for ax, p in zip(axes[0], reference):
            draw_stress(ax, p, ("rr", "tt", "zz", "rz"))
            ax.set_title(f"{friction_name(p)}, " + r"$\tilde\phi_0$ = 0.9", fontsize=9)
        axes[0][0].set_ylabel("stress [m $u_0^2$/d$^3$]")
        s.add_figure(ctx.figures.save(fig, "F5_3_stress"), "stress components against "
                     "r/R_tar in the 5 d layer, phi~0 = 0.9 (ensemble mean ± std over seeds)")
        s.add_table(stress_table(reference, ("rr", "tt", "zz", "rz")))
    ratios = Table("ratio_rz_zz", ["group", "height origin", "mu_p", "phi~0",
                                   "sigma_rz/sigma_zz at r/R_tar = 0.1"],
                   "Per seed, then mean ± std over seeds.")
    headline = {}
    for p in sorted(present(points), key=lambda q: (q.group.name, q.number("contact.friction"),
                                                   q.number("jet.phi_tilde"))):
        ratio = p.over_seeds(inner_ratio)
        origin = p.param("analysis.height_origin", "wall_centres")
        ratios.add(p.group.name, origin, p.number("contact.friction"),
                   p.number("jet.phi_tilde"), ratio)
        if math.isclose(p.number("jet.phi_tilde"), 0.9):
            key = "ratio_rz_zz_r0.1" + ("" if origin == "wall_centres" else f"_{origin}")
            headline.setdefault(key, {})[friction_key(p)] = ratio
    s.add_table(ratios)
    s.results.update({key: {friction: m.json() for friction, m in by.items()}
                      for key, by in headline.items()})
    s.compare("granjet sigma_rz/sigma_zz at r/R_tar = 0.1, phi~0 = 0.9: " + "; ".join(
        f"{friction} {format_measured(m)}"
        for friction, m in sorted(headline.get("ratio_rz_zz_r0.1", {}).items())) +
        ". The study has frictional below frictionless; "
        f"{PUBLISHED}.")
    return s


def draw_stress(ax, point, pairs, layer=0, prefix="stress", style="-", label_suffix=""):
    x = lateral_positions(point)[layer]
    for j, pair in enumerate(pairs):
        field = ensemble_field(point, f"{prefix}.{pair}")
        if field is None:
            continue
        sym = f"\\sigma_{{{pa.tex(pair[0])}{pa.tex(pair[1])}}}"
        pa.errorbar(ax, x, field[0][layer], yerr=field[1][layer], marker=pa.MARKERS[j], ls=style,
                    color=COLOURS[j], ms=4, label=f"${sym}${label_suffix}")
    ax.axhline(0, color="0.7", lw=0.8)
    ax.set_xlabel(point.ensemble().x_label)
    ax.legend(fontsize=7)


def stress_table(points, pairs, layer=0):
    """Per bin of one layer: each point's stress components."""
    columns = ["r/R_tar" if points[0].ensemble().dim == 3 else "y/R_tar"]
    for p in points:
        columns += [f"sigma_{pair} ({friction_key(p)})" for pair in pairs]
    table = Table(f"stress_layer{layer}", columns, "Ensemble mean ± std over seeds, "
                  "m u0^2/d^D.")
    for k, x in enumerate(lateral_positions(points[0])[layer]):
        row = [float(x)]
        for p in points:
            row += [field_cell(p, f"stress.{pair}", layer, k) for pair in pairs]
        table.add(*row)
    return table


def section_f5_4(ctx):
    s = ctx.section("F5.4", "3D radial velocity v_r and sqrt(T_g/m) against r")
    points = ctx.points_for("F5.4")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F5.4")):
        return s
    s.add(seeds_note(points))
    rheology = rheology_points(ctx, "F5.4")
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    table = Table("profiles", ["mu_p", "phi~0", "r/R_tar", "v_r", "sqrt(T_g/m)"],
                  "Ensemble mean ± std over seeds (sqrt(T_g) by error propagation), units u0.")
    for p in rheology:
        v_r, t_g = ensemble_field(p, "v.r"), ensemble_field(p, "T_g")
        if v_r is None or t_g is None:
            continue
        x = lateral_positions(p)[0]
        root = np.sqrt(np.clip(t_g[0][0], 0, None))
        root_error = t_g[1][0] / (2 * np.where(root > 0, root, np.nan))
        colour = COLOURS[0 if p.number("contact.friction") == 0 else 1]
        marker = pa.MARKERS[int(round(p.number("jet.phi_tilde") * 10)) % len(pa.MARKERS)]
        label = f"$\\mu_p$ = {p.number('contact.friction'):g}, " \
                f"$\\tilde\\phi_0$ = {p.number('jet.phi_tilde'):g}"
        pa.errorbar(left, x, v_r[0][0], yerr=v_r[1][0], marker=marker, color=colour, ls="-",
                    lw=0.8, ms=4, label=label)
        pa.errorbar(right, x, root, yerr=root_error, marker=marker, color=colour, ls="-", lw=0.8,
                    ms=4)
        for k in range(len(x)):
            table.add(p.number("contact.friction"), p.number("jet.phi_tilde"), float(x[k]),
                      Measured(v_r[0][0][k], v_r[1][0][k]), Measured(root[k], root_error[k]))
    left.set(xlabel="$r/R_{tar}$", ylabel="$v_r$ [$u_0$]")
    right.set(xlabel="$r/R_{tar}$", ylabel=r"$\sqrt{T_g/m}$ [$u_0$]")
    left.legend(fontsize=6)
    s.add_figure(ctx.figures.save(fig, "F5_4_velocity"), "v_r and sqrt(T_g/m) against "
                 "r/R_tar (blue frictionless, orange frictional; marker: phi~0)")
    s.add_table(table)
    s.compare(f"{QUALITATIVE}.")
    return s


def kinetic_theory_rows(ctx, result_id, quantity, theory, label):
    """Compact per-ring tables: for each rheology point the measured quantity, phi and the
    theory at the measured phi."""
    rheology = rheology_points(ctx, result_id)
    if not rheology:
        return None
    table = Table(quantity.replace(".", "_"), ["mu_p", "phi~0", "row", *ring_columns(rheology[0])],
                  f"Per ring: phi, measured {label} (ensemble mean ± std over seeds) and "
                  f"{theory.__doc__.split(':')[0]} at the measured phi with e (frictionless) or "
                  "e-bar [2.55] (frictional).")
    for p in rheology:
        phi, field = ensemble_field(p, "phi"), ensemble_field(p, quantity)
        if phi is None or field is None:
            continue
        mu_p, phi_tilde = p.number("contact.friction"), p.number("jet.phi_tilde")
        table.add(mu_p, phi_tilde, "phi", *(Measured(m, e) for m, e in zip(phi[0][0],
                                                                          phi[1][0])))
        table.add(mu_p, phi_tilde, label, *(Measured(m, e) for m, e in zip(field[0][0],
                                                                          field[1][0])))
        table.add(mu_p, phi_tilde, "theory", *(float(v) for v in
                                               theory(phi[0][0], restitution_for(p))))
    return table


def theory_5_2(phi, e):
    """[5.2]+[5.3]: 1 + 2 phi (1+e) chi"""
    return pa.pressure_ratio_5_2(phi, e)


def theory_5_6(phi, e):
    """[5.6] (Garzo-Dufty eta*): the kinetic-theory eta*"""
    return viscosity_star_5_6(phi, e)


def draw_against_phi(ax, ctx, result_id, quantity, theory, positive=True):
    """Every rheology point's quantity against phi, one colour per friction, with the theory
    curve for e and e-bar."""
    grid = np.linspace(0.01, pa.PHI_C - 0.005, 300)
    for mu_p, colour, pts in by_friction(rheology_points(ctx, result_id)):
        for p in pts:
            phi, field = ensemble_field(p, "phi"), ensemble_field(p, quantity)
            if phi is None or field is None:
                continue
            marker = pa.MARKERS[int(round(p.number("jet.phi_tilde") * 10)) % len(pa.MARKERS)]
            pa.errorbar(ax, phi[0][0], field[0][0], xerr=phi[1][0], yerr=field[1][0],
                        positive=positive, marker=marker, color=colour, ms=4)
        if pts:
            e = restitution_for(pts[0])
            ax.plot(grid, theory(grid, e), "-", color=colour, lw=1,
                    label=f"$\\mu_p$ = {mu_p:g}: theory, e = {e:.3g}")
    ax.set(xlabel=r"$\phi$", yscale="log" if positive else "linear")


def kinetic_theory_section(ctx, rid, title, field, theory, label, ylabel, figure, caption):
    """A measured field against its kinetic-theory curve over phi, every ring and phi~0 (F5.5,
    F5.9): the figure, the table of measured/theory and its summary."""
    s = ctx.section(rid, title)
    if not describe_groups(s, ctx.campaign, ctx.groups_for(rid)):
        return s
    s.add(seeds_note(ctx.points_for(rid)))
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    draw_against_phi(ax, ctx, rid, field, theory)
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=7)
    s.add_figure(ctx.figures.save(fig, figure), caption)
    table = kinetic_theory_rows(ctx, rid, field, theory, label)
    if table:
        s.add_table(table)
        s.compare(deviation_summary(table, label))
    return s


def section_f5_5(ctx):
    return kinetic_theory_section(
        ctx, "F5.5", "P/(n T_g) against phi and the kinetic theory [5.2]", "P_over_nT",
        theory_5_2, "P/(n T_g)", r"$P/(n T_g)$", "F5_5_eos",
        "P/(n T_g) against phi, every ring and phi~0 (marker), blue frictionless, orange "
        "frictional; lines [5.2]+[5.3]")


def deviation_summary(table, label):
    """Median and range of measured/theory over every ring of every point."""
    ratios = []
    rows = table.json()
    for measured, theory in zip(rows[1::3], rows[2::3]):
        for column in measured:
            if column.startswith("r/R") and measured[column] and measured[column][0] is not None \
                    and theory[column]:
                ratios.append(measured[column][0] / theory[column])
    if not ratios:
        return f"no {label} to compare."
    return (f"measured {label} over kinetic theory, all rings and points: median "
            f"{format_number(float(np.median(ratios)), 3)}, range "
            f"{format_number(min(ratios), 3)} to {format_number(max(ratios), 3)}.")


def section_f5_6(ctx):
    s = ctx.section("F5.6", "directional P_alpha/(n T_alpha) against phi")
    points = ctx.points_for("F5.6")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F5.6")):
        return s
    s.add(seeds_note(points))
    axes_names = ("r", "t", "z")
    fig, axes = plt.subplots(1, 3, figsize=(12, 4), sharey=True)
    for ax, alpha in zip(axes, axes_names):
        draw_against_phi(ax, ctx, "F5.6", f"P_over_nT_alpha.{alpha}", theory_5_2)
        ax.set_title(f"$\\alpha = {pa.tex(alpha)}$", fontsize=9)
    axes[0].set_ylabel(r"$P_\alpha/(n T_\alpha)$")
    axes[0].legend(fontsize=6)
    s.add_figure(ctx.figures.save(fig, "F5_6_directional"), "P_alpha/(n T_alpha) against phi "
                 "for alpha = r, theta, z; lines: the directional [5.2]")
    for alpha in axes_names:
        table = kinetic_theory_rows(ctx, "F5.6", f"P_over_nT_alpha.{alpha}", theory_5_2,
                                    f"P_{alpha}/(n T_{alpha})")
        if table:
            s.add_table(table)
            s.compare(deviation_summary(table, f"P_{alpha}/(n T_{alpha})"))
    return s


def section_t5_1(ctx):
    s = ctx.section("T5.1", "flatness of the scaled velocity distributions")
    points = ctx.points_for("T5.1")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("T5.1")):
        return s
    s.add(seeds_note(points))
    chosen = sorted(by_keys(present(points), jet__phi_tilde=0.9),
                    key=lambda q: (q.group.name, q.number("contact.friction")))
    table = Table("flatness", ["group", "height origin", "mu_p", "scaling", "z", "r", "theta"],
                  "Flatness <c^4>/<c^2>^2 (Gaussian 3), ensemble mean ± std over seeds; "
                  "scaling 'bin': each bin's own T_a, 'region': one T_a for the region.")
    for p in chosen:
        for scaling in ("bin", "region"):
            cells = [global_measured(p, f"flatness_{scaling}.{a}") for a in ("z", "r", "t")]
            origin = p.param("analysis.height_origin", "wall_centres")
            table.add(p.group.name, origin, p.number("contact.friction"), scaling, *cells)
            if origin == "wall_centres":
                s.results.setdefault(f"flatness_{scaling}", {})[friction_key(p)] = {
                    a: c.json() for a, c in zip(("z", "r", "theta"), cells)}
    reference = reference_3d(ctx, "T5.1")
    if reference:
        fig, axes = plt.subplots(1, len(reference), figsize=(5.5 * len(reference), 4),
                                 sharey=True, squeeze=False)
        for ax, p in zip(axes[0], reference):
            draw_vdf(ax, p)
            ax.set_title(friction_name(p), fontsize=9)
        s.add_figure(ctx.figures.save(fig, "T5_1_vdf"), "scaled velocity distributions at "
                     "phi~0 = 0.9 (each bin's own scaling), unit Gaussian for reference")
    s.add_table(table)
    s.compare(f"{NOT_PUBLISHED}; the two readings of the scaling are both in "
              "the table.")
    return s


def draw_vdf(ax, point):
    a = point.ensemble()
    c = a.h5.get("/analysis/vdf/c")
    if c is None:
        return
    c = c[()]
    for j, axis in enumerate(a.axes):
        density = a._spread("/analysis/vdf/density", axis)
        if density is not None:
            pa.errorbar(ax, c, density[0], yerr=density[1], positive=True, marker=pa.MARKERS[j],
                        ms=3, label=f"$c_{{{pa.tex(axis)}}}$")
    ax.plot(c, pa.unit_gaussian(c), "k-", lw=1, label="unit Gaussian")
    ax.set(yscale="log", ylim=(1e-5, 1), xlabel="scaled velocity $c$", ylabel="density")
    ax.legend(fontsize=7)


def section_f5_7(ctx):
    s = ctx.section("F5.7", "effective friction mu* against I, fit mu* = a I")
    points = ctx.points_for("F5.7")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F5.7")):
        return s
    s.add(seeds_note(points))
    per_point = Table("a_per_point", ["group", "height origin", "mu_p", "phi~0",
                                      "a (fit to mean) ± LM s.e.",
                                      "a: fit value ± std over seeds"],
                      "granjet's stored fit mu* = a I over the 5 rings of one point.")
    for p in sorted(present(points), key=lambda q: (q.group.name, q.number("contact.friction"),
                                                   q.number("jet.phi_tilde"))):
        per_point.add(p.group.name, p.param("analysis.height_origin", "wall_centres"),
                      p.number("contact.friction"), p.number("jet.phi_tilde"),
                      ensemble_fit(p, "mu_linear").get("a", NOT_MEASURED),
                      fit_over_seeds(p, "mu_linear", "a"))
    pooled = Table("pooled", ["mu_p", "a (mu* = a I)", "mu0 (mu* = mu0 + a' I)", "a'"],
                   "Pooled over every ring and phi~0 (wall_centres): the fit to the ensemble "
                   "means, error the std over seeds of the same fit made to each seed's rings.")
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for mu_p, colour, pts in by_friction(rheology_points(ctx, "F5.7")):
        i, mu = pooled_means(pts, "I", "mu_star")
        for p in pts:
            f_i, f_mu = ensemble_field(p, "I"), ensemble_field(p, "mu_star")
            if f_i is not None and f_mu is not None:
                marker = pa.MARKERS[int(round(p.number("jet.phi_tilde") * 10)) % 10]
                pa.errorbar(ax, f_i[0][0], f_mu[0][0], xerr=f_i[1][0], yerr=f_mu[1][0],
                            marker=marker, color=colour, ms=4)
        a, mu0, a_free = mu_lines(i, mu)
        seed_fits = [mu_lines(x, y) for x, y in pooled_per_seed(pts, "I", "mu_star")]
        errors = [cd.spread_over_seeds(col).error for col in zip(*seed_fits)] if seed_fits \
            else [math.nan] * 3
        row = (Measured(a, errors[0]), Measured(mu0, errors[1]), Measured(a_free, errors[2]))
        pooled.add(mu_p, *row)
        s.results.setdefault("a", {})["frictionless" if mu_p == 0 else "frictional"] = \
            row[0].json()
        s.results.setdefault("free_intercept", {})[
            "frictionless" if mu_p == 0 else "frictional"] = {"mu0": row[1].json(),
                                                              "a": row[2].json()}
        grid = np.linspace(0, np.nanmax(i) if np.isfinite(i).any() else 1, 100)
        ax.plot(grid, a * grid, "-", color=colour, lw=1, label=f"$\\mu_p$ = {mu_p:g}: a I")
        ax.plot(grid, mu0 + a_free * grid, ":", color=colour, lw=1,
                label=f"$\\mu_p$ = {mu_p:g}: $\\mu_0$ + a' I")
    ax.set(xlabel="$I$", ylabel=r"$\mu^*$")
    ax.legend(fontsize=7)
    s.add_figure(ctx.figures.save(fig, "F5_7_friction"), "mu* against I, every ring and phi~0 "
                 "(marker); lines: pooled fits through the origin (solid) and with an "
                 "intercept (dotted)")
    s.add_table(pooled)
    s.add_table(per_point)
    s.compare(f"{PUBLISHED}; the study finds mu* through the origin, so the intercept "
              "mu0 should be zero within its error.")
    return s


def mu_lines(i, mu):
    """F5.7's a of mu* = a I, and mu_0, a of the free-intercept reading mu* = mu_0 + a I."""
    return (fitted(pa.fits.mu_linear, i, mu)[0][0], *fitted(pa.fits.mu_affine, i, mu)[0])


def pooled_means(points, x_name, y_name):
    """The ensemble means of two fields over every bin of every point, flattened."""
    xs, ys = [], []
    for p in points:
        fx, fy = ensemble_field(p, x_name), ensemble_field(p, y_name)
        if fx is not None and fy is not None:
            xs.append(np.ravel(fx[0]))
            ys.append(np.ravel(fy[0]))
    return (np.concatenate(xs), np.concatenate(ys)) if xs else (np.array([]), np.array([]))


def pooled_per_seed(points, x_name, y_name):
    """[(x, y)] per seed number: the two fields of that seed's run at every point, flattened."""
    metric = cd.seed_fields(x_name, y_name)
    by_seed = {}
    for p in points:
        for seed, value in p.per_seed(metric).items():
            if value is not None:
                by_seed.setdefault(seed, []).append(value)
    return [(np.concatenate([np.ravel(v[0]) for v in values]),
             np.concatenate([np.ravel(v[1]) for v in values]))
            for seed, values in sorted(by_seed.items())]


def section_t5_2(ctx):
    s = ctx.section("T5.2", "extrapolated yield stress sigma_Y at r/R_tar = 0.3 ... 0.9")
    points = ctx.points_for("T5.2")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("T5.2")):
        return s
    s.add(seeds_note(points))
    rheology = rheology_points(ctx, "T5.2")
    if not rheology:
        return s
    rings = [k for k, x in enumerate(lateral_positions(rheology[0])[0]) if x > 0.2]
    columns = [ring_columns(rheology[0])[k] for k in rings]
    table = Table("sigma_Y", ["mu_p", "phi~0", "row", *columns],
                  "sigma_Y = sigma_rz + eta_kin D_rz (model §6) and sigma_Y/P; ensemble mean ± "
                  "std over seeds.")
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for p in rheology:
        sigma_y, pressure = ensemble_field(p, "sigma_Y"), ensemble_field(p, "P")
        if sigma_y is None:
            continue
        mu_p, phi_tilde = p.number("contact.friction"), p.number("jet.phi_tilde")
        table.add(mu_p, phi_tilde, "sigma_Y", *(Measured(sigma_y[0][0][k], sigma_y[1][0][k])
                                                for k in rings))
        if pressure is not None:
            table.add(mu_p, phi_tilde, "sigma_Y/P",
                      *(float(sigma_y[0][0][k] / pressure[0][0][k]) for k in rings))
        x = lateral_positions(p)[0]
        colour = COLOURS[0 if mu_p == 0 else 1]
        pa.errorbar(ax, x[rings], sigma_y[0][0][rings], yerr=sigma_y[1][0][rings], ls="-",
                    lw=0.8, marker=pa.MARKERS[int(round(phi_tilde * 10)) % 10], color=colour,
                    ms=4, label=f"$\\mu_p$ = {mu_p:g}, $\\tilde\\phi_0$ = {phi_tilde:g}")
    ax.axhline(0, color="0.7", lw=0.8)
    ax.set(xlabel="$r/R_{tar}$", ylabel=r"$\sigma_Y$ [m $u_0^2$/d$^3$]")
    ax.legend(fontsize=6)
    s.add_figure(ctx.figures.save(fig, "T5_2_yield_stress"), "extrapolated yield stress "
                 "against r/R_tar")
    s.add_table(table)
    s.compare("the study finds sigma_Y close to zero; compare the sigma_Y/P rows with zero.")
    return s


def section_f5_9(ctx):
    return kinetic_theory_section(
        ctx, "F5.9", "dimensionless shear viscosity eta* against phi and [5.6]", "eta_star",
        theory_5_6, "eta*", r"$\eta^*$", "F5_9_viscosity",
        "eta* (eta over the dilute 5/(16 d^2) sqrt(m T_g/pi)) against phi; lines [5.6]; "
        "negative values are off the log axis")


# ---- Chapter 6: the 2D jet ------------------------------------------------------------------
def first_present(points):
    found = present(points)
    return found[0] if found else None


def profile_table(name, point, fields, caption):
    """Per lateral bin, per layer: ensemble mean ± std of each field."""
    x = lateral_positions(point)
    layers = range(x.shape[0])
    columns = ["y/R_tar"] + [f"{f} ({chr(97 + k)})" for k in layers for f in fields]
    table = Table(name, columns, caption)
    for j in range(x.shape[1]):
        table.add(float(x[0][j]), *(field_cell(point, f, k, j) for k in layers for f in fields))
    return table


def section_f6_3(ctx):
    s = ctx.section("F6.3", "2D T_g and phi/phi_max in layers (a), (b) against the 3D profile")
    points = ctx.points_for("F6.3")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F6.3")):
        return s
    s.add(seeds_note(points))
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for k, p in enumerate(sorted(present(points), key=lambda q: q.group.name)):
        draw_2d_profile(left, right, p, k)
    reference = by_keys(reference_3d(ctx, "F5.3"), contact__friction=0.0)
    if reference:
        draw_3d_profile(left, right, reference[0])
    left.set(xlabel="$y/R_{tar}$ (2D), $r/R_{tar}$ (3D)", ylabel="$T_g$ [m $u_0^2$]")
    right.set(xlabel="$y/R_{tar}$ (2D), $r/R_{tar}$ (3D)", ylabel=r"$\phi/\phi_{max}$")
    left.legend(fontsize=6)
    s.add_figure(ctx.figures.save(fig, "F6_3_profiles"), "T_g and phi/phi_max across the "
                 "target; phi_max is the profile's largest bin value (the model does not define "
                 "it)")
    for p in sorted(present(points), key=lambda q: q.group.name):
        s.add_table(profile_table(f"profiles_{p.group.name}", p, ("T_g", "phi", "v.x"),
                                  f"[{p.group.name}] ({p.param('analysis.height_origin')}): "
                                  "ensemble mean ± std over seeds per bin and layer."))
        s.results.setdefault("phi_max", {})[p.group.name] = phi_max(p)
    s.compare(f"{QUALITATIVE}; the dead zone shows as the low T_g and |v_x| of layer (a) "
              "near y = 0.")
    return s


def phi_max(point):
    field = ensemble_field(point, "phi")
    return None if field is None else cd.finite_or_none(float(np.nanmax(field[0])))


def draw_2d_profile(t_ax, phi_ax, point, index):
    t_g, phi = ensemble_field(point, "T_g"), ensemble_field(point, "phi")
    x = lateral_positions(point)
    top = phi_max(point) or math.nan
    for layer in range(x.shape[0]):
        style = dict(marker=pa.MARKERS[layer], ls="-" if index == 0 else "--", lw=0.8, ms=4,
                     color=COLOURS[2 * index + layer])
        label = f"[{point.group.name}] layer ({chr(97 + layer)})"
        if t_g is not None:
            pa.errorbar(t_ax, x[layer], t_g[0][layer], yerr=t_g[1][layer], label=label, **style)
        if phi is not None:
            pa.errorbar(phi_ax, x[layer], phi[0][layer] / top, yerr=phi[1][layer] / top, **style)


def draw_3d_profile(t_ax, phi_ax, point):
    t_g, phi = ensemble_field(point, "T_g"), ensemble_field(point, "phi")
    x = lateral_positions(point)[0]
    style = dict(marker="*", color="k", ls=":", lw=0.8, ms=5)
    if t_g is not None:
        pa.errorbar(t_ax, x, t_g[0][0], yerr=t_g[1][0],
                    label=f"3D [{point.group.name}] frictionless", **style)
    if phi is not None:
        top = float(np.nanmax(phi[0][0]))
        pa.errorbar(phi_ax, x, phi[0][0] / top, yerr=phi[1][0] / top, **style)


def section_f6_4(ctx):
    s = ctx.section("F6.4", "2D stress profiles in layers (a) and (b)")
    points = ctx.points_for("F6.4")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F6.4")):
        return s
    s.add(seeds_note(points))
    p = first_present(by_keys(points, contact__friction=0.0)) or first_present(points)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for layer, ax in enumerate(axes):
        draw_stress(ax, p, ("xx", "yy", "xy"), layer=layer)
        ax.set_title(f"[{p.group.name}] layer ({chr(97 + layer)})", fontsize=9)
    axes[0].set_ylabel("stress [m $u_0^2$/d$^2$]")
    s.add_figure(ctx.figures.save(fig, "F6_4_stress"), "2D stress components across the "
                 "target, layers (a) and (b)")
    s.add_table(profile_table("stress", p, ("stress.xx", "stress.yy", "stress.xy"),
                              f"[{p.group.name}]: ensemble mean ± std over seeds."))
    s.compare(NOT_PUBLISHED + ".")
    return s


FITS_2D = {"6.2": ("phi_T", "a_T", "alpha_T"), "6.3": ("phi_s", "a_s", "alpha_s"),
           "6.9": ("mu_s", "mu_max", "I_0"), "6.10": ("b", "beta")}


def fit_table(name, points, laws, caption_extra=""):
    """Per point: each parameter of the laws, the fit to the ensemble mean ± std over seeds of
    the seeds' own fits."""
    parameters = [(law, n) for law in laws for n in FITS_2D[law]]
    table = Table(name, ["group", "mu_p", "t_c", *(f"{n} [{law}]" for law, n in parameters)],
                  "granjet's Levenberg-Marquardt fit to the ensemble-mean fields; error: std "
                  "over seeds of the same fit to each seed's fields. " + caption_extra)
    for p in points:
        table.add(p.group.name, p.number("contact.friction"), p.number("contact.contact_time"),
                  *(fit_over_seeds(p, law, n) for law, n in parameters))
    return table


def fit_error_table(name, points, laws):
    """The same fits' own standard errors (Levenberg-Marquardt), for comparison."""
    parameters = [(law, n) for law in laws for n in FITS_2D[law]]
    table = Table(name, ["group", *(f"{n} [{law}]" for law, n in parameters)],
                  "The same fits to the ensemble means with their Levenberg-Marquardt standard "
                  "errors.")
    for p in points:
        fits = {law: ensemble_fit(p, law) for law in laws}
        table.add(p.group.name, *(fits[law].get(n, NOT_MEASURED) for law, n in parameters))
    return table


def draw_fit_panels(axes, point, panels, colour="C0", label_prefix=""):
    """Scatter of field pairs per layer with granjet's stored fit of each law."""
    a = point.ensemble()
    for ax, (x_name, y_name, laws, x_label, y_label) in zip(axes, panels):
        fx, fy = a.field(x_name, quiet=True), a.field(y_name, quiet=True)
        ax.set(xlabel=x_label, ylabel=y_label)
        if fx is None or fy is None:
            continue
        for layer in range(fx[0].shape[0]):
            pa.errorbar(ax, fx[0][layer], fy[0][layer], xerr=fx[1][layer], yerr=fy[1][layer],
                        marker=pa.MARKERS[layer], color=colour, ms=4,
                        label=f"{label_prefix}layer ({chr(97 + layer)})")
        for law, style in zip(laws, ("-", "--")):
            fit = a.fit(law, quiet=True)
            if fit is None:
                continue
            model, name, positive = pa.FIT_LAWS[law]
            x = np.ravel(fx[0])
            x = x[np.isfinite(x) & ((x > 0) if positive else True)]
            if x.size:
                grid = np.linspace(x.min(), x.max(), 200)
                ax.plot(grid, model(grid, *fit["value"]), style, color=colour, lw=1,
                        label=f"{label_prefix}{name}")
        ax.legend(fontsize=6)


def section_f6_5(ctx):
    s = ctx.section("F6.5", "packing fraction against I_T and I_s, fits [6.2] and [6.3]")
    points = sorted(present(ctx.points_for("F6.5")), key=lambda q: q.group.name)
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F6.5")):
        return s
    s.add(seeds_note(points))
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for k, p in enumerate(points):
        draw_fit_panels(axes, p, [("I_T", "phi", ["6.2"], "$I_T$", r"$\phi$"),
                                  ("I_s", "phi", ["6.3"], "$I_s$", r"$\phi$")],
                        colour=COLOURS[k], label_prefix=f"[{p.group.name}] ")
    s.add_figure(ctx.figures.save(fig, "F6_5_packing"), "phi against I_T and I_s with the "
                 "fits [6.2] and [6.3] (bidisperse, frictionless)")
    s.add_table(fit_table("fits", points, ("6.2", "6.3")))
    s.add_table(fit_error_table("fit_errors", points, ("6.2", "6.3")))
    reference = next((p for p in points if p.group.name == "jet2d"), points[0] if points else None)
    if reference:
        fitted = {name: fit_over_seeds(reference, "6.2" if name.endswith("_T") else "6.3", name)
                  for name in ("phi_T", "alpha_T", "phi_s", "alpha_s")}
        s.results.update({name: m.json() for name, m in fitted.items()})
        s.compare(f"[{reference.group.name}] phi_T {format_measured(fitted['phi_T'])}, phi_s "
                  f"{format_measured(fitted['phi_s'])}; {PUBLISHED}.")
    return s


def section_f6_7(ctx):
    s = ctx.section("F6.7", "mu* against I_s, fits [6.9] and [6.10]")
    points = sorted(present(ctx.points_for("F6.7")), key=lambda q: q.group.name)
    if not describe_groups(s, ctx.campaign, ctx.groups_for("F6.7")):
        return s
    s.add(seeds_note(points))
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for k, p in enumerate(points):
        draw_fit_panels([ax], p, [("I_s", "mu_star", ["6.9", "6.10"], "$I_s$", r"$\mu^*$")],
                        colour=COLOURS[k], label_prefix=f"[{p.group.name}] ")
    s.add_figure(ctx.figures.save(fig, "F6_7_friction"), "mu* against I_s with [6.9] (solid) "
                 "and [6.10], mu_s = 0 (dashed)")
    s.add_table(fit_table("fits", points, ("6.9", "6.10")))
    s.add_table(fit_error_table("fit_errors", points, ("6.9", "6.10")))
    if points:
        for law in ("6.9", "6.10"):
            for name in FITS_2D[law]:
                s.results[name] = fit_over_seeds(points[0], law, name).json()
    s.compare(PUBLISHED + ".")
    return s


def friction_study_points(ctx, result_id, reference_group):
    """The points of an id at the study's contact time for their mu_p (model §2), with the
    frictionless reference group's point first."""
    chosen = [p for p in ctx.points_for(result_id) + ctx.campaign.points(reference_group)
              if math.isclose(p.number("contact.contact_time"),
                              STUDY_CONTACT_TIME.get(p.number("contact.friction"), math.nan))]
    unique = {p.name: p for p in chosen}
    return sorted(unique.values(), key=lambda q: q.number("contact.friction"))


def draw_parameters_against_friction(fig_axes, points, names):
    for ax, (law, name) in zip(fig_axes, names):
        x = [p.number("contact.friction") for p in points]
        values = [fit_over_seeds(p, law, name) for p in points]
        pa.errorbar(ax, x, [v.value for v in values], yerr=[v.error for v in values],
                    marker="o", ls="-", lw=0.8)
        ax.set(xlabel=r"$\mu_p$", ylabel=f"${pa.tex(name)}$")


def section_friction_fits(ctx, result_id, title, reference_group, stem, dispersity):
    s = ctx.section(result_id, title)
    points = friction_study_points(ctx, result_id, reference_group)
    groups = ctx.groups_for(result_id)
    reference = ctx.campaign.file.group(reference_group)
    if reference is not None and reference not in groups:
        groups = [reference] + groups
    if not describe_groups(s, ctx.campaign, groups):
        return s, []
    contact_times = ", ".join(f"{t:g} at mu_p = {mu:g}" for mu, t in STUDY_CONTACT_TIME.items())
    s.add(f"Points: each mu_p at the study's contact time (model §2: t_c = {contact_times}); "
          f"[{reference_group}] is the mu_p = 0 reference ({dispersity}).")
    found = present(points)
    s.add(seeds_note(found))
    names = [("6.3", "phi_s"), ("6.2", "phi_T"), ("6.3", "alpha_s"), ("6.2", "alpha_T"),
             ("6.10", "beta")]
    fig, axes = plt.subplots(1, len(names), figsize=(14, 3.4))
    draw_parameters_against_friction(axes, found, names)
    s.add_figure(ctx.figures.save(fig, stem), "fit parameters against mu_p (fit to the "
                 "ensemble mean, error bar std over seeds)")
    s.add_table(fit_table("fits", found, ("6.2", "6.3", "6.9", "6.10")))
    for p in found:
        s.results.setdefault("by_mu_p", {})[f"{p.number('contact.friction'):g}"] = {
            n: fit_over_seeds(p, law, n).json() for law, n in names}
    s.compare(QUALITATIVE + ".")
    return s, found


def section_f6_11(ctx):
    s, _ = section_friction_fits(ctx, "F6.11-F6.14", "2D fits against mu_p (bidisperse)",
                                 "jet2d", "F6_11-F6_14_fits", "bidisperse")
    return s


def section_f6_16(ctx):
    s, found = section_friction_fits(ctx, "F6.16-F6.18", "monodisperse 2D jet: stress, fits and "
                                     "mu*(I_s) branches", "jet2d_mono", "F6_17_fits",
                                     "monodisperse")
    if not found:
        return s
    fig, axes = plt.subplots(2, len(found), figsize=(3.6 * len(found), 6), sharey="row",
                             squeeze=False)
    for j, p in enumerate(found):
        for layer in range(2):
            draw_stress(axes[layer][j], p, ("xx", "yy", "xy"), layer=layer)
            axes[layer][j].set_title(f"$\\mu_p$ = {p.number('contact.friction'):g}, layer "
                                     f"({chr(97 + layer)})", fontsize=8)
    s.add_figure(ctx.figures.save(fig, "F6_16_stress"), "F6.16: monodisperse stress profiles "
                 "per mu_p, layers (a) top and (b) bottom")
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for k, p in enumerate(found):
        draw_fit_panels([ax], p, [("I_s", "mu_star", [], "$I_s$", r"$\mu^*$")],
                        colour=COLOURS[k], label_prefix=f"$\\mu_p$ = "
                        f"{p.number('contact.friction'):g} ")
    s.add_figure(ctx.figures.save(fig, "F6_18_branches"), "F6.18: mu* against I_s per mu_p, "
                 "layers (a) and (b) by marker")
    for p in found:
        s.add_table(profile_table(f"stress_mu{p.number('contact.friction'):g}", p,
                                  ("stress.xx", "stress.yy", "stress.xy"),
                                  f"[{p.group.name}] mu_p = {p.number('contact.friction'):g}: "
                                  "ensemble mean ± std over seeds."))
    return s


# ---- FE.1: T_g(t) in layer (a) -------------------------------------------------------------
def burst_measures(series):
    """<T_g>, std, peak and CV of one T_g(t)."""
    t = series[np.isfinite(series)]
    if t.size < 2:
        return [math.nan] * 4
    return [float(t.mean()), float(t.std(ddof=1)), float(t.max()), float(t.std(ddof=1) / t.mean())]


def section_fe1(ctx):
    s = ctx.section("FE.1", "T_g(t) in layer (a), -dy < y < 0, mu_p = 1.0, several t_c")
    points = ctx.points_for("FE.1")
    if not describe_groups(s, ctx.campaign, ctx.groups_for("FE.1")):
        return s
    found = sorted(present(points), key=lambda q: -q.number("contact.contact_time"))
    s.add(seeds_note(found) + " T_g(t) from the stored frames (every output.interval) inside "
          "the analysis window; masses m = 1 as the study (model §2).")
    table = Table("bursts", ["t_c", "e", "<T_g>", "std of T_g(t)", "peak T_g",
                             "CV = std/<T_g>"],
                  "Per seed over the window, then mean ± std over seeds.")
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    for k, p in enumerate(found):
        per_seed, drawn = [], False
        for seed in p.seeds_done():
            path = p.seed_path(seed, "h5")
            times, series = cd.layer_a_series(path)
            per_seed.append(burst_measures(series))
            if not drawn and series.size:
                label = f"$t_c$ = {p.number('contact.contact_time'):g} (seed {seed})"
                top.plot(times, series, lw=0.8, color=COLOURS[k], label=label)
                bottom.plot(times, series / np.nanmean(series), lw=0.8, color=COLOURS[k])
                drawn = True
        cells = [cd.spread_over_seeds(col) for col in zip(*per_seed)] if per_seed else \
            [NOT_MEASURED] * 4
        table.add(p.number("contact.contact_time"), p.number("contact.restitution"), *cells)
        s.results.setdefault("by_t_c", {})[f"{p.number('contact.contact_time'):g}"] = {
            n: c.json() for n, c in zip(("mean", "std", "peak", "cv"), cells)}
    top.set_ylabel(r"$T_g$ [m $u_0^2$]")
    top.legend(fontsize=7)
    bottom.set(xlabel="$t$ [$d/u_0$]", ylabel=r"$T_g/\langle T_g\rangle$")
    s.add_figure(ctx.figures.save(fig, "FE_1_temperature"), "T_g(t) in layer (a), "
                 "-dy < y < 0, one seed per t_c (top) and relative to its mean (bottom)")
    s.add_table(table)
    s.compare("the study shows bursts for soft grains that die away as t_c falls; compare the "
              "std and peak rows across t_c.")
    return s


# ---- HC: hard cores -------------------------------------------------------------------------
HC_FIELDS = {"P": "$P$ [m $u_0^2$/d$^2$]", "T_g": "$T_g$ [m $u_0^2$]", "phi": r"$\phi$",
             "stress.xx": r"$\sigma_{xx}$ [m $u_0^2$/d$^2$]",
             "stress.yy": r"$\sigma_{yy}$ [m $u_0^2$/d$^2$]",
             "stress.xy": r"$\sigma_{xy}$ [m $u_0^2$/d$^2$]"}


SOFT_REFERENCE_2D = "jet2d"  # the soft-sphere 2D jet the hard-core jet is compared with


def section_hc(ctx):
    """The HC groups on a flat plate (wall.kind = plate) feed the psi0 benchmark, the others
    the jet compared with the frictionless [jet2d] point."""
    s = ctx.section("HC", "hard cores: the event-driven 2D jet, and the jet on a flat plate")
    groups = ctx.groups_for("HC")
    reference = ctx.campaign.file.group(SOFT_REFERENCE_2D)
    if reference is not None and reference not in groups:
        groups = groups + [reference]
    if not describe_groups(s, ctx.campaign, groups):
        return s
    points = ctx.points_for("HC")
    plate = [p for p in points if p.param("wall.kind") == "plate"]
    hard = first_present([p for p in points if p not in plate and
                          p.group.backend == "event_driven"])
    soft = first_present(by_keys(ctx.campaign.points(SOFT_REFERENCE_2D), contact__friction=0.0))
    if hard is not None and soft is not None:
        hc_jet_profiles(ctx, s, hard, soft)
    else:
        s.add(f"The jet comparison needs the event-driven jet and [{SOFT_REFERENCE_2D}]: not yet "
              "run.")
    hc_plate(ctx, s, plate)
    return s


def hc_jet_profiles(ctx, s, hard, soft):
    s.add(seeds_note([hard, soft]))
    for layer in range(lateral_positions(soft).shape[0]):
        fig, axes = plt.subplots(2, 3, figsize=(11, 6))
        for ax, (name, label) in zip(axes.ravel(), HC_FIELDS.items()):
            for k, (p, backend) in enumerate(((soft, "soft DEM"), (hard, "event-driven"))):
                field = ensemble_field(p, name)
                if field is not None:
                    pa.errorbar(ax, lateral_positions(p)[layer], field[0][layer],
                                yerr=field[1][layer], marker=pa.MARKERS[k], ls="-", lw=0.8,
                                ms=4, color=COLOURS[k], label=backend)
            ax.set(xlabel="$y/R_{tar}$", ylabel=label)
        axes[0][0].legend(fontsize=7)
        s.add_figure(ctx.figures.save(fig, f"HC_jet_layer_{chr(97 + layer)}"),
                     f"layer ({chr(97 + layer)}): soft DEM [jet2d] and event-driven "
                     "[hardcore2d] profiles")
    for layer in range(lateral_positions(soft).shape[0]):
        table = Table(f"jet_layer_{chr(97 + layer)}",
                      ["y/R_tar", *(f"{n} ({b})" for n in ("P", "T_g", "phi", "|v|")
                                    for b in ("DEM", "ED"))],
                      f"Layer ({chr(97 + layer)}): ensemble mean ± std over seeds.")
        for j, y in enumerate(lateral_positions(soft)[layer]):
            cells = []
            for name in ("P", "T_g", "phi"):
                cells += [field_cell(p, name, layer, j) for p in (soft, hard)]
            cells += [speed_cell(p, layer, j) for p in (soft, hard)]
            table.add(float(y), *cells)
        s.add_table(table)


def speed_cell(point, layer, index):
    """|v| of the bin's mean velocity (the dead zone's signature), error by propagation."""
    vx, vy = field_cell(point, "v.x", layer, index), field_cell(point, "v.y", layer, index)
    speed = math.hypot(vx.value, vy.value)
    if speed == 0 or not math.isfinite(speed):
        return Measured(speed, math.nan)
    return Measured(speed, math.hypot(vx.value * vx.error, vy.value * vy.error) / speed)


def jet_area_fraction(point):
    """The 2D jet's incoming area fraction: phi~0 times the triangular lattice's,
    (pi/4) <d^2> / ((sqrt 3 / 2) s^2), <d^2> over the 50:50 mixture of d and jet.small_diameter
    or 1 (mono). Nominal: the event-driven backend spreads a touching lattice (s = 1) to 1.001 d,
    0.2% less, so that both backends' runs of one scene share a row."""
    spacing = point.number("jet.spacing")
    small = point.number("jet.small_diameter")
    mean_square = 1.0 if point.param("jet.dispersity") == "mono" else 0.5 * (1.0 + small ** 2)
    lattice = (math.pi / 4.0) * mean_square / (math.sqrt(3.0) / 2.0 * spacing ** 2)
    return point.number("jet.phi_tilde") * lattice


def plate_jet(point):
    """Which jet a plate point throws, named by its grains, lattice and area fraction."""
    return (f"{point.param('jet.dispersity')}, s = {format_number(point.number('jet.spacing'), 3)}"
            f" d, phi~0 = {format_number(point.number('jet.phi_tilde'), 3)} (area fraction "
            f"{jet_area_fraction(point):.3f})")


def steady_psi0(point):
    """psi0 of the grains scattered within the analysis window (the steady flow the exact
    solution describes), or over the whole run for files written before psi0_window existed."""
    measured = global_measured(point, "psi0_window")
    if not math.isfinite(measured.value):
        measured = global_measured(point, "psi0")
    return radians_to_degrees(measured)


def hc_plate(ctx, s, plate):
    if not present(plate):
        s.add(f"**Flat plate**: not yet run (0 of {len(plate)} ensembles present).")
        return
    rows = {}
    for p in present(plate):
        ratio = p.number("wall.diameter") / p.number("jet.diameter")
        key = (plate_jet(p), round(ratio, 9))
        row = rows.setdefault(key, {"jet": key[0], "L_over_R": ratio, "psi0_exact_deg": None,
                                    "area_fraction": jet_area_fraction(p)})
        row[f"psi0_{p.group.backend}_deg"] = steady_psi0(p)
        exact = global_measured(p, "psi0_free_streamline")
        if math.isfinite(exact.value):
            row["psi0_exact_deg"] = math.degrees(exact.value)
    table = Table("plate", ["jet", "L/R", "psi0 exact [deg]", "psi0 event-driven [deg]",
                            "psi0 soft DEM [deg]"],
                  "Flat frictionless plate; psi0 of the grains scattered in the analysis window "
                  "(steady flow); ensemble mean ± std over seeds; exact: model §7b.")
    for key in sorted(rows):
        r = rows[key]
        table.add(r["jet"], r["L_over_R"], r["psi0_exact_deg"],
                  r.get("psi0_event_driven_deg", NOT_MEASURED),
                  r.get("psi0_soft_dem_deg", NOT_MEASURED))
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    exact = sorted({(r["L_over_R"], r["psi0_exact_deg"]) for r in rows.values()
                    if r["psi0_exact_deg"] is not None})
    if exact:
        ax.plot(*zip(*exact), "kx:", lw=0.8, label="free streamline (model §7b) at the runs' L/R")
    series = sorted({(r["jet"], b) for r in rows.values()
                     for b in ("event_driven", "soft_dem") if f"psi0_{b}_deg" in r})
    for k, (jet, backend) in enumerate(series):
        pts = [(r["L_over_R"], r[f"psi0_{backend}_deg"]) for _, r in sorted(rows.items())
               if r["jet"] == jet and f"psi0_{backend}_deg" in r]
        pa.errorbar(ax, [x for x, _ in pts], [m.value for _, m in pts],
                    yerr=[m.error for _, m in pts], marker=pa.MARKERS[k % len(pa.MARKERS)],
                    color=COLOURS[k % len(COLOURS)],
                    label=f"{backend.replace('_', ' ')} ({jet})")
    ax.set(xlabel="$L/R$", ylabel=r"$\psi_0$ [deg]")
    ax.legend(fontsize=7)
    s.add_figure(ctx.figures.save(fig, "HC_plate_psi0"), "psi0 against L/R on a flat "
                 "frictionless plate, both backends and both jets, and the exact free-streamline "
                 "angle")
    s.add_table(table)
    s.results["plate"] = [{"jet": row["jet"], "L_over_R": row["L/R"],
                           "psi0_exact_deg": row["psi0 exact [deg]"],
                           "psi0_event_driven_deg": row["psi0 event-driven [deg]"],
                           "psi0_soft_dem_deg": row["psi0 soft DEM [deg]"]}
                          for row in table.json()]
    if not exact:
        s.compare("the run files carry no psi0_free_streamline: no exact angle to compare with.")
        return
    hc_gap_against_density(ctx, s, rows)
    for jet in sorted({r["jet"] for r in rows.values()}):
        gaps = [abs(r["psi0_event_driven_deg"].value - r["psi0_exact_deg"])
                for r in rows.values() if r["jet"] == jet and r["psi0_exact_deg"] is not None
                and "psi0_event_driven_deg" in r
                and math.isfinite(r["psi0_event_driven_deg"].value)]
        s.compare(f"{jet}: largest |psi0(ED) - exact| "
                  f"{format_number(max(gaps, default=math.nan), 3)} deg (goal: within 3 deg).")


def hc_gap_against_density(ctx, s, rows):
    """psi0 minus the exact angle against the incoming jet's area fraction, at each L/R that has
    several jets: does the ideal fluid's angle come back as the jet becomes incompressible?"""
    by_ratio = {}
    for r in rows.values():
        if r["psi0_exact_deg"] is not None:
            by_ratio.setdefault(round(r["L_over_R"], 6), []).append(r)
    swept = {ratio: rs for ratio, rs in sorted(by_ratio.items()) if len(rs) >= 3}
    if not swept:
        return
    table = Table("plate_gap_by_density", ["L/R", "jet", "area fraction",
                                           "psi0 - exact, event-driven [deg]",
                                           "psi0 - exact, soft DEM [deg]"],
                  "psi0 minus the free-streamline angle against the jet's incoming area fraction "
                  "(one jet per row; error bars as in the plate table).")
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for k, (ratio, rs) in enumerate(swept.items()):
        for backend, style in (("event_driven", "-"), ("soft_dem", ":")):
            key = f"psi0_{backend}_deg"
            pts = sorted((r["area_fraction"], r[key].value - r["psi0_exact_deg"], r[key].error)
                         for r in rs if key in r)
            if pts:
                label = f"L/R = {ratio:g}, {backend.replace('_', ' ')}"
                pa.errorbar(ax, [p[0] for p in pts], [p[1] for p in pts],
                            yerr=[p[2] for p in pts], marker=pa.MARKERS[k], ls=style,
                            color=COLOURS[k], label=label)
        for r in sorted(rs, key=lambda q: q["area_fraction"]):
            table.add(ratio, r["jet"], r["area_fraction"],
                      *(Measured(r[f"psi0_{b}_deg"].value - r["psi0_exact_deg"],
                                 r[f"psi0_{b}_deg"].error) if f"psi0_{b}_deg" in r
                        else NOT_MEASURED for b in ("event_driven", "soft_dem")))
    ax.axhline(0, color="0.5", lw=0.8)
    ax.axhspan(-3, 3, color="0.9", label="goal: within 3 deg")
    ax.set(xlabel="incoming area fraction of the jet", ylabel=r"$\psi_0 - \psi_0^{exact}$ [deg]")
    ax.legend(fontsize=7)
    s.add_figure(ctx.figures.save(fig, "HC_plate_gap_density"), "psi0 minus the exact angle "
                 "against the jet's incoming area fraction")
    s.add_table(table)


# ---- Sensitivity ----------------------------------------------------------------------------
def metrics_for(dimension):
    """The contested numbers and how to get each from a point (Measured)."""
    if dimension == 3:
        return {"|sigma_rz/sigma_zz| r/R_tar=0.1": lambda p: p.over_seeds(abs_inner_ratio),
                "a (mu* = a I)": lambda p: fit_over_seeds(p, "mu_linear", "a"),
                "flatness z (bin)": lambda p: global_measured(p, "flatness_bin.z"),
                "flatness z (region)": lambda p: global_measured(p, "flatness_region.z")}
    return {"phi_T [6.2]": lambda p: fit_over_seeds(p, "6.2", "phi_T"),
            "phi_s [6.3]": lambda p: fit_over_seeds(p, "6.3", "phi_s")}


def metric_table(name, rows, metrics, caption=""):
    """rows: (label, Point); metrics: {column: Point -> Measured}. Missing points: '–'."""
    table = Table(name, ["case", "group/point", "seeds", *metrics], caption)
    for label, point in rows:
        done = point.state() != "missing"
        seeds = point.seeds_combined() if done else 0
        table.add(label, point.name, f"{seeds}/{len(point.seeds)}",
                  *(metric(point) if done else NOT_MEASURED for metric in metrics.values()))
    return table


# The groups the sens_* groups depart from (the study's target), under both height origins.
REFERENCE_3D = ("rheology3d", "rheology3d_surface")
REFERENCE_2D = ("jet2d", "jet2d_surface")


def case_label(point):
    """The point's physics overrides, 'key=value, ...' (output.* keys left out: they change
    what is stored, not what is simulated)."""
    return ", ".join(f"{k}={v}" for k, v in sorted(point.params.items())
                     if not k.startswith("output."))


def section_sensitivity(ctx):
    s = ctx.section("Sensitivity", "how the contested numbers move with the open choices")
    groups = [g for g in ctx.campaign.file.groups if g.name.startswith("sens_")]
    if not groups:
        s.add("No `sens_*` groups in the campaign file: not yet run.")
        s.results["status"] = "not yet run"
        return s
    describe_groups(s, ctx.campaign, groups)
    for dimension, reference in ((3, REFERENCE_3D), (2, REFERENCE_2D)):
        rows = [(f"{name}: {case_label(p)}".rstrip(": "), p)
                for name in reference for p in ctx.campaign.points(name)
                if math.isclose(p.number("jet.phi_tilde"), 0.9)]
        s.add_table(metric_table(f"reference_{dimension}d", rows, metrics_for(dimension),
                                 f"The references ({dimension}D) each sens_* table moves away "
                                 "from, under both height origins: value ± std over seeds."))
    for g in groups:
        points = ctx.campaign.points(g.name)
        metrics = metrics_for(g.dimension())
        rows = [(case_label(p) or p.label, p)
                for p in points]
        s.add_table(metric_table(g.name, rows, metrics,
                                 f"[{g.name}] ({g.dimension()}D): value ± std over seeds; "
                                 "'–' where not yet run."))
    return s


# ---- The document ---------------------------------------------------------------------------
SECTIONS = [section_t4_1, section_f4_2, section_f4_3, section_f5_3, section_f5_4, section_f5_5,
            section_f5_6, section_t5_1, section_f5_7, section_t5_2, section_f5_9, section_f6_3,
            section_f6_4, section_f6_5, section_f6_7, section_f6_11, section_f6_16, section_fe1,
            section_hc, section_sensitivity, section_causes, section_readings]


class Context:
    def __init__(self, campaign, figures, text_dir):
        self.campaign, self.figures, self.text_dir = campaign, figures, text_dir

    def section(self, result_id, title):
        return Section(result_id, title, self.text_dir)

    def points_for(self, result_id):
        return self.campaign.points_for(result_id)

    def groups_for(self, result_id):
        return self.campaign.file.groups_for(result_id)

    def describe(self, section, groups):
        return describe_groups(section, self.campaign, groups)


def commits(campaign):
    """{granjet version: runs} over the finished runs' files."""
    counts = {}
    for p in campaign.all_points():
        for seed in p.seeds:
            path = p.seed_path(seed, "h5")
            if os.path.isfile(path):
                version = cd.creator_version(path) or "unknown"
                counts[version] = counts.get(version, 0) + 1
    return dict(sorted(counts.items()))


def header(campaign):
    """The top block (machine, commits, wall time, coverage) and its numbers for the JSON."""
    wall, slots = cd.campaign_wall_seconds(campaign.manifest)
    model, cores = cd.cpu_model()
    hosts = sorted({i.get("host", "?") for i in campaign.manifest.get("invocations", [])})
    versions = commits(campaign)
    meta = {"campaign": campaign.manifest.get("campaign", os.path.basename(campaign.directory)),
            "campaign_file": os.path.relpath(campaign.file.path, ROOT), "quick": campaign.quick,
            "hosts": hosts, "cpu": model, "cores": cores, "versions": versions,
            "wall_seconds": wall, "run_seconds": slots}
    lines = [f"- Campaign `{meta['campaign']}` from `{meta['campaign_file']}`"
             + (" (**--quick**: one seed, shortened runs; not the study's numbers)"
                if campaign.quick else "") + ".",
             f"- Machine: host {', '.join(hosts) or 'not recorded'} (manifest); CPU {model}, "
             f"{cores} logical cores (read from the machine that wrote this report: the "
             "manifest does not record the CPU).",
             "- granjet: " + ("; ".join(f"`{v}` ({n} runs)" for v, n in versions.items())
                              or "no run files") + " (the creator version in each run file).",
             f"- Campaign wall time {format_duration(wall)} over "
             f"{len(campaign.manifest.get('invocations', []))} invocation(s); the runs' own "
             f"times add up to {format_duration(slots)}."]
    coverage = Table("coverage", ["group", "results", "backend", "points complete",
                                  "points partial", "points missing", "runs done / planned"])
    for g in campaign.file.groups:
        pts = campaign.points(g.name)
        states = [p.state() for p in pts]
        done = sum(len(p.seeds_done()) for p in pts)
        coverage.add(g.name, ", ".join(g.results), g.backend, states.count("complete"),
                     states.count("partial"), states.count("missing"),
                     f"{done} / {sum(len(p.seeds) for p in pts)}")
    meta["coverage"] = coverage.json()
    return "\n".join(lines) + "\n\n" + coverage.markdown(), meta


def format_duration(seconds):
    minutes = int(round(seconds / 60))
    return f"{minutes // 60}h{minutes % 60:02d}m" if minutes >= 60 else f"{seconds / 60:.1f} min"


def write_report(campaign, docs_dir, text_dir):
    figures = Figures(docs_dir)
    context = Context(campaign, figures, text_dir)
    top, meta = header(campaign)
    sections = [build(context) for build in SECTIONS]
    published = section_published(context, sections)  # reads the other sections' results
    intro, _ = read_text(text_dir, "intro")
    verdicts = "\n".join(f"- **{s.id}**: {verdict_line(s.after)}" for s in sections
                         if s.id not in ANALYSES)
    document = "\n\n".join(["# Reproduction of the study", intro, "## The campaign", top,
                            *(s.markdown() for s in sections), published.markdown(),
                            "## Verdicts", verdicts]) + "\n"
    with open(os.path.join(docs_dir, "reproduction.md"), "w", encoding="utf-8") as f:
        f.write(document)
    figures.remove_stale()
    results = {"meta": meta, **{s.id: s.results for s in (*sections, published)}}
    with open(os.path.join(figures.directory, "results.json"), "w", encoding="utf-8") as f:
        json.dump(results, f, indent=1, sort_keys=True, allow_nan=False)
        f.write("\n")
    return os.path.join(docs_dir, "reproduction.md")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("campaign_dir", help="the directory `granjet campaign --out` wrote")
    parser.add_argument("--out", default=os.path.join(ROOT, "docs"), help="DOCS_DIR")
    parser.add_argument("--campaign", help="campaign file (default: the manifest's)")
    parser.add_argument("--text", default=os.path.join(ROOT, "docs", "reproduction", "text"),
                        help="directory of the hand-written texts")
    args = parser.parse_args(argv)
    if not os.path.isdir(args.campaign_dir):
        print(f"reproduction_report: error: '{args.campaign_dir}' is not a directory",
              file=sys.stderr)
        return 2
    try:
        campaign = cd.Campaign(args.campaign_dir, args.campaign)
    except (FileNotFoundError, ValueError) as err:
        print(f"reproduction_report: error: {err}", file=sys.stderr)
        return 2
    try:
        print(write_report(campaign, args.out, args.text))
    finally:
        campaign.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
