"""The 'Published' section of docs/reproduction.md: the study's published numbers beside
granjet's, one row per number and per reading of granjet's, each with a verdict.

The study's values are copied into ROWS below from its publication (the study's published
values: constants, never read from a file). granjet's values are read from the other sections'
`results` dicts, the same numbers results.json stores; nothing is recomputed here but the
comparison itself. A missing section, table or value gives '–' and the verdict 'not measured'.

To compare another reading of granjet's (another definition or option) with a published number,
add a Numeric or Qualitative entry to ROWS, next to the rows of that number: a Numeric row names
a function of the sections' results returning a Measured (`stored`, `table_cell` make them), a
Qualitative row a function returning a Finding (granjet's numbers as text, and whether they meet
the criterion its reading states). For example, psi0 by the momentum balance, once a section
stores it in a table `psi0_readings` with columns e, X and "psi0 momentum [deg]":

    Numeric("F4.2", "psi0 at X = 1 [rad] (the study's law and C0, C1, C2)", study_psi0(1.0),
            None, table_cell("Readings", "psi0_readings", "psi0 momentum [deg]",
                             {"e": 0.75, "X": 1.0}, then=degrees_to_radians),
            "psi0 by the momentum balance [4.3], e = 0.75")
"""
import math
import os
from typing import Callable, NamedTuple, Optional

from campaign_data import NOT_MEASURED, Measured, finite_or_none
from report_document import Table, format_number

PUBLISHED_ID = "Published"
TITLE = "The study's numbers beside granjet's"
TOLERANCE = 0.1  # "within 10%": |granjet/theory - 1| <= TOLERANCE (qualitative criteria)
MU_0_SMALL = 0.05  # "mu_0 ~ 0": a tenth of the study's mu_max (0.521)

# The study's published values (F4.2): C0, C1, C2 of its psi0(X) law, in radians.
STUDY_C = (1.68, 0.563, 0.554)
STUDY_X = (0.5, 1.0, 2.0, 4.0)
# The restitutions of granjet's F4.2 runs (campaigns/thesis.ini [scattering]); the study finds
# psi0 independent of e over 0.75 ... 0.99, so each is a reading of the same published number.
RESTITUTIONS = (0.75, 0.9, 0.99)
FRICTIONS = (("frictional", 0.2, "mu_p = 0.2"), ("frictionless", 0.0, "frictionless"))
ORIGINS_3D = (("rheology3d", "", "height origin: wall centres"),
              ("rheology3d_surface", "_wall_surface", "height origin: wall surface"))
ORIGINS_2D = (("jet2d", "height origin: wall centres"),
              ("jet2d_surface", "height origin: wall surface"))
PHI_J = 0.8425  # the study's phi_J by the conventional route (chapter 6)
# The study's abs(sigma_rz/sigma_zz) at r/R_tar = 0.1 (F5.3) and a of mu* = a I (F5.7).
STUDY_RATIO = {"frictional": 1.7e-2, "frictionless": 3.0e-2}
STUDY_A = {"frictional": 0.240, "frictionless": 0.223}
# T5.2: -sigma_Y x 1e3 at r/R_tar = 0.3, 0.5, 0.7, 0.9, (value, error).
STUDY_SIGMA_Y = ((0.3, 5.21, 2.7), (0.5, -0.540, 2.9), (0.7, -0.396, 1.2), (0.9, 0.243, 0.83))
# F6.5 and F6.7: the bidisperse frictionless fits, (parameter, law, value, error).
STUDY_FITS_2D = (("phi_T", "6.2", 0.858, 0.006), ("a_T", "6.2", 0.980, 0.1),
                 ("alpha_T", "6.2", 1.15, 0.1), ("phi_s", "6.3", 0.834, 0.001),
                 ("a_s", "6.3", 3.94, 0.5), ("alpha_s", "6.3", 1.36, 0.05),
                 ("mu_s", "6.9", 0.0153, 0.009), ("mu_max", "6.9", 0.521, 0.06),
                 ("I_0", "6.9", 0.0820, 0.02), ("b", "6.10", 1.18, 0.1),
                 ("beta", "6.10", 0.592, 0.03))

WITHIN_ERRORS, WITHIN_2X, NOT_MEASURED_VERDICT = "within error bars", "within 2x", "not measured"
AGREES, DIFFERS = "agrees", "differs"


# ---- Rows --------------------------------------------------------------------------------------
class Finding(NamedTuple):
    """granjet's numbers behind a qualitative verdict, and whether they meet the criterion
    (None: the report holds no number for it)."""
    text: str
    agrees: Optional[bool]


class Numeric(NamedTuple):
    """A number of the study. study: the value, or a function of no argument giving it; error:
    the study's error bar (None where it gives none); granjet(results) -> Measured."""
    id: str
    quantity: str
    study: object
    error: Optional[float]
    granjet: Callable
    reading: str


class Qualitative(NamedTuple):
    """A statement of the study. check(results) -> Finding by the criterion the reading states;
    None where no simple criterion on granjet's numbers exists (verdict: see section `see`)."""
    id: str
    quantity: str
    study: str
    check: Optional[Callable]
    reading: str
    see: str = ""


