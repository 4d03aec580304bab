"""The 'Readings' section of docs/reproduction.md: the readings of the study's text that its
words leave open, each measured, beside the study's published numbers.

1. psi0 by the momentum balance [4.3] (group reading_psi0_momentum, analysis.psi0 = momentum)
   beside the departure-direction psi0 of the scattering group.
2. The stress without the contacts with target grains (reading_stress_own,
   analysis.stress_wall_contacts = exclude) beside rheology3d: F5.3, F5.7, T5.2, F5.5, F5.9.
3. The stress transformed after the ring average: the Cartesian ring average stress_xyz of
   rheology3d, whose sigma_xz a full ring cancels.
4. The 2D fits pooled over phi~0 = 0.3 ... 0.9 and both layers, as the study's Figs. 6.5 and 6.7
   (reading_pooled2d, both height origins).
5. Smaller conventions: F4.3's v2 normalisation, F6.3's phi_max, FE.1's printed parameters.
6. The packed 2D jet on the flat plate (reading_hc_*): the soft DEM against the event-driven
   backend and the exact free-streamline angle, one change at a time.

Every number is formed from the ensembles (error bar: std over seeds) like the rest of the
report; fits are granjet's own (granjet.fits) to the pooled ensemble means.
"""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import campaign_data as cd  # noqa: E402
import plot_analysis as pa  # noqa: E402
from campaign_data import NOT_MEASURED, Measured  # noqa: E402
from report_document import Table, format_number  # noqa: E402

from report_published import STUDY_A, STUDY_C, STUDY_FITS_2D, STUDY_RATIO, STUDY_SIGMA_Y, \
    STUDY_X  # noqa: E402  (the study's published values live there)

FE1_PRINTED = (796.0, 10.15)  # FE.1's printed k_n, eta_n for mu_p = 1.0, labelled t_c = 0.01
HEXAGONAL_PACKING_2D = math.pi / (2 * math.sqrt(3))  # 0.9069, F6.3's phi normalisation
INNER, RINGS_OUT = 0, (1, 2, 3, 4)  # ring indices: r/R_tar = 0.1; 0.3, 0.5, 0.7, 0.9


def section_readings(ctx):
    import reproduction_report as rr  # the report's shared helpers (it imports this module)
    s = ctx.section("Readings", "the study's text read other ways, each measured")
    groups = [g for g in ctx.campaign.file.groups if g.name.startswith("reading_")]
    rr.describe_groups(s, ctx.campaign, groups)
    psi0_momentum(ctx, s, rr)
    stress_own(ctx, s, rr)
    ring_frame(ctx, s, rr)
    pooled_2d(ctx, s, rr)
    conventions(ctx, s, rr)
    packed_plate(ctx, s, rr)
    return s


# ---- 1. psi0 from the momentum balance -----------------------------------------------------
def study_psi0_deg(x):
    import reproduction_report as rr
    return math.degrees(float(rr.scattering_fit_law(x, *STUDY_C)))


