"""The 'Causes' section of docs/reproduction.md: where the 3D inner ring's
shear stress sits and what carries it, and whether the 2D jet's slow region is a jammed solid.

Reads the `causes*` groups of the campaign file: jets whose measuring layers are cut into
sublayers of 1 d (analysis.layers, analysis.layer_height) so that the contact stress split of
field_accumulator.cpp (stress_contact_wall, stress_contact_normal), the contact density and
the fabric can be followed away from the target. Every derived number (the flowing grains'
part, the tangential part, the contacts per grain) is formed per seed and then averaged, with
the spread over seeds as its error bar, like the rest of the report.
"""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import campaign_data as cd  # noqa: E402
import plot_analysis as pa  # noqa: E402
from campaign_data import NOT_MEASURED, Measured  # noqa: E402
from report_document import Table, format_measured  # noqa: E402

INNER_RING = 0  # r/R_tar = 0.1, the ring of F5.3
ISOSTATIC_2D = 4.0  # contacts per grain of a jammed frictionless disk packing (2 D)

# The inner ring's sigma_rz, sublayer by sublayer, and its carriers: name -> (fields, formula).
# Each formula takes the per-seed arrays of its fields [layers][lateral].
SHEAR_PARTS = {
    "sigma_rz": (("stress.rz",), lambda s: s[0]),
    "kinetic": (("stress_kinetic.rz",), lambda s: s[0]),
    "contact flowing-flowing": (("stress_contact.rz", "stress_contact_wall.rz"),
                                lambda s: s[0] - s[1]),
    "contact with target": (("stress_contact_wall.rz",), lambda s: s[0]),
    "tangential (all contacts)": (("stress_contact.rz", "stress_contact_normal.rz"),
                                  lambda s: s[0] - s[1]),
    "kinetic theory -eta_kin D_rz": (("stress.rz", "sigma_Y"), lambda s: s[0] - s[1]),
}
STATE_3D = {
    "sigma_zz": (("stress.zz",), lambda s: s[0]),
    "phi": (("phi",), lambda s: s[0]),
    "T_g": (("T_g",), lambda s: s[0]),
    "v_r": (("v.r",), lambda s: s[0]),
    "D_rz": (("D",), lambda s: s[0]),
    "mu*": (("mu_star",), lambda s: s[0]),
    "I": (("I",), lambda s: s[0]),
    "contact density": (("contact_density",), lambda s: s[0]),
    "fabric rz": (("fabric.rz",), lambda s: s[0]),
}
STATE_2D = {
    "phi": (("phi",), lambda s: s[0]),
    # Each contact joins two grains: 2 n_c / n contacts per grain (target contacts included).
    "contacts per grain": (("contact_density", "n"), lambda s: 2.0 * s[0] / s[1]),
    "T_g": (("T_g",), lambda s: s[0]),
    "speed": (("v.x", "v.y"), lambda s: np.hypot(s[0], s[1])),
    "fabric xx - yy": (("fabric.xx", "fabric.yy"), lambda s: s[0] - s[1]),
}


def over_seeds(point, fields, formula):
    """Mean and std over seeds of formula(per-seed arrays), per bin: (mean, std) arrays, or
    None without finished seeds."""
    with np.errstate(divide="ignore", invalid="ignore"):  # empty bins give NaN, said as '–'
        values = [np.asarray(formula([np.asarray(a, dtype=float) for a in arrays]))
                  for arrays in point.per_seed(cd.seed_fields(*fields)).values()
                  if arrays is not None]
    if not values:
        return None
    stack = np.array(values)
    std = stack.std(axis=0, ddof=1) if len(values) > 1 else np.full(stack.shape[1:], np.nan)
    return stack.mean(axis=0), std


def cell(spread, layer, lateral):
    if spread is None:
        return NOT_MEASURED
    return Measured(float(spread[0][layer][lateral]), float(spread[1][layer][lateral]))


def sublayer_heights(point):
    """Centre heights of the sublayers, from the ensemble's mesh."""
    h = point.ensemble().h5["fields/mesh/height"][()]
    return 0.5 * (h[1:] + h[:-1])


def friction_label(point):
    mu_p = point.number("contact.friction")
    return "frictionless" if mu_p == 0 else f"mu_p = {mu_p:g}"