class Line(NamedTuple):
    """One evaluated row. study: the study's number or statement; granjet: Measured or text."""
    id: str
    quantity: str
    study: object
    study_error: Optional[float]
    granjet: object
    reading: str
    verdict: str
    numeric: bool

    def study_cell(self):
        """'value ± error' where the study prints an error bar."""
        if self.study_error is None:
            return self.study
        return Measured(self.study, self.study_error)

    def json(self):
        granjet = self.granjet
        if isinstance(granjet, Measured):
            granjet = granjet.json() if math.isfinite(granjet.value) else None
        study = finite_or_none(self.study) if isinstance(self.study, float) else self.study
        return {"id": self.id, "quantity": self.quantity, "study": study,
                "study_error": finite_or_none(self.study_error), "granjet": granjet,
                "reading": self.reading, "verdict": self.verdict}


# ---- Reading the sections' results ------------------------------------------------------------
def lookup(results, *path):
    """results[path[0]][path[1]]..., None where a step is missing."""
    node = results
    for key in path:
        if not isinstance(node, dict) or key not in node:
            return None
        node = node[key]
    return node


def as_measured(cell):
    """A stored [value, error] pair (None for NaN) or a bare number as Measured."""
    if isinstance(cell, (list, tuple)) and len(cell) == 2:
        value, error = cell
    elif isinstance(cell, (int, float)) and not isinstance(cell, bool):
        value, error = cell, None
    else:
        return NOT_MEASURED
    return Measured(math.nan if value is None else float(value),
                    math.nan if error is None else float(error))


def number(cell):
    return as_measured(cell).value


def same(cell, wanted):
    if isinstance(wanted, float) and isinstance(cell, (int, float)):
        return math.isclose(cell, wanted, abs_tol=1e-9)
    return cell == wanted


def table_rows(results, section, table, where=None):
    """The rows of a stored table (section results -> 'tables') whose columns match `where`."""
    rows = lookup(results, section, "tables", table)
    if not isinstance(rows, list):
        return []
    return [r for r in rows if isinstance(r, dict) and
            all(same(r.get(k), v) for k, v in (where or {}).items())]


def stored(section, *path, then=None):
    """A Numeric row's granjet: the [value, error] stored at results[section][path...]."""
    def granjet(results):
        m = as_measured(lookup(results, section, *path))
        return then(m) if then else m
    return granjet


def table_cell(section, table, column, where, then=None):
    """A Numeric row's granjet: one cell of the first table row matching `where`."""
    def granjet(results):
        rows = table_rows(results, section, table, where)
        m = as_measured(rows[0].get(column)) if rows else NOT_MEASURED
        return then(m) if then else m
    return granjet


def reading_list_cell(path, index):
    """A Numeric row's granjet: item `index` of a stored list of [value, error] pairs."""
    def granjet(results):
        cells = lookup(results, *path)
        ok = isinstance(cells, list) and index < len(cells)
        return as_measured(cells[index]) if ok else NOT_MEASURED
    return granjet


def magnitude(m):
    return Measured(abs(m.value), m.error)


def times(factor):
    return lambda m: Measured(m.value * factor, abs(m.error * factor))


def degrees_to_radians(m):
    return Measured(math.radians(m.value), math.radians(m.error))


def study_psi0(x):
    """The study's psi0 at X from its fit law with its C0, C1, C2 (rad). Imported when the
    section is built: reproduction_report imports this module."""
    def value():
        from reproduction_report import scattering_fit_law
        return float(scattering_fit_law(x, *STUDY_C))
    return value


def half_beta_alpha(results):
    """(1 - beta/2) alpha_s of [jet2d]: beta of [6.10] (F6.7), alpha_s of [6.3] (F6.5); errors
    combined as if independent."""
    beta = table_cell("F6.7", "fits", "beta [6.10]", {"group": "jet2d"})(results)
    alpha = table_cell("F6.5", "fits", "alpha_s [6.3]", {"group": "jet2d"})(results)
    factor = 1 - beta.value / 2
    return Measured(factor * alpha.value,
                    math.hypot(alpha.value / 2 * beta.error, factor * alpha.error))


# ---- Qualitative criteria ---------------------------------------------------------------------
def numbers_text(values, digits=3):
    return ", ".join(format_number(v, digits) for v in values)


def not_in_report(_results):
    return Finding("–", None)


def v2_trend(results):
    """F4.3: |v2| grows with eps at every step, not linearly, and stays below 0.16 at eps 0.6."""
    rows = sorted((r for r in table_rows(results, "F4.3", "v2")
                   if math.isfinite(number(r.get("epsilon")))), key=lambda r: r["epsilon"])
    eps = [r["epsilon"] for r in rows]
    v2 = [abs(number(r.get("v2"))) for r in rows]
    if len(v2) < 3 or not all(map(math.isfinite, v2)):
        return Finding("–", None)
    growing = all(b > a for a, b in zip(v2, v2[1:]))
    slopes = [v / e for v, e in zip(v2, eps) if e > 0]
    curved = len(slopes) >= 2 and abs(slopes[-1] / slopes[0] - 1) > TOLERANCE
    near = min(range(len(eps)), key=lambda k: abs(eps[k] - 0.615))
    text = (f"|v2| = {numbers_text(v2, 2)} at eps = {numbers_text(eps, 2)}; |v2|/eps "
            f"{numbers_text(slopes, 2)}")
    return Finding(text, growing and curved and v2[near] < 0.16)


