#!/usr/bin/python3
"""Tests of scripts/reproduction_report.py on a real campaign: campaigns/smoke.ini run by the
granjet binary (a few seconds), and the report written from it into temporary directories.

    /usr/bin/python3 tests/scripts/test_reproduction_report.py [--granjet PATH]

PATH defaults to build/app/granjet (CMake passes the built target). Prints "N passed,
M failed" last; exit code 0 only when all pass.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "reproduction_report.py")
TEXTS = os.path.join(ROOT, "docs", "reproduction", "text")
sys.dont_write_bytecode = True  # no __pycache__ in scripts/
GRANJET = None  # the binary under test: script_tests.main_with_granjet sets it from --granjet
sys.path.insert(0, os.path.dirname(SCRIPT))
import campaign_data  # noqa: E402
import report_published  # noqa: E402
import reproduction_report  # noqa: E402
import script_tests  # noqa: E402

# Spec §7 in the table's order, plus the hard-core question.
RESULT_IDS = ["T4.1", "F4.2", "F4.3", "F5.3", "F5.4", "F5.5", "F5.6", "T5.1", "F5.7", "T5.2",
              "F5.9", "F6.3", "F6.4", "F6.5", "F6.7", "F6.11-F6.14", "F6.16-F6.18", "FE.1", "HC"]
# What campaigns/smoke.ini feeds (its groups' `results`, and F6.11-F6.14 through its
# frictionless 2D jet, the reference of the friction study).
SMOKE_IDS = {"T4.1", "F5.3", "F6.3", "F6.4", "F6.11-F6.14", "HC"}
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


class SmokeCampaign:
    """campaigns/smoke.ini run once into a directory shared by the tests, and its report."""
    directory = None
    report = None

    @classmethod
    def path(cls):
        if cls.directory is None:
            cls.directory = tempfile.mkdtemp(prefix="granjet_report_campaign_")
            result = subprocess.run([GRANJET, "campaign", os.path.join(ROOT, "campaigns",
                                                                       "smoke.ini"),
                                     "--out", cls.directory, "--jobs", "2"],
                                    capture_output=True, text=True, timeout=120)
            assert result.returncode == 0, f"smoke campaign failed:\n{result.stderr}"
        return cls.directory


def default_report():
    """The report of the smoke campaign with the repository's texts, written once:
    (directory, Markdown, results)."""
    if SmokeCampaign.report is None:
        out = os.path.join(SmokeCampaign.path(), "docs")
        SmokeCampaign.report = (out, *report(out))
    return SmokeCampaign.report


def report(out, *args, campaign_dir=None):
    result = subprocess.run([sys.executable, SCRIPT, campaign_dir or SmokeCampaign.path(),
                             "--out", out, *args], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, f"exit {result.returncode}\n{result.stderr}"
    assert "Traceback" not in result.stderr and "Warning" not in result.stderr, result.stderr
    with open(os.path.join(out, "reproduction.md"), encoding="utf-8") as f:
        markdown = f.read()
    with open(os.path.join(out, "reproduction", "results.json"), encoding="utf-8") as f:
        results = json.load(f)
    return markdown, results


def section(markdown, result_id):
    """The text of one section, from its heading to the next."""
    start = markdown.index(f"\n## {result_id}: ")
    end = markdown.find("\n## ", start + 1)
    return markdown[start:end]


def linked_figures(markdown):
    return [line.split("](", 1)[1].rstrip(")") for line in markdown.splitlines()
            if line.startswith("![")]


# ---- The report of a real campaign ----------------------------------------------------------
def test_every_id_has_a_section_in_the_spec_order(tmp):
    _, markdown, _ = default_report()
    positions = [markdown.index(f"\n## {rid}: ") for rid in RESULT_IDS]
    assert positions == sorted(positions), "sections out of the model's order"
    assert markdown.index("\n## The campaign") < positions[0]
    assert "\n## Sensitivity: " in markdown, markdown[-400:]
    # The closing list: one verdict line per id, HC last.
    last = markdown.rstrip().rsplit("\n", 1)[-1]
    assert last.startswith("- **HC**: Verdict: "), last


def test_ids_without_runs_say_not_yet_run(tmp):
    _, markdown, results = default_report()
    for rid in RESULT_IDS:
        text = section(markdown, rid)
        if rid in SMOKE_IDS:
            assert "Not yet run" not in text, f"{rid} has runs:\n{text[:600]}"
            assert results[rid]["status"] == "complete", (rid, results[rid]["status"])
        else:
            assert "**Not yet run** (0 of 0 ensembles present)" in text, text[:600]
            assert results[rid]["status"] == "not yet run", rid


def test_figures_are_small_pngs_and_all_linked(tmp):
    docs, markdown, _ = default_report()
    links = linked_figures(markdown)
    assert len(links) >= 5, links
    on_disk = sorted(f for f in os.listdir(os.path.join(docs, "reproduction"))
                     if f.endswith(".png"))
    assert sorted(os.path.basename(p) for p in links) == on_disk, (links, on_disk)
    for link in links:
        path = os.path.join(docs, link)
        with open(path, "rb") as png:
            assert png.read(8) == PNG_SIGNATURE, path
        assert 3000 < os.path.getsize(path) < 100_000, (path, os.path.getsize(path))


def test_results_json_holds_the_numbers_by_id(tmp):
    _, _, results = default_report()
    assert set(results) == set(RESULT_IDS) | {"meta", "Sensitivity", "Causes", "Readings",
                                              "Published"}, sorted(results)
    assert results["meta"]["campaign"] == "smoke" and not results["meta"]["quick"]
    ratio = results["F5.3"]["ratio_rz_zz_r0.1"]["frictional"]  # smoke's 3D jet: mu_p = 0.2
    assert len(ratio) == 2 and math.isfinite(ratio[0]) and ratio[1] >= 0, ratio
    binary = results["T4.1"]["tables"]["binary"]
    assert [row["e"] for row in binary] == [0.75, 0.9], binary
    for row in binary:  # the simulated collision restores the requested e
        assert abs(row["measured e"] - row["e"]) < 0.01 * row["e"], row
    hc = results["HC"]["tables"]["jet_layer_a"]
    assert len(hc) == 10 and all(len(row["P (ED)"]) == 2 for row in hc), hc[:2]


def test_report_is_deterministic_and_replaces_stale_figures(tmp):
    first, markdown, results = default_report()
    second = os.path.join(tmp, "second")
    os.makedirs(os.path.join(second, "reproduction"))
    stale = os.path.join(second, "reproduction", "F4_2_psi0.png")
    shutil.copy(os.path.join(first, linked_figures(markdown)[0]), stale)
    again, results_again = report(second)
    assert again == markdown and results_again == results
    with open(os.path.join(first, "reproduction", "results.json"), "rb") as a, \
            open(os.path.join(second, "reproduction", "results.json"), "rb") as b:
        assert a.read() == b.read(), "results.json differs between two runs"
    assert not os.path.exists(stale), "a figure of an earlier report was left behind"


def test_missing_and_incomplete_ensembles(tmp):
    campaign = os.path.join(tmp, "campaign")
    shutil.copytree(SmokeCampaign.path(), campaign)
    os.remove(os.path.join(campaign, "jet3d", "jet3d.h5"))  # F5.3's only ensemble
    os.remove(os.path.join(campaign, "jet2d", "friction-0.2.h5"))  # one of F6.3's two
    markdown, results = report(os.path.join(tmp, "docs"), campaign_dir=campaign)
    assert "**Not yet run** (0 of 1 ensembles present)" in section(markdown, "F5.3")
    assert results["F5.3"]["status"] == "not yet run"
    assert "**Incomplete**: 1 of 2 ensembles present" in section(markdown, "F6.3")
    assert results["F6.3"]["ensembles"] == {"planned": 2, "present": 1, "complete": 1}


def test_text_files_wrap_the_numbers(tmp):
    texts = os.path.join(tmp, "text")
    os.makedirs(texts)
    with open(os.path.join(texts, "F5.3.md"), "w", encoding="utf-8") as f:
        f.write("What the study shows, in test words.\n\nVerdict: agrees, tested.\nCause: none.\n")
    markdown, _ = report(os.path.join(tmp, "docs"), "--text", texts)
    text = section(markdown, "F5.3")
    study, table, verdict = (text.index(s) for s in ("in test words", "| group |",
                                                        "Verdict: agrees, tested."))
    assert study < table < text.index("Generated comparison") < verdict, text
    assert "Cause: none." in text
    assert "- **F5.3**: Verdict: agrees, tested." in markdown
    assert "No text yet: write `docs/reproduction/text/F4.2.md`" in markdown


def test_sensitivity_groups_are_listed_before_they_run(tmp):
    campaign_file = os.path.join(tmp, "smoke_sens.ini")
    with open(os.path.join(ROOT, "campaigns", "smoke.ini"), encoding="utf-8") as f:
        smoke = f.read().replace("../scenes/", os.path.join(ROOT, "scenes") + "/")
    with open(campaign_file, "w", encoding="utf-8") as f:
        f.write(smoke + "\n# The target's kind.\n[sens_wall]\nresults = F5.3\nscene = "
                + os.path.join(ROOT, "scenes", "jet3d.ini") + "\nwall.kind = fixed, tethered\n")
    markdown, results = report(os.path.join(tmp, "docs"), "--campaign", campaign_file)
    text = section(markdown, "Sensitivity")
    assert "| wall.kind=fixed | sens_wall/kind-fixed | 0/2 | – | – | – | – |" in text, text
    assert "a (mu\\* = a I)" in text, text
    rows = results["Sensitivity"]["tables"]["sens_wall"]
    assert [r["group/point"] for r in rows] == ["sens_wall/kind-fixed", "sens_wall/kind-tethered"]


def test_causes_resolve_the_layers_and_split_the_contact_stress(tmp):
    """A smoke campaign with `causes` groups: the smoke jets cut into sublayers of 1 d."""
    campaign_file = os.path.join(tmp, "smoke_causes.ini")
    with open(os.path.join(ROOT, "campaigns", "smoke.ini"), encoding="utf-8") as f:
        smoke = f.read().replace("../scenes/", os.path.join(ROOT, "scenes") + "/")
    sublayers = "analysis.layers = 3\nanalysis.layer_height = 1\nseeds = 1..2\n"
    groups = []
    for name, source in (("causes3d", "[jet3d]"), ("causes2d", "[jet2d]")):
        body = smoke.split(source, 1)[1].split("\n[", 1)[0]
        body = body.replace("results = F5.3", "").replace("results = F6.3, F6.4", "")
        if name == "causes3d":  # both frictions: frictionless contacts carry no tangential force
            body += "\ncontact.friction = 0, 0.2\n"
        else:
            body = body.replace("contact.friction = 0, 0.2", "contact.friction = 0")
        groups.append(f"\n[{name}]\nresults = causes\n{body.strip()}\n{sublayers}")
    with open(campaign_file, "w", encoding="utf-8") as f:
        f.write(smoke + "".join(groups))
    campaign = os.path.join(tmp, "campaign")
    shutil.copytree(SmokeCampaign.path(), campaign)
    result = subprocess.run([GRANJET, "campaign", campaign_file, "--out", campaign, "--quiet"],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    markdown, results = report(os.path.join(tmp, "docs"), "--campaign", campaign_file,
                               campaign_dir=campaign)
    text = section(markdown, "Causes")
    assert "causes_3d_shear_sublayers.png" in text and "causes_2d_slow_region.png" in text, text
    tables = results["Causes"]["tables"]
    frictionless = tables["causes3d/friction-0"]
    assert [row["h (d)"] for row in frictionless] == [0.5, 1.5, 2.5], frictionless
    for row in frictionless:
        value, error = row["tangential (all contacts)"]
        assert abs(value) < 1e-12 and abs(error) < 1e-12, row
    frictional = tables["causes3d/friction-0.2"]
    assert any(abs(row["tangential (all contacts)"][0]) > 1e-6 for row in frictional), frictional
    for row in frictionless + frictional:  # only the lowest sublayer holds target contacts
        if row["h (d)"] > 1:
            assert row["contact with target"][0] == 0.0, row
    assert {r["group"] for r in results["Causes"]["targets_3d"]} == {"causes3d"}
    contacts = [row["contacts per grain"][0] for row in tables["causes2d/causes2d"]]
    assert len(contacts) == 3 and all(c is None or c >= 0 for c in contacts), contacts
    assert "- **Causes**" not in markdown, "the closing list holds the study's ids only"


def test_a_missing_campaign_directory_is_refused(tmp):
    result = subprocess.run([sys.executable, SCRIPT, os.path.join(tmp, "none"), "--out", tmp],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2 and "is not a directory" in result.stderr, result.stderr
    assert not os.path.exists(os.path.join(tmp, "reproduction.md"))


# ---- The pieces ------------------------------------------------------------------------------
def test_plan_matches_what_granjet_planned(tmp):
    campaign = campaign_data.Campaign(SmokeCampaign.path())
    planned = {f"{r['group']}/{r['point']}.seed{r['seed']}" for r in
               campaign.manifest["runs"].values()}
    ours = {f"{p.name}.seed{s}" for p in campaign.all_points() for s in p.seeds}
    assert ours == planned, (sorted(ours), sorted(planned))
    assert campaign_data.parse_seeds("1..3") == [1, 2, 3]
    assert campaign_data.parse_seeds("4, 7") == [4, 7]


def test_formulas_match_the_spec(tmp):
    r = reproduction_report
    for (e, t_c), (k_n, eta_n) in r.STUDY_T4_1.items():  # model §2's table, 3 digits
        derived = r.contact_parameters_3_4_3_5(e, t_c)
        assert abs(derived[0] - k_n) < 0.005 * k_n and abs(derived[1] - eta_n) < 0.005 * eta_n
    assert abs(r.viscosity_star_5_6(1e-12, 1.0) - 1.0) < 1e-9  # dilute elastic limit
    # The report's fits are granjet's (granjet.fits), values in the order of their parameters.
    x = np.linspace(0.5, 4, 8)
    truth = (100.0, 30.0, 20.0)
    fit, error = r.fitted(r.pa.fits.scattering_angle, x, r.scattering_fit_law(x, *truth))
    assert np.allclose(fit, truth, rtol=1e-6), fit
    a, b, slope = r.mu_lines([1, 2, 3, 4], [1.5, 2.5, 3.5, 4.5])
    assert abs(a - 35 / 30) < 1e-9  # through the origin: sum(x y) / sum(x^2)
    assert abs(b - 0.5) < 1e-9 and abs(slope - 1) < 1e-9


def test_published_verdicts_follow_the_stated_rule(tmp):
    verdict = report_published.numeric_verdict
    m = campaign_data.Measured
    assert verdict(m(1.0, 0.3), 1.2, 0.1) == "within error bars"  # 0.2 <= sqrt(0.1)
    assert verdict(m(1.0, math.nan), 1.2, None) == "within 2x"
    assert verdict(m(3.0, 0.1), 1.0, 0.1) == "off by a factor 3"
    assert verdict(m(-1.0, 0.1), 1.0, 0.1) == "opposite sign"
    assert verdict(m(math.nan, 0.1), 1.0, 0.1) == "not measured"
    # Every published number has a row, and the count line adds up.
    _, markdown, results = default_report()
    rows = results["Published"]["rows"]
    assert {r["id"] for r in rows} >= {"F4.2", "F5.3", "F5.7", "T5.2", "F6.5", "F6.7", "ch. 6"}
    text = section(markdown, "Published")
    assert "numeric rows within the study's error bars" in text, text[:400]


def test_readings_fe1_printed_parameters_under_3_4_and_3_5(tmp):
    _, _, results = default_report()
    printed = results["Readings"]["fe1_printed"]
    # Back through [3.4]-[3.5]: the (e, t_c) found give the printed (k_n, eta_n) again.
    k_n, eta_n = reproduction_report.contact_parameters_3_4_3_5(printed["e"], printed["t_c"])
    assert abs(k_n - 796.0) < 1e-9 * 796 and abs(eta_n - 10.15) < 1e-9 * 10.15, (k_n, eta_n)
    assert 0.08 < printed["t_c"] < 0.083 and 0.43 < printed["e"] < 0.45, printed


def cleanup():
    if SmokeCampaign.directory:
        shutil.rmtree(SmokeCampaign.directory, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(script_tests.main_with_granjet(globals(), ROOT, cleanup))