def psi0_momentum(ctx, s, rr):
    s.add("### psi0 from the momentum balance [4.3]\n\n"
          "The study relates psi0 to the wall force, 1 - cos psi0 = 4 A_cs/(pi D_jet^2) with "
          "A_cs = F_wall/j_in, and does not say how it measured psi0. `analysis.psi0 = momentum` "
          "measures exactly that ratio: cos psi0 = sum m v_out . e_in / (u0 sum m) over the "
          "scattered grains (their impulse from the target over their incident momentum). "
          "The departure reading (the default) is the polar angle of the grains' mean unit "
          "direction; the two agree for a perfect fluid (every grain leaving at u0).")
    departure = {key_of(p): p for p in rr.present(ctx.campaign.points("scattering"))}
    momentum = {key_of(p): p for p in rr.present(ctx.campaign.points("reading_psi0_momentum"))}
    if not momentum:
        s.add("**Not yet run**: group `reading_psi0_momentum`.")
        return
    table = Table("psi0_readings", ["e", "X", "psi0 departure [deg] (scattering)",
                                    "psi0 departure [deg] (these runs)", "psi0 momentum [deg]",
                                    "the study's curve [deg]"],
                  "Ensemble mean ± std over seeds; the study's curve is its fit law with its "
                  "C0, C1, C2 = 1.68, 0.563, 0.554 rad (the same for every e). The scattering "
                  "group's runs and these were made by granjet builds whose trajectories differ "
                  "in the last bits (grown by the flow's chaos), so the two departure columns "
                  "are two ensembles of the same jets.")
    by_e = {}
    for key in sorted(momentum):
        e, x = key
        m = rr.radians_to_degrees(rr.global_measured(momentum[key], "psi0_momentum"))
        d = rr.radians_to_degrees(rr.global_measured(departure[key], "psi0")) \
            if key in departure else NOT_MEASURED
        again = rr.radians_to_degrees(rr.global_measured(momentum[key], "psi0_departure"))
        table.add(e, x, d, again, m, study_psi0_deg(x))
        by_e.setdefault(e, []).append((x, m, d))
    s.add_table(table)
    spread = spread_over_e(by_e)
    s.add_table(spread)
    s.add_table(momentum_fits(by_e, rr, s))
    draw_psi0(ctx, s, by_e, rr)


def key_of(point):
    return (point.number("contact.restitution"),
            point.number("wall.diameter") / point.number("jet.diameter"))


def spread_over_e(by_e):
    """Per X: the largest minus the smallest ensemble mean over e, for both readings."""
    xs = sorted({x for rows in by_e.values() for x, _, _ in rows})
    table = Table("psi0_spread_over_e", ["X", "departure: max - min over e [deg]",
                                         "momentum: max - min over e [deg]"],
                  "The study: psi0 \"does not depend on the restitution coefficient\".")
    for x in xs:
        dep = [d.value for rows in by_e.values() for xx, _, d in rows if xx == x]
        mom = [m.value for rows in by_e.values() for xx, m, _ in rows if xx == x]
        table.add(x, np.ptp(dep) if dep else math.nan, np.ptp(mom) if mom else math.nan)
    return table


def momentum_fits(by_e, rr, s):
    fits = Table("psi0_momentum_fit", ["e", "C0 [rad]", "C1 [rad]", "C2 [rad]",
                                       *(f"psi0(X={x:g}) [deg]" for x in STUDY_X)],
                 "The interpolation law fitted to the momentum reading's ensemble means "
                 "(granjet.fits.scattering_angle, standard errors), and its values at the study's X. The "
                 "study: C = 1.68, 0.563, 0.554 rad; psi0 = " +
                 ", ".join(f"{study_psi0_deg(x):.1f}" for x in STUDY_X) + " deg.")
    for e, rows in sorted(by_e.items()):
        rows.sort(key=lambda r: r[0])
        xs = np.array([x for x, _, _ in rows])
        ys = np.radians([m.value for _, m, _ in rows])
        p, err = rr.fitted(pa.fits.scattering_angle, xs, ys)
        at = [math.degrees(float(rr.scattering_fit_law(x, *p))) for x in STUDY_X]
        fits.add(e, *(Measured(v, de) for v, de in zip(p, err)), *at)
        s.results.setdefault("psi0_momentum_fit", {})[f"e{e:g}"] = {
            "C": [Measured(v, de).json() for v, de in zip(p, err)],
            "psi0_deg_at_X": dict(zip((f"{x:g}" for x in STUDY_X),
                                      (cd.finite_or_none(a) for a in at)))}
    return fits