def normal_stresses(friction):
    """F5.3: sigma_zz > sigma_thetatheta and sigma_zz > sigma_rr in the innermost ring."""
    def check(results):
        rows = [r for r in table_rows(results, "F5.3", "stress_layer0")
                if math.isfinite(number(r.get("r/R_tar")))]
        if not rows:
            return Finding("–", None)
        inner = min(rows, key=lambda r: r["r/R_tar"])
        zz, tt, rr = (number(inner.get(f"sigma_{c} ({friction})")) for c in ("zz", "tt", "rr"))
        if not all(map(math.isfinite, (zz, tt, rr))):
            return Finding("–", None)
        return Finding(f"zz {format_number(zz, 3)}, thetatheta {format_number(tt, 3)}, rr "
                       f"{format_number(rr, 3)} at r/R_tar = {format_number(inner['r/R_tar'], 2)}",
                       zz > tt and zz > rr)
    return check


def centre_extreme(column, want):
    """F5.4: at how many points the innermost ring holds the largest (want=max) sqrt(T_g/m) or
    the smallest (want=min) |v_r| of its profile; agrees when at every point."""
    def check(results):
        profiles = {}
        for r in table_rows(results, "F5.4", "profiles"):
            profiles.setdefault((r.get("mu_p"), r.get("phi~0")), []).append(r)
        hits, total = 0, 0
        for rows in profiles.values():
            values = [(number(r.get("r/R_tar")), abs(number(r.get(column)))) for r in rows]
            values = [v for v in values if all(map(math.isfinite, v))]
            if len(values) >= 2:
                total += 1
                hits += min(values)[1] == want(v for _, v in values)
        if total == 0:
            return Finding("–", None)
        return Finding(f"at {hits} of {total} points (mu_p, phi~0)", hits == total)
    return check


class Bin(NamedTuple):
    ring: float
    phi: float
    ratio: float  # measured over the kinetic theory


def theory_bins(results, section, table):
    """Every ring of every point of a kinetic-theory table (rows 'phi', the measured quantity,
    'theory' per point), with measured/theory."""
    points = {}
    for r in table_rows(results, section, table):
        kind = r.get("row")
        kind = kind if kind in ("phi", "theory") else "measured"
        points.setdefault((r.get("mu_p"), r.get("phi~0")), {})[kind] = r
    bins = []
    for rows in points.values():
        if len(rows) < 3:
            continue
        for column in rows["phi"]:
            if not column.startswith("r/R="):
                continue
            phi = number(rows["phi"].get(column))
            measured, theory = number(rows["measured"].get(column)), number(
                rows["theory"].get(column))
            if all(map(math.isfinite, (phi, measured, theory))) and theory != 0:
                bins.append(Bin(float(column[4:]), phi, measured / theory))
    return bins


def ratio_range(bins):
    ratios = [b.ratio for b in bins]
    return f"measured/theory {format_number(min(ratios), 3)} to {format_number(max(ratios), 3)}"


def within_theory(section, table, keep, description):
    """Every kept bin's measured/theory within TOLERANCE of 1."""
    def check(results):
        bins = [b for b in theory_bins(results, section, table) if keep(b)]
        if not bins:
            return Finding("–", None)
        close = sum(abs(b.ratio - 1) <= TOLERANCE for b in bins)
        return Finding(f"{close} of {len(bins)} {description} within 10%; {ratio_range(bins)}",
                       close == len(bins))
    return check


def above_theory(section, table, keep, description):
    """Every kept bin's measured/theory above 1."""
    def check(results):
        bins = [b for b in theory_bins(results, section, table) if keep(b)]
        if not bins:
            return Finding("–", None)
        above = sum(b.ratio > 1 for b in bins)
        return Finding(f"{above} of {len(bins)} {description} above; {ratio_range(bins)}",
                       above == len(bins))
    return check


def dense_deviation(results):
    """F5.5: the bins with 0.5 < phi < 0.6 off [5.2] by more than 10% are all in the inner
    ring, and there is at least one."""
    bins = [b for b in theory_bins(results, "F5.5", "P_over_nT") if 0.5 < b.phi < 0.6]
    if not bins:
        return Finding("no bin with 0.5 < phi < 0.6", None)
    off = [b for b in bins if abs(b.ratio - 1) > TOLERANCE]
    rings = sorted({b.ring for b in off})
    text = (f"{len(off)} of {len(bins)} bins with 0.5 < phi < 0.6 off by more than 10%"
            + (f", at r/R_tar = {numbers_text(rings, 2)}" if off else ""))
    return Finding(text, bool(off) and rings == [min(b.ring for b in bins)])


def profile_dip(values):
    """Whether the central bins (smallest |y|) sit below the next bin on each side: values are
    (y, T_g) sorted by y."""
    ys = [abs(y) for y, _ in values]
    central = [k for k, y in enumerate(ys) if math.isclose(y, min(ys))]
    left, right = min(central) - 1, max(central) + 1
    if left < 0 or right >= len(values):
        return None
    return max(values[k][1] for k in central) < min(values[left][1], values[right][1])