def causes_points(ctx, prefix):
    return [p for g in ctx.campaign.file.groups if g.name.startswith(prefix)
            and "causes" in g.results for p in ctx.campaign.points(g.name)
            if p.state() != "missing" and p.ensemble() is not None]


# ---- 3D: the inner ring's shear stress, sublayer by sublayer ---------------------------------
def kinetic_theory_ratio(point):
    """P/(n T_g) over [5.2]+[5.3] at the sublayer's phi, with e or, for frictional grains,
    e-bar [2.55] (as the F5.5 section)."""
    e, mu_p = point.number("contact.restitution"), point.number("contact.friction")
    e_kt = pa.effective_restitution_2_55(e, mu_p) if mu_p > 0 else e
    return over_seeds(point, ("P_over_nT", "phi"),
                      lambda s: s[0] / pa.pressure_ratio_5_2(s[1], e_kt))


def shear_table(point):
    parts = {name: over_seeds(point, *spec) for name, spec in {**SHEAR_PARTS, **STATE_3D}.items()}
    parts["P/(n T_g) over [5.2]"] = kinetic_theory_ratio(point)
    table = Table(f"{point.name}", ["h (d)", *parts],
                  f"[{point.group.name}] {friction_label(point)}, inner ring r/R_tar = 0.1, "
                  "sublayers of 1 d (heights from the analysis origin); mean ± std over seeds.")
    for layer, h in enumerate(sublayer_heights(point)):
        table.add(float(h), *(cell(parts[name], layer, INNER_RING) for name in parts))
    return table, parts


def layer_ratio(point):
    """|sigma_rz/sigma_zz| of the whole 5 d layer from its sublayers (equal volumes, so the
    layer's stress is their mean), per seed, then mean ± std."""
    def metric(analysis):
        rz, zz = analysis.field("stress.rz", quiet=True), analysis.field("stress.zz", quiet=True)
        if rz is None or zz is None:
            return math.nan
        return abs(float(np.mean(rz[0][:, INNER_RING]) / np.mean(zz[0][:, INNER_RING])))
    return point.over_seeds(metric)


def draw_shear_profiles(ax, parts, heights, title):
    for j, name in enumerate(SHEAR_PARTS):
        spread = parts[name]
        if spread is None:
            continue
        pa.errorbar(ax, spread[0][:, INNER_RING], heights, xerr=spread[1][:, INNER_RING],
                    marker=pa.MARKERS[j], ls="-" if j == 0 else "--", ms=4, label=name)
    ax.axvline(0, color="0.7", lw=0.8)
    ax.set_xlabel(r"$\sigma_{rz}$ part [m $u_0^2$/d$^3$], $r/R_{tar}$ = 0.1")
    ax.set_title(title, fontsize=9)