def draw_psi0(ctx, s, by_e, rr):
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    grid = np.linspace(0.01, 4.2, 200)
    ax.plot(grid, np.degrees(rr.scattering_fit_law(grid, *STUDY_C)), "k-", lw=1.2,
            label="the study's fit")
    for k, (e, rows) in enumerate(sorted(by_e.items())):
        rows.sort(key=lambda r: r[0])
        xs = [x for x, _, _ in rows]
        pa.errorbar(ax, xs, [m.value for _, m, _ in rows], yerr=[m.error for _, m, _ in rows],
                    marker="o", color=rr.COLOURS[k], ls="-", lw=0.8, ms=4,
                    label=f"momentum, e = {e:g}")
        pa.errorbar(ax, xs, [d.value for _, _, d in rows], yerr=[d.error for _, _, d in rows],
                    marker="s", mfc="none", color=rr.COLOURS[k], ls=":", lw=0.8, ms=4,
                    label=f"departure, e = {e:g}")
    ax.set(xlabel="$X = D_{tar}/D_{jet}$", ylabel=r"$\psi_0$ [deg]")
    ax.legend(fontsize=7)
    s.add_figure(ctx.figures.save(fig, "readings_psi0"), "psi0 against X under both readings, "
                 "with the study's interpolation curve")


# ---- 2. the stress without the target's contacts -------------------------------------------
def stress_points(ctx, group, rr):
    pts = [p for p in rr.present(ctx.campaign.points(group))
           if p.param("analysis.height_origin", "wall_centres") == "wall_centres"]
    return {(p.number("contact.friction"), p.number("jet.phi_tilde")): p for p in pts}


def stress_own(ctx, s, rr):
    s.add("### The stress without the contacts with target grains\n\n"
          "The study sums the contact stress \"over the particles located at r\"; whether the "
          "contacts between flowing grains and the target's grains count is not said. granjet "
          "counts them by default; `analysis.stress_wall_contacts = exclude` leaves them out of "
          "the contact stress and of everything derived from it (P, mu*, I, eta*, sigma_Y).")
    with_wall = stress_points(ctx, "rheology3d", rr)
    own = stress_points(ctx, "reading_stress_own", rr)
    if not own:
        s.add("**Not yet run**: group `reading_stress_own`.")
        return
    ratio = Table("ratio_rz_zz_readings", ["mu_p", "phi~0", "|sigma_rz/sigma_zz| with target "
                                           "contacts", "without", "the study"],
                  "At r/R_tar = 0.1 of the 5 d layer; per seed, then mean ± std over seeds.")
    for key in sorted(own):
        mu_p, phi_tilde = key
        study = STUDY_RATIO["frictional" if mu_p > 0 else "frictionless"] \
            if math.isclose(phi_tilde, 0.9) else math.nan
        both = [with_wall[key].over_seeds(rr.abs_inner_ratio) if key in with_wall
                else NOT_MEASURED, own[key].over_seeds(rr.abs_inner_ratio)]
        ratio.add(mu_p, phi_tilde, *both, study)
        if math.isclose(phi_tilde, 0.9):
            s.results.setdefault("ratio_rz_zz_r0.1", {})[friction(mu_p)] = {
                "with_target": both[0].json(), "without_target": both[1].json(), "study": study}
    s.add_table(ratio)
    s.add_table(raised_windows(ctx, rr, s))
    s.add_table(smoother_targets(ctx, rr, s))
    s.add_table(slope_a(ctx, rr, with_wall, own, s))
    s.add_table(yield_stress(rr, with_wall, own, s))
    s.add_table(theory_ratios(rr, with_wall, own, s))


TARGETS = (  # label, group of the ratio and its layers, group of a (5 d layer, 5 rings)
    ("touching grains (spacing 1 d), the default", "reading_stress_layers", 10, "rheology3d"),
    ("overlapping grains", "reading_smooth_target", 1, "reading_smooth_target"),
    ("flat plate", "sens_wall3d_plate", 1, "sens_wall3d_plate"),
)