def dead_zone(group):
    """F6.3: T_g of layer (a) dips at the centre, that of layer (b) does not."""
    def check(results):
        rows = table_rows(results, "F6.3", f"profiles_{group}")
        dips = {}
        for layer in ("a", "b"):
            values = sorted(v for v in ((number(r.get("y/R_tar")),
                                         number(r.get(f"T_g ({layer})"))) for r in rows)
                            if all(map(math.isfinite, v)))
            dips[layer] = profile_dip(values) if len(values) >= 3 else None
        if None in dips.values():
            return Finding("–", None)
        said = {True: "dips", False: "no dip"}
        return Finding(f"layer (a): {said[dips['a']]}; layer (b): {said[dips['b']]}",
                       dips["a"] and not dips["b"])
    return check


def hotter_in_3d(group):
    """F6.3: the largest 3D T_g (F5.4, frictionless, phi~0 = 0.9) above the largest 2D T_g of
    either layer."""
    def check(results):
        rows = table_rows(results, "F5.4", "profiles", {"mu_p": 0.0, "phi~0": 0.9})
        t3 = [number(r.get("sqrt(T_g/m)")) ** 2 for r in rows]
        t2 = [number(r.get(f"T_g ({layer})")) for r in table_rows(results, "F6.3",
                                                                    f"profiles_{group}")
              for layer in ("a", "b")]
        t3, t2 = [t for t in t3 if math.isfinite(t)], [t for t in t2 if math.isfinite(t)]
        if not t3 or not t2:
            return Finding("–", None)
        return Finding(f"largest T_g 3D {format_number(max(t3), 3)}, 2D "
                       f"{format_number(max(t2), 3)}", max(t3) > max(t2))
    return check


def fits_by_friction(results, column):
    """{mu_p: Measured} of one fit parameter of the F6.11-F6.14 table, by increasing mu_p."""
    cells = {}
    for r in table_rows(results, "F6.11-F6.14", "fits"):
        mu_p = number(r.get("mu_p"))
        if math.isfinite(mu_p):
            cells[mu_p] = as_measured(r.get(column))
    return {mu_p: m for mu_p, m in sorted(cells.items()) if math.isfinite(m.value)}


def series_text(cells):
    return "; ".join(f"{format_number(mu_p, 2)}: {format_number(m.value, 3)} ± "
                     f"{format_number(m.error, 2)}" for mu_p, m in cells.items())


def slight_decrease(column):
    """F6.12: falls at every step of mu_p, by less than 10% of its mu_p = 0 value in all."""
    def check(results):
        cells = fits_by_friction(results, column)
        values = [m.value for m in cells.values()]
        if len(values) < 2:
            return Finding("–", None)
        falling = all(b < a for a, b in zip(values, values[1:]))
        slight = (values[0] - values[-1]) <= TOLERANCE * abs(values[0])
        return Finding(f"by mu_p {series_text(cells)}", falling and slight)
    return check


def insensitive(column):
    """F6.14: every mu_p's value within the error bars of the mu_p = 0 one (the numeric rule);
    values whose error bar exceeds their size are undetermined and left out."""
    def check(results):
        cells = fits_by_friction(results, column)
        determined = {mu_p: m for mu_p, m in cells.items() if not abs(m.error) > abs(m.value)}
        text = f"by mu_p {series_text(cells)}"
        if len(determined) < 2 or 0.0 not in determined:
            return Finding(text + " (fewer than two determined)", None)
        reference = determined[0.0]
        return Finding(text, all(within_error_bars(m, reference.value, reference.error)
                                 for m in determined.values()))
    return check


def small_at_every_friction(column, bound):
    """F6.14: |mu_0| below `bound` at every mu_p."""
    def check(results):
        cells = fits_by_friction(results, column)
        if not cells:
            return Finding("–", None)
        return Finding(f"by mu_p {series_text(cells)}",
                       all(abs(m.value) < bound for m in cells.values()))
    return check


def bursts_fall(column):
    """FE.1: the measure at the smallest t_c below that at the largest, beyond the combined
    error bars (the study's e = 0.75 rows)."""
    def check(results):
        rows = {number(r.get("t_c")): as_measured(r.get(column))
                for r in table_rows(results, "FE.1", "bursts", {"e": 0.75})}
        rows = {t: m for t, m in sorted(rows.items()) if math.isfinite(t)
                and math.isfinite(m.value)}
        if len(rows) < 2:
            return Finding("–", None)
        stiff, soft = rows[min(rows)], rows[max(rows)]
        text = "; ".join(f"t_c {format_number(t, 2)}: {format_number(m.value, 3)} ± "
                         f"{format_number(m.error, 2)}" for t, m in sorted(rows.items(),
                                                                           reverse=True))
        return Finding(text, soft.value - stiff.value > combined_error(soft.error, stiff.error))
    return check