def section_3d(ctx, s):
    points = causes_points(ctx, "causes3d")
    if not points:
        return
    reference = [p for p in points if p.group.name == "causes3d"]
    if reference:
        fig, axes = plt.subplots(1, len(reference), figsize=(5.5 * len(reference), 4.2),
                                 sharey=True, squeeze=False)
        for ax, p in zip(axes[0], reference):
            table, parts = shear_table(p)
            s.add_table(table)
            draw_shear_profiles(ax, parts, sublayer_heights(p), friction_label(p))
        axes[0][0].set_ylabel("height above the wall grains' centres, h [d]")
        axes[0][0].legend(fontsize=7)
        s.add_figure(ctx.figures.save(fig, "causes_3d_shear_sublayers"),
                     "inner ring: sigma_rz and its carriers against height, reference target")
    variants = Table("targets_3d", ["group", "mu_p", "seeds", "|sigma_rz/sigma_zz| 5 d layer",
                                    "sigma_rz h<1", "sigma_rz 1<h<2", "sigma_rz 2<h<5 (mean)",
                                    "target share of sigma_rz h<1"],
                     "Inner ring of each target variant: the whole layer's ratio and sigma_rz "
                     "by height; mean ± std over seeds.")
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ratios = []
    for j, p in enumerate(sorted(points, key=lambda q: (q.group.name,
                                                         q.number("contact.friction")))):
        total = over_seeds(p, *SHEAR_PARTS["sigma_rz"])
        upper = over_seeds(p, ("stress.rz",), lambda a: np.mean(a[0][2:], axis=0, keepdims=True))
        share = over_seeds(p, ("stress_contact_wall.rz", "stress.rz"), lambda a: a[0] / a[1])
        ratio = layer_ratio(p)
        ratios.append(f"{p.group.name} {friction_label(p)} {format_measured(ratio)}")
        variants.add(p.group.name, p.number("contact.friction"), p.seeds_combined(),
                     ratio, cell(total, 0, INNER_RING), cell(total, 1, INNER_RING),
                     cell(upper, 0, INNER_RING), cell(share, 0, INNER_RING))
        if total is not None and p.number("contact.friction") > 0:
            pa.errorbar(ax, total[0][:, INNER_RING], sublayer_heights(p),
                        xerr=total[1][:, INNER_RING], marker=pa.MARKERS[j % 9], ms=4,
                        label=p.group.name.replace("causes3d", "reference").replace(
                            "reference_", ""))
    s.add_table(variants)
    s.results["targets_3d"] = variants.json()
    ax.axvline(0, color="0.7", lw=0.8)
    ax.set_xlabel(r"$\sigma_{rz}$ [m $u_0^2$/d$^3$], $r/R_{tar}$ = 0.1, $\mu_p$ = 0.2")
    ax.set_ylabel("h [d]")
    ax.legend(fontsize=7)
    s.add_figure(ctx.figures.save(fig, "causes_3d_targets"),
                 "inner ring sigma_rz against height for each target (frictional)")
    s.compare("3D inner ring, |sigma_rz/sigma_zz| of the 5 d layer by target: "
              + "; ".join(ratios))


# ---- 2D: is the slow region in front of the target jammed? -----------------------------------
def section_2d(ctx, s):
    points = causes_points(ctx, "causes2d")
    if not points:
        return
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    for j, p in enumerate(points):
        state = {name: over_seeds(p, *spec) for name, spec in STATE_2D.items()}
        centre = central_bins(p)
        table = Table(f"{p.name}", ["h (d)", *state],
                      f"[{p.group.name}] {p.label}: the two central bins (|y| < R_tar/5), "
                      "sublayers of 1 d; mean ± std over seeds (both bins averaged per seed).")
        central = {name: over_seeds(p, spec[0], lambda a, f=spec[1]: central_mean(f(a), centre))
                   for name, spec in STATE_2D.items()}
        heights = sublayer_heights(p)
        for layer, h in enumerate(heights):
            table.add(float(h), *(cell(central[name], layer, 0) for name in state))
        s.add_table(table)
        for ax, name in zip(axes, ("phi", "contacts per grain")):
            spread = central[name]
            if spread is not None:
                pa.errorbar(ax, spread[0][:, 0], heights, xerr=spread[1][:, 0],
                            marker=pa.MARKERS[j], ms=4, label=p.label)
    axes[0].set_xlabel(r"$\phi$, central bins")
    axes[1].set_xlabel("contacts per grain $2 n_c/n$, central bins")
    axes[1].axvline(ISOSTATIC_2D, color="0.5", ls=":", lw=1, label="isostatic (4)")
    axes[0].set_ylabel("height above the target grains' centres, h [d]")
    axes[1].legend(fontsize=7)
    s.add_figure(ctx.figures.save(fig, "causes_2d_slow_region"),
                 "2D jet: packing and contacts per grain in front of the target, by height")


def central_bins(point):
    """Lateral indices of the bins next to the axis (|y/R_tar| smallest)."""
    x = np.abs(point.ensemble().x[0])
    return np.flatnonzero(np.isclose(x, x.min()))


def central_mean(values, columns):
    """[layers][1]: the mean over the central bins of each layer (NaN if one is empty)."""
    return np.mean(np.asarray(values)[:, columns], axis=1, keepdims=True)


def section_causes(ctx):
    s = ctx.section("Causes", "the near-wall shear in 3D and the packing of the 2D jet")
    if not ctx.describe(s, ctx.groups_for("causes")):
        return s
    section_3d(ctx, s)
    section_2d(ctx, s)
    return s