def smoother_targets(ctx, rr, s):
    """F5.3's ratio and F5.7's a (phi~0 = 0.9) from the grain layer towards the flat plate."""
    table = Table("targets", ["target", "wall.spacing", "mu_p", "|sigma_rz/sigma_zz| with "
                              "target contacts", "without", "a (phi~0 = 0.9 alone)",
                              "the study's ratio"],
                  "phi~0 = 0.9, r/R_tar = 0.1, the 5 d layer from the target grains' centres "
                  "(for the touching layer rebuilt from its 0.5 d sublayers); per seed, then "
                  "mean ± std over seeds; a: granjet's fit mu* = a I over the five rings "
                  "(value ± std over seeds of each seed's fit); '–' where the runs predate the "
                  "stored target part.")
    for label, group, layers, a_group in TARGETS:
        fits = {key_of_target(p): p for p in rr.present(ctx.campaign.points(a_group))}
        for p in sorted(rr.present(ctx.campaign.points(group)), key=key_of_target):
            if not math.isclose(p.number("jet.phi_tilde"), 0.9):
                continue
            spacing, mu_p = key_of_target(p)
            cells = [p.over_seeds(window_ratio(0, own, layers)) for own in (False, True)]
            a = rr.fit_over_seeds(fits[(spacing, mu_p)], "mu_linear", "a") \
                if (spacing, mu_p) in fits else NOT_MEASURED
            shown = "–" if group == "sens_wall3d_plate" else spacing
            table.add(label, shown, mu_p, *cells, a, STUDY_RATIO[friction(mu_p)])
            s.results.setdefault("targets", {}).setdefault(group, {})[
                f"spacing{shown}_mu{mu_p:g}"] = {"with_target": cells[0].json(),
                                                 "without_target": cells[1].json(),
                                                 "a": a.json()}
    return table


def key_of_target(point):
    return (point.number("wall.spacing"), point.number("contact.friction"))


WINDOW_SUBLAYERS = 10  # a 5 d window of 0.5 d sublayers
WINDOW_STARTS = (0, 1, 2, 3, 4, 6)  # first sublayer: h0 = 0, 0.5, 1, 1.5, 2, 3 d


def raised_windows(ctx, rr, s):
    """|sigma_rz/sigma_zz| of the inner ring in 5 d windows rebuilt from 0.5 d sublayers,
    starting higher above the target, with and without the target's contacts."""
    table = Table("ratio_rz_zz_raised", ["mu_p", "window [d]", "|sigma_rz/sigma_zz| with target "
                                         "contacts", "without", "the study"],
                  "reading_stress_layers (phi~0 = 0.9): each window's stress is the mean of its "
                  "ten 0.5 d sublayers (exact for the contact part; the kinetic part is taken "
                  "about each sublayer's mean velocity), r/R_tar = 0.1; per seed, then mean ± "
                  "std over seeds. The 0-5 d window is the rheology3d layer.")
    for (mu_p, _), p in sorted(stress_points(ctx, "reading_stress_layers", rr).items()):
        for k0 in WINDOW_STARTS:
            window = f"{k0 / 2:g}-{k0 / 2 + 5:g}"
            cells = [p.over_seeds(window_ratio(k0, own)) for own in (False, True)]
            table.add(mu_p, window, *cells, STUDY_RATIO[friction(mu_p)])
            s.results.setdefault("ratio_rz_zz_raised", {}).setdefault(friction(mu_p), {})[
                window] = {"with_target": cells[0].json(), "without_target": cells[1].json()}
    return table


_WINDOW_METRICS = {}


def window_ratio(first, own, layers=WINDOW_SUBLAYERS):
    """A per-seed metric (one cached function object per window, as per_seed wants): the inner
    ring's |sigma_rz/sigma_zz| over `layers` layers from `first`, without the target's contacts
    when `own`."""
    key = (first, own, layers)
    if key not in _WINDOW_METRICS:
        names = ("stress.rz", "stress.zz") + (
            ("stress_contact_wall.rz", "stress_contact_wall.zz") if own else ())

        def metric(analysis):
            parts = []
            for name in names:
                field = analysis.field(name, quiet=True)
                if field is None or field[0].shape[0] < first + layers:
                    return math.nan  # e.g. a run stored before the target's part was
                parts.append(float(np.mean(field[0][first:first + layers, INNER])))
            rz, zz = parts[0], parts[1]
            if own:
                rz, zz = rz - parts[2], zz - parts[3]
            return abs(rz / zz)
        _WINDOW_METRICS[key] = metric
    return _WINDOW_METRICS[key]