def phi_j_between(group):
    """ch. 6: the study's phi_J lies between granjet's phi_s and phi_T."""
    def check(results):
        rows = table_rows(results, "F6.5", "fits", {"group": group})
        if not rows:
            return Finding("–", None)
        phi_s, phi_t = number(rows[0].get("phi_s [6.3]")), number(rows[0].get("phi_T [6.2]"))
        if not (math.isfinite(phi_s) and math.isfinite(phi_t)):
            return Finding("–", None)
        return Finding(f"phi_s {format_number(phi_s, 3)}, phi_T {format_number(phi_t, 3)}",
                       min(phi_s, phi_t) < PHI_J < max(phi_s, phi_t))
    return check


# ---- The rows, in the order of the study's publication ----------------------------------------
def low_phi(b):
    return b.phi < 0.5


def outer_rings(b):
    return 0.2 < b.ring < 1


ROWS = [
    *(Numeric("F4.2", f"{name} of the psi0(X) law [rad]", value, None,
              stored("F4.2", "fit", f"e{e:g}", f"{name} [deg]", then=degrees_to_radians),
              f"fit to the ensemble means, e = {e:g} (deg converted); error: the fit's s.e.")
      for name, value in zip(("C0", "C1", "C2"), STUDY_C) for e in RESTITUTIONS),
    *(Numeric("F4.2", f"psi0 at X = {x:g} [rad] (the study's law and C0, C1, C2)",
              study_psi0(x), None,
              table_cell("F4.2", "psi0", "psi0 [deg]", {"e": e, "X": x},
                         then=degrees_to_radians),
              f"psi0 from the scattered grains' mean velocity (default), e = {e:g} (deg "
              "converted)")
      for x in STUDY_X for e in RESTITUTIONS),
    Qualitative("F4.2", "psi0 and the wall force",
                "[4.3]: 4 A_cs/(pi D_jet^2) = 1 - cos psi0, A_cs = F_wall/j_in", None,
                "granjet measures psi0 by this relation under analysis.psi0 = momentum (the "
                "F4.2 rows read that way)", "Readings"),
    Qualitative("F4.3", "v2 against eps",
                "grows with eps, not linearly, much smaller than the experiment's 0.16 at "
                "eps = 0.615", v2_trend,
                "criterion: |v2| grows at every step of eps, |v2|/eps at the largest eps off "
                "that at the smallest non-zero eps by more than 10%, |v2| < 0.16 at the eps "
                "nearest 0.615 (magnitudes: granjet's v2 is negative)"),
    *(Numeric("F5.3", f"abs(sigma_rz/sigma_zz) at r/R_tar = 0.1, {label}", STUDY_RATIO[key],
              None, stored("F5.3", f"ratio_rz_zz_r0.1{suffix}", key, then=magnitude),
              f"{origin}; phi~0 = 0.9, ratio per seed")
      for key, _, label in FRICTIONS for _, suffix, origin in ORIGINS_3D),
    *(Qualitative("F5.3", f"normal stresses, {label}", "sigma_zz > sigma_thetatheta, sigma_rr "
                  "(these two about equal)", normal_stresses(key),
                  "criterion: sigma_zz > sigma_thetatheta and sigma_zz > sigma_rr in the inner "
                  "ring; wall centres, phi~0 = 0.9")
      for key, _, label in FRICTIONS),
    Qualitative("F5.4", "sqrt(T_g/m) against r", "largest at the centre (no dead zone in 3D)",
                centre_extreme("sqrt(T_g/m)", max),
                "criterion: the inner ring's is the largest of its profile at every point "
                "(both mu_p, every phi~0; wall centres)"),
    Qualitative("F5.4", "v_r against r", "small at the centre", centre_extreme("v_r", min),
                "criterion: the inner ring's |v_r| is the smallest of its profile at every "
                "point (both mu_p, every phi~0; wall centres)"),
    Qualitative("F5.5", "P/(n T_g) for phi < 0.5", "on [5.2]",
                within_theory("F5.5", "P_over_nT", low_phi, "bins with phi < 0.5"),
                "criterion: every bin with phi < 0.5 within 10% of [5.2]+[5.3] (e, or e-bar "
                "[2.55] for mu_p = 0.2); all rings, phi~0, mu_p; wall centres"),
    Qualitative("F5.5", "P/(n T_g) for 0.5 < phi < 0.6", "deviates from [5.2] only at "
                "r/R_tar = 0.1", dense_deviation,
                "criterion: the bins off by more than 10% are all in the inner ring, and there "
                "is one; wall centres"),
    *(Qualitative("F5.6", f"P_{a}/(n T_{a})", "on [5.2]",
                  within_theory("F5.6", f"P_over_nT_alpha_{a}", low_phi, "bins with phi < 0.5"),
                  "criterion: every bin with phi < 0.5 within 10% of the directional [5.2]; "
                  "all rings, phi~0, mu_p; wall centres")
      for a in ("z", "r")),
    Qualitative("F5.6", "P_theta/(n T_theta)", "systematically above [5.2]",
                above_theory("F5.6", "P_over_nT_alpha_t", low_phi, "bins with phi < 0.5"),
                "criterion: every bin with phi < 0.5 above the directional [5.2]; all rings, "
                "phi~0, mu_p; wall centres"),
    *(Numeric("F5.7", f"a of mu* = a I, {label}", STUDY_A[key], None, granjet, reading)
      for key, mu_p, label in FRICTIONS
      for granjet, reading in (
          (stored("F5.7", "a", key), "pooled over every ring and phi~0; wall centres"),
          *((table_cell("F5.7", "a_per_point", "a: fit value ± std over seeds",
                        {"group": group, "mu_p": mu_p, "phi~0": 0.9}),
             f"phi~0 = 0.9 alone; {origin}") for group, _, origin in ORIGINS_3D))),
    *(Numeric("T5.2", f"-sigma_Y x 1e3 at r/R_tar = {ring:g}, {label}", value, error,
              table_cell("T5.2", "sigma_Y", f"r/R={ring:.1f}",
                         {"mu_p": mu_p, "phi~0": 0.9, "row": "sigma_Y"}, then=times(-1e3)),
              "sigma_Y = sigma_rz + eta_kin D_rz; phi~0 = 0.9; wall centres")
      for _, mu_p, label in FRICTIONS
      for ring, value, error in STUDY_SIGMA_Y),
    Qualitative("F5.9", "eta* against phi, 0.2 < r/R_tar < 1", "kinetic theory [5.6] "
                "reproduced", within_theory("F5.9", "eta_star", outer_rings,
                                            "bins with 0.2 < r/R_tar < 1"),
                "criterion: every bin with 0.2 < r/R_tar < 1 within 10% of [5.6]; all phi~0, "
                "mu_p; the study's strain-rate window is not applied (D_rz is not stored)"),
    Qualitative("F5.10", "eta*_mu", "below 80% of kinetic theory", not_in_report,
                "the report holds no eta*_mu"),
    *(Qualitative("F6.3", "2D T_g: dead zone", "T_g drops at the centre in layer (a), not in "
                  "(b)", dead_zone(group),
                  f"criterion: the central bins' T_g below the next bin on each side in layer "
                  f"(a), not in (b); [{group}], {origin}")
      for group, origin in ORIGINS_2D),
    *(Qualitative("F6.3", "3D T_g against 2D", "3D T_g higher than 2D", hotter_in_3d(group),
                  f"criterion: the largest 3D T_g (frictionless, phi~0 = 0.9, F5.4) above the "
                  f"largest 2D T_g of either layer; [{group}], {origin}")
      for group, origin in ORIGINS_2D),
    *(Numeric("F6.5", f"{name} [{law}]", value, error,
              table_cell("F6.5", "fits", f"{name} [{law}]", {"group": group}),
              f"[{group}], {origin}")
      for name, law, value, error in STUDY_FITS_2D if law in ("6.2", "6.3")
      for group, origin in ORIGINS_2D),
    *(Numeric("F6.7", f"{name} [{law}]", value, error,
              table_cell("F6.7", "fits", f"{name} [{law}]", {"group": "jet2d"}),
              "[jet2d], height origin: wall centres")
      for name, law, value, error in STUDY_FITS_2D if law in ("6.9", "6.10")),
    Numeric("F6.7", "(1 - beta/2) alpha_s", 0.96, None, half_beta_alpha,
            "[jet2d], wall centres: beta [6.10] (F6.7), alpha_s [6.3] (F6.5); errors combined "
            "as independent"),
    Qualitative("F6.12", "phi_s against mu_p", "decreases slightly with mu_p",
                slight_decrease("phi_s [6.3]"),
                "criterion: falls at every step of mu_p, by less than 10% in all; bidisperse, "
                "each mu_p at the study's t_c; wall centres"),
    *(Qualitative("F6.14", f"{name} against mu_p", "insensitive to mu_p",
                  insensitive(column),
                  "criterion: every mu_p within the error bars of mu_p = 0 (numeric rule), "
                  "values with error > value left out; bidisperse; wall centres")
      for name, column in (("beta [6.10]", "beta [6.10]"), ("mu_max [6.9]", "mu_max [6.9]"))),
    Qualitative("F6.14", "mu_0 (mu_s of [6.9]) against mu_p", "mu_0 about 0",
                small_at_every_friction("mu_s [6.9]", MU_0_SMALL),
                f"criterion: |mu_s| < {MU_0_SMALL:g} (a tenth of the study's mu_max) at every "
                "mu_p; bidisperse; wall centres"),
    Qualitative("F6.18", "monodisperse mu*(I_s)", "layers (a), (b) not on one curve, "
                "non-monotonic: two branches", None, "no single number stored for the branches",
                see="F6.16-F6.18"),
    *(Qualitative("FE.1", f"bursts against t_c ({name})", "T_g in layer (a) rises many times "
                  "at large t_c (mu_p = 1.0), suppressed at small t_c", bursts_fall(column),
                  f"criterion: the {name} at the smallest t_c below that at the largest, beyond "
                  "the combined error bars")
      for name, column in (("std of T_g(t)", "std of T_g(t)"),
                           ("CV of T_g(t)", "CV = std/<T_g>"))),
    Qualitative("FE.1", "frictionless and mu_p = 0.2", "reach a small steady T_g",
                not_in_report, "FE.1 runs mu_p = 1.0 only"),
    Numeric("ch. 6", "phi_J by the conventional route", PHI_J, None,
            lambda _results: NOT_MEASURED, "not run (reference only)"),
    *(Qualitative("ch. 6", "phi_J between phi_s and phi_T", f"{PHI_J:g} between them",
                  phi_j_between(group),
                  f"criterion: the study's phi_J between granjet's phi_s [6.3] and phi_T [6.2]; "
                  f"[{group}], {origin}")
      for group, origin in ORIGINS_2D),
]

# The readings of the study's text (section Readings), each beside the same published number.
WITHOUT_TARGET = "analysis.stress_wall_contacts = exclude (contacts with target grains left out)"
READING_ROWS = [
    *(Numeric("F4.2", f"{name} of the psi0(X) law [rad]", value, None,
              reading_list_cell(("Readings", "psi0_momentum_fit", f"e{e:g}", "C"), k),
              f"analysis.psi0 = momentum, fit to the ensemble means, e = {e:g}; error: the "
              "fit's s.e.")
      for k, (name, value) in enumerate(zip(("C0", "C1", "C2"), STUDY_C))
      for e in RESTITUTIONS),
    *(Numeric("F4.2", f"psi0 at X = {x:g} [rad] (the study's law and C0, C1, C2)",
              study_psi0(x), None,
              table_cell("Readings", "psi0_readings", "psi0 momentum [deg]", {"e": e, "X": x},
                         then=degrees_to_radians),
              f"analysis.psi0 = momentum: 1 - cos psi0 = impulse / incident momentum [4.3], "
              f"e = {e:g}")
      for x in STUDY_X for e in RESTITUTIONS),
    *(Numeric("F5.3", f"abs(sigma_rz/sigma_zz) at r/R_tar = 0.1, {label}", STUDY_RATIO[key],
              None, stored("Readings", "ratio_rz_zz_r0.1", key, "without_target"),
              f"{WITHOUT_TARGET}; wall centres, phi~0 = 0.9")
      for key, _, label in FRICTIONS),
    *(Numeric("F5.3", f"abs(sigma_rz/sigma_zz) at r/R_tar = 0.1, {label}", STUDY_RATIO[key],
              None, stored("Readings", "ratio_rz_zz_raised", key, window, "with_target"),
              f"the 5 d window {window} d above the target grains' centres (rebuilt from 0.5 d "
              "sublayers; the target's contacts do not reach it); phi~0 = 0.9")
      for key, _, label in FRICTIONS for window in ("1-6", "2-7")),
    *(Numeric("F5.3", f"abs(sigma_rz/sigma_zz) at r/R_tar = 0.1, {label}", STUDY_RATIO[key],
              None, stored("Readings", "targets", "reading_smooth_target",
                           f"spacing0.5_mu{mu_p:g}", part),
              f"a smoother target: overlapping grains at wall.spacing = 0.5{how}; phi~0 = 0.9")
      for key, mu_p, label in FRICTIONS
      for part, how in (("with_target", ""), ("without_target",
                                              ", without the target's contacts"))),
    *(Numeric("F5.7", f"a of mu* = a I, {label}", STUDY_A[key], None,
              stored("Readings", "a", key, "without", "a"),
              f"{WITHOUT_TARGET}; pooled over every ring and phi~0")
      for key, _, label in FRICTIONS),
    *(Numeric("T5.2", f"-sigma_Y x 1e3 at r/R_tar = {ring:g}, {label}", value, error,
              reading_list_cell(("Readings", "minus_sigma_Y_1e3", key, "without"), k),
              f"{WITHOUT_TARGET}; phi~0 = 0.9")
      for key, _, label in FRICTIONS for k, (ring, value, error) in enumerate(STUDY_SIGMA_Y)),
    *(Numeric(fig, f"{name} [{law}]", value, error,
              stored("Readings", "pooled_2d", origin, name, "value"),
              f"pooled over phi~0 = 0.3 ... 0.9 and layers (a), (b) as the study; "
              f"height origin: {origin.replace('_', ' ')}")
      for name, law, value, error in STUDY_FITS_2D
      for fig in ("F6.5" if law in ("6.2", "6.3") else "F6.7",)
      for origin in ("wall_centres", "wall_surface")),
    *(Numeric("F6.5", f"{name} [{law}]", value, error,
              stored("Readings", "pooled_2d", f"{origin}_centres", name, "value"),
              f"pooled as the study, phi counted by grain centres (times the mean disk area); "
              f"height origin: {origin.replace('_', ' ')}")
      for name, law, value, error in STUDY_FITS_2D if law in ("6.2", "6.3")
      for origin in ("wall_centres", "wall_surface")),
]
ID_ORDER = [row.id for row in ROWS]
ROWS = sorted(ROWS + READING_ROWS, key=lambda row: ID_ORDER.index(row.id))  # stable: by id