def friction(mu_p):
    return "frictional" if mu_p > 0 else "frictionless"


def slope_a(ctx, rr, with_wall, own, s):
    table = Table("a_readings", ["mu_p", "reading", "a (mu* = a I)", "mu0 (mu* = mu0 + a' I)",
                                 "a'", "the study's a"],
                  "Pooled over every ring and phi~0 as section F5.7; error: std over seeds of "
                  "the same fit to each seed.")
    for mu_p in sorted({k[0] for k in own}):
        for label, points in (("with target contacts", with_wall), ("without", own)):
            pts = [p for k, p in sorted(points.items()) if k[0] == mu_p]
            if not pts:
                continue
            i, mu = rr.pooled_means(pts, "I", "mu_star")
            a, mu0, a_free = rr.mu_lines(i, mu)
            seeds = [rr.mu_lines(x, y) for x, y in rr.pooled_per_seed(pts, "I", "mu_star")]
            errors = [cd.spread_over_seeds(c).error for c in zip(*seeds)] if seeds \
                else [math.nan] * 3
            row = [Measured(a, errors[0]), Measured(mu0, errors[1]),
                   Measured(a_free, errors[2])]
            table.add(mu_p, label, *row, STUDY_A[friction(mu_p)])
            s.results.setdefault("a", {}).setdefault(friction(mu_p), {})[label] = {
                "a": row[0].json(), "mu0": row[1].json(), "a_free": row[2].json()}
    return table


def yield_stress(rr, with_wall, own, s):
    table = Table("sigma_Y_readings", ["mu_p", "reading", *(f"-sigma_Y x 1e3, r/R={r}" for r in
                                                            ("0.3", "0.5", "0.7", "0.9"))],
                  "phi~0 = 0.9; ensemble mean ± std over seeds. The study: " + ", ".join(
                      f"{v:g} ± {e:g}" for _, v, e in STUDY_SIGMA_Y) + ".")
    for mu_p in sorted({k[0] for k in own}):
        for label, points in (("with target contacts", with_wall), ("without", own)):
            p = points.get((mu_p, 0.9))
            field = None if p is None else rr.ensemble_field(p, "sigma_Y")
            if field is None:
                continue
            cells = [Measured(-1e3 * field[0][0][k], 1e3 * field[1][0][k]) for k in RINGS_OUT]
            table.add(mu_p, label, *cells)
            s.results.setdefault("minus_sigma_Y_1e3", {}).setdefault(friction(mu_p), {})[
                label] = [c.json() for c in cells]
    return table


def theory_ratios(rr, with_wall, own, s):
    """P/(n T_g) over [5.2] and eta* over [5.6], median over the rings of every phi~0."""
    table = Table("theory_readings", ["mu_p", "reading", "P/(n T_g) over [5.2]: median",
                                      "eta* over [5.6]: median"],
                  "Ensemble means of every ring and phi~0 over the kinetic theory at the ring's "
                  "phi (e-bar [2.55] for frictional grains); the study: P/(n T_g) on [5.2] for "
                  "phi < 0.5, eta* close to [5.6] for 0.2 < r/R_tar < 1.")
    for mu_p in sorted({k[0] for k in own}):
        for label, points in (("with target contacts", with_wall), ("without", own)):
            pts = [p for k, p in sorted(points.items()) if k[0] == mu_p]
            if not pts:
                continue
            eos, visc = [], []
            for p in pts:
                e = rr.restitution_for(p)
                phi, ratio = rr.ensemble_field(p, "phi"), rr.ensemble_field(p, "P_over_nT")
                eta = rr.ensemble_field(p, "eta_star")
                if phi is None or ratio is None or eta is None:
                    continue
                eos += list(np.ravel(ratio[0][0]) / np.ravel(rr.theory_5_2(phi[0][0], e)))
                visc += list(np.ravel(eta[0][0][1:]) / np.ravel(rr.theory_5_6(phi[0][0][1:], e)))
            table.add(mu_p, label, finite_median(eos), finite_median(visc))
            s.results.setdefault("theory_medians", {}).setdefault(friction(mu_p), {})[label] = {
                "eos": cd.finite_or_none(finite_median(eos)),
                "viscosity": cd.finite_or_none(finite_median(visc))}
    return table