# ---- Verdicts ---------------------------------------------------------------------------------
def combined_error(*errors):
    """sqrt of the sum of squares; a missing (NaN) error counts as 0."""
    return math.sqrt(sum(e * e for e in errors if e is not None and math.isfinite(e)))


def within_error_bars(m, study, study_error):
    return abs(m.value - study) <= combined_error(study_error, m.error)


def two_digits(x):
    return f"{float(f'{x:.2g}'):g}"


def numeric_verdict(m, study, study_error):
    if not (math.isfinite(m.value) and math.isfinite(study)):
        return NOT_MEASURED_VERDICT
    if within_error_bars(m, study, study_error):
        return WITHIN_ERRORS
    if m.value * study < 0:
        return "opposite sign"
    if study == 0:
        return "off by a factor inf"
    ratio = m.value / study
    return WITHIN_2X if 0.5 <= ratio <= 2 else f"off by a factor {two_digits(ratio)}"


def qualitative_verdict(finding):
    if finding.agrees is None:
        return NOT_MEASURED_VERDICT
    return AGREES if finding.agrees else DIFFERS


def evaluate_numeric(row, results):
    study = float(row.study() if callable(row.study) else row.study)
    try:
        m = row.granjet(results)
    except (KeyError, TypeError, ValueError, IndexError, ZeroDivisionError, AttributeError):
        m = NOT_MEASURED
    return Line(row.id, row.quantity, study, row.error, m, row.reading,
                numeric_verdict(m, study, row.error), True)


def evaluate_qualitative(row, results):
    if row.check is None:
        return Line(row.id, row.quantity, row.study, None, "–", row.reading,
                    f"qualitative: see section {row.see or row.id}", False)
    try:
        finding = row.check(results)
    except (KeyError, TypeError, ValueError, IndexError, ZeroDivisionError, AttributeError):
        finding = Finding("–", None)
    return Line(row.id, row.quantity, row.study, None, finding.text, row.reading,
                qualitative_verdict(finding), False)


def evaluate(row, results):
    if isinstance(row, Numeric):
        return evaluate_numeric(row, results)
    return evaluate_qualitative(row, results)


# ---- The section ------------------------------------------------------------------------------
RULE = (
    "Each row puts one of the study's published numbers or statements (its value ± its error "
    "bar where it prints one) beside granjet's, read from the other sections' results (the "
    "numbers results.json stores; ± the std over seeds unless the reading says otherwise), "
    "once for each reading the report holds: the reading column names the definition or option "
    "that produced granjet's number (for qualitative rows, also the criterion). Numeric rows: "
    "'within error bars' when |granjet - study| <= sqrt(err_study^2 + err_granjet^2), a missing "
    "error counting as 0; else 'within 2x' when both have the same sign and granjet/study is in "
    "[0.5, 2]; else 'off by a factor N' (N = granjet/study to two significant digits) or "
    "'opposite sign'. Qualitative rows: 'agrees' or 'differs' by the criterion stated in the "
    "row, on granjet's numbers ('within 10%': |granjet/theory - 1| <= 0.1); 'not measured' "
    "where the report holds no number for it; 'qualitative: see section X' where no simple "
    "criterion on granjet's numbers exists. Angles in radians, as the study prints them.")


def counts(lines):
    numeric = [line.verdict for line in lines if line.numeric]
    qualitative = [line.verdict for line in lines if not line.numeric]
    return {"numeric": len(numeric), "within_error_bars": numeric.count(WITHIN_ERRORS),
            "within_2x": numeric.count(WITHIN_2X),
            "not_measured": numeric.count(NOT_MEASURED_VERDICT),
            "qualitative": len(qualitative), "agrees": qualitative.count(AGREES),
            "differs": qualitative.count(DIFFERS),
            "qualitative_not_measured": qualitative.count(NOT_MEASURED_VERDICT),
            "qualitative_only": sum(v.startswith("qualitative") for v in qualitative)}


def count_line(count):
    off = count["numeric"] - count["within_error_bars"] - count["within_2x"] - \
        count["not_measured"]
    return (f"**{count['within_error_bars']} of {count['numeric']} numeric rows within the "
            f"study's error bars** ({count['within_2x']} within 2x, {off} further off, "
            f"{count['not_measured']} not measured); qualitative rows: {count['agrees']} agree, "
            f"{count['differs']} differ, {count['qualitative_not_measured']} not measured, "
            f"{count['qualitative_only']} left to the figures, of {count['qualitative']}.")


def published_table(lines):
    table = Table("published", ["id", "quantity", "the study", "granjet", "reading", "verdict"])
    for line in lines:
        table.add(line.id, line.quantity, line.study_cell(), line.granjet, line.reading,
                  line.verdict)
    return table


def hand_written(ctx, section):
    """The text file's part before its verdict, when there is one (no placeholder)."""
    path = os.path.join(ctx.text_dir, f"{PUBLISHED_ID}.md")
    return section.before if os.path.isfile(path) else ""


def section_published(ctx, sections):
    """The section, from the results of the sections built before it."""
    s = ctx.section(PUBLISHED_ID, TITLE)
    results = {section.id: section.results for section in sections}
    lines = [evaluate(row, results) for row in ROWS]
    count = counts(lines)
    s.before = "\n\n".join(p for p in (count_line(count), hand_written(ctx, s)) if p)
    s.add(RULE)
    s.add(published_table(lines).markdown())
    s.results["count"] = count
    s.results["rows"] = [line.json() for line in lines]
    return s