def finite_median(values):
    x = np.array([v for v in values if math.isfinite(v)], dtype=float)
    return float(np.median(x)) if x.size else math.nan


# ---- 3. transform after the ring average ---------------------------------------------------
def ring_frame(ctx, s, rr):
    s.add("### The stress transformed after the ring average\n\n"
          "The study \"firstly calculate[s] sigma in Cartesian coordinates ... and transform[s] "
          "it\". Averaged over a whole ring first, the Cartesian sigma_xz is the ring average of "
          "sigma_rz cos(theta) - sigma_thetaz sin(theta), which is zero for an axisymmetric "
          "flow: nothing is left to rotate back, and mu* = -sigma_rz/P would vanish up to "
          "noise. The stored Cartesian ring averages (stress_xyz) show it:")
    table = Table("ring_frame", ["mu_p", "|sigma_rz/sigma_zz| (local frame)",
                                 "|sigma_xz/sigma_zz| (ring average)",
                                 "|sigma_yz/sigma_zz| (ring average)"],
                  "rheology3d, phi~0 = 0.9, r/R_tar = 0.1; ensemble means.")
    for (mu_p, phi_tilde), p in sorted(stress_points(ctx, "rheology3d", rr).items()):
        if not math.isclose(phi_tilde, 0.9):
            continue
        cells = [ratio_cell(rr, p, a, b) for a, b in (("stress.rz", "stress.zz"),
                                                      ("stress_xyz.xz", "stress_xyz.zz"),
                                                      ("stress_xyz.yz", "stress_xyz.zz"))]
        table.add(mu_p, *cells)
        s.results.setdefault("ring_frame", {})[friction(mu_p)] = cells
    s.add_table(table)


def ratio_cell(rr, point, numerator, denominator):
    top, bottom = rr.ensemble_field(point, numerator), rr.ensemble_field(point, denominator)
    if top is None or bottom is None:
        return math.nan
    return abs(float(top[0][0][INNER] / bottom[0][0][INNER]))


# ---- 4. the 2D fits pooled over phi~0 ------------------------------------------------------
# The disk area per grain centre of the 50:50 mix of diameters d and 0.8 d (scenes/jet2d.ini),
# for phi counted by centres: n times it, assuming the flow keeps the mix (no segregation).
MEAN_DISK_AREA = math.pi / 4 * (1.0 + 0.8 ** 2) / 2
VOLUME, CENTRES = "grain area inside the bin", "centres x mean disk area"
POOLED_LAWS = (  # law, x field, y field, y scale, granjet's fit, parameter names, phi counted as
    ("6.2", "I_T", "phi", 1.0, pa.fits.phi_of_i_t, ("phi_T", "a_T", "alpha_T"), VOLUME),
    ("6.3", "I_s", "phi", 1.0, pa.fits.phi_of_i_s, ("phi_s", "a_s", "alpha_s"), VOLUME),
    ("6.9", "I_s", "mu_star", 1.0, pa.fits.mu_saturating, ("mu_s", "mu_max", "I_0"), ""),
    ("6.10", "I_s", "mu_star", 1.0, pa.fits.mu_power, ("b", "beta"), ""),
    ("6.2", "I_T", "n", MEAN_DISK_AREA, pa.fits.phi_of_i_t, ("phi_T", "a_T", "alpha_T"),
     CENTRES),
    ("6.3", "I_s", "n", MEAN_DISK_AREA, pa.fits.phi_of_i_s, ("phi_s", "a_s", "alpha_s"),
     CENTRES),
)
STUDY_FITS_2D_BY_NAME = {name: (value, error) for name, _, value, error in STUDY_FITS_2D}


def pooled_2d(ctx, s, rr):
    s.add("### The 2D fits pooled over phi~0\n\n"
          "The study fits \"data of (a) and (b) layer for several phi~0\" (Figs. 6.5, 6.7); "
          "section F6.5 fits one phi~0 (0.9). Here every bin of both layers at phi~0 = 0.3, "
          "0.5, 0.7 and 0.9 enters one fit, under each height origin.")
    table = Table("pooled_2d", ["height origin", "phi counted as", "law", "parameter",
                                "pooled fit ± LM s.e.", "± std over seeds", "the study"],
                  "Levenberg-Marquardt fits to the ensemble means of every bin (finite, I > 0) "
                  "of the four phi~0; second error: std over seeds of the same pooled fit made "
                  "to each seed's bins. phi is granjet's (the grains' area inside the bin) or, "
                  "the next reading, the grain centres in the bin times the mean disk area of "
                  "the 50:50 mix (0.644 d^2, assuming no segregation).")
    found = False
    for group in ("reading_pooled2d", "reading_pooled2d_surface"):
        pts = rr.present(ctx.campaign.points(group))
        if not pts:
            continue
        found = True
        origin = pts[0].param("analysis.height_origin", "wall_centres")
        for law, x_name, y_name, scale, fit, names, counted in POOLED_LAWS:
            x, y = rr.pooled_means(pts, x_name, y_name)
            keep = x > 0
            p, err = rr.fitted(fit, x[keep], scale * y[keep])
            per_seed = []
            for sx, sy in rr.pooled_per_seed(pts, x_name, y_name):
                k = sx > 0
                per_seed.append(rr.fitted(fit, sx[k], scale * sy[k])[0])
            spread = [cd.spread_over_seeds(c).error for c in zip(*per_seed)] if per_seed \
                else [math.nan] * len(names)
            key = origin + ("_centres" if counted == CENTRES else "")
            for name, v, de, ds in zip(names, p, err, spread):
                study = STUDY_FITS_2D_BY_NAME[name]
                table.add(origin, counted or "–", law, name, Measured(v, de), Measured(v, ds),
                          Measured(*study))
                s.results.setdefault("pooled_2d", {}).setdefault(key, {})[name] = {
                    "value": Measured(v, ds).json(), "lm_error": cd.finite_or_none(de),
                    "study": list(study)}
    if not found:
        s.add("**Not yet run**: groups `reading_pooled2d`, `reading_pooled2d_surface`.")
        return
    s.add_table(table)


# ---- 5. smaller conventions ----------------------------------------------------------------
def conventions(ctx, s, rr):
    s.add("### Smaller conventions\n\n"
          "- F4.3: the study's [4.6] writes dN/dphi = v0 (1 + 2 v2 cos 2phi + ...) and plots "
          "v2 normalised by v0; if its v2 is the Fourier amplitude 2 <cos 2phi> rather than "
          "<cos 2phi>, every granjet v2 of section F4.3 doubles (below).\n"
          "- F6.3: the study normalises phi by 0.907 (hexagonal disks, pi/(2 sqrt 3)), not by "
          "the largest bin; the profiles are shown that way below.\n"
          "- FE.1: the printed mu_p = 1.0 parameters, under [3.4]-[3.5].")
    v2 = Table("v2_normalisations", ["aspect ratio", "<cos 2phi> (section F4.3)",
                                     "2 <cos 2phi>"], "e = 0.75; ensemble mean ± std.")
    for p in sorted(rr.present(ctx.points_for("F4.3")),
                    key=lambda q: q.number("jet.aspect_ratio")):
        m = rr.global_measured(p, "v2")
        v2.add(p.number("jet.aspect_ratio"), m, Measured(2 * m.value, 2 * m.error))
    s.add_table(v2)
    phi_table = Table("phi_over_0907", ["layer", *(f"y/R={x:+.1f}" for x in
                                                    (-0.9, -0.7, -0.5, -0.3, -0.1, 0.1, 0.3,
                                                     0.5, 0.7, 0.9))],
                      "[jet2d], phi~0 = 0.9: phi/0.907 per bin (ensemble mean).")
    jet2d = rr.present(ctx.campaign.points("jet2d"))
    field = rr.ensemble_field(jet2d[0], "phi") if jet2d else None
    if field is not None:
        for layer in range(field[0].shape[0]):
            phi_table.add(f"({chr(97 + layer)})", *(float(v) / HEXAGONAL_PACKING_2D
                                                    for v in field[0][layer]))
        s.add_table(phi_table)
    k_n, eta_n = FE1_PRINTED
    collision = pa.granjet.contact.collision(k_n, eta_n)  # [3.4]-[3.5] the other way
    t_c, e = collision["t_c"], collision["e"]
    s.results["fe1_printed"] = {"k_n": k_n, "eta_n": eta_n, "t_c": t_c, "e": e}
    s.add(f"FE.1's printed k_n = {k_n:g}, eta_n = {eta_n:g} give t_c = {format_number(t_c, 3)} "
          f"and e = {format_number(e, 3)} under [3.4]-[3.5], not the t_c = 0.01 of its label "
          "(which needs k_n = " + format_number(rr.contact_parameters_3_4_3_5(0.75, 0.01)[0], 4)
          + ", eta_n = " + format_number(rr.contact_parameters_3_4_3_5(0.75, 0.01)[1], 4) +
          " at e = 0.75). granjet's FE.1 runs use the label's (e, t_c); section FE.1 shows "
          "them, and the printed pair is the t_c = 0.081 one, between its t_c = 0.1 and 0.05.")


# ---- 6. the packed 2D jet on the plate: soft against hard grains ---------------------------
PACKED_CASES = (  # group, label
    ("reading_hc_packed", "event-driven (e(v_n), v0 = 0.1)"),
    ("reading_hc_packed_ed_v0", "event-driven, v0 = 0.01"),
    ("reading_hc_packed_dem", "soft DEM (e = 0.75, t_c = 0.1)"),
    ("reading_hc_packed_dem_elastic", "soft DEM, e = 0.99"),
    ("reading_hc_packed_dem_stiff", "soft DEM, t_c = 0.02"),
    ("reading_hc_packed_dem_verlet", "soft DEM, velocity Verlet"),
    ("reading_hc_packed_dem_gap", "soft DEM, lattice spacing 1.001 d"),
)


def packed_plate(ctx, s, rr):
    s.add("### The packed 2D jet on the plate: soft against hard grains\n\n"
          "The event-driven jet at the densest packing (area fraction 0.907) leaves at the exact "
          "free-streamline angle; the soft DEM's same jet leaves below it. Each case changes one "
          "thing; psi0 is the steady flow's (grains scattered in the analysis window) under "
          "both readings.")
    table = Table("packed_plate", ["case", "L/R", "exact [deg]", "departure [deg]",
                                   "departure - exact", "momentum [deg]"],
                  "One seed a point (full lattices leave nothing random).")
    found = False
    for group, label in PACKED_CASES:
        for p in sorted(rr.present(ctx.campaign.points(group)),
                        key=lambda q: q.number("wall.diameter")):
            found = True
            exact = math.degrees(rr.global_measured(p, "psi0_free_streamline").value)
            departure = math.degrees(rr.global_measured(p, "psi0_departure_window").value)
            momentum = math.degrees(rr.global_measured(p, "psi0_momentum_window").value)
            ratio = p.number("wall.diameter") / p.number("jet.diameter")
            table.add(label, ratio, exact, departure, departure - exact, momentum)
            s.results.setdefault("packed_plate", {}).setdefault(group, {})[f"{ratio:g}"] = {
                "exact": cd.finite_or_none(exact), "departure": cd.finite_or_none(departure),
                "momentum": cd.finite_or_none(momentum)}
    if not found:
        s.add("**Not yet run**: groups `reading_hc_packed*`.")
        return
    s.add_table(table)
