"""The first screen: the verdict matrix and its legend, the coarse configuration's banner."""

from pathlib import Path

import pandas as pd
import pytest
import xarray as xr

from lsbg.tables import claims as claim_tables
from lsbg.tables import first_screen

#: The workflow's configurations (the repository's).
WORKFLOW = Path(__file__).resolve().parents[2] / "workflow"


def verdict(better):
    table = pd.DataFrame({"cell": [f"c{i}" for i in range(len(better))], "quantity": "x",
                          "better": better})
    return claim_tables.claim_verdict(table, "wins")


def test_the_matrix_has_a_column_per_level_ran_and_a_word_per_cell():
    published = ({"stability": verdict(["SBG", "LSBG", "SBG"]),
                  "contact state": verdict(["SBG", "tie"]),
                  "service life": verdict(["tie", "tie"])},
                 {"stability": 16, "contact state": 6, "service life": 9})
    practice = ({"stability": verdict(["tie", "tie"]), "contact state": verdict(["SBG"])},
                {"stability": 2, "contact state": 1})
    matrix = first_screen.verdict_matrix({"published": published, "practice": practice,
                                          "best": ({}, {})})
    # a level with no claims is no column
    assert list(dict.fromkeys(matrix.level)) == ["as published", "as a designer would make it"]
    cell = matrix.set_index(["claim", "level"])
    assert cell.loc[("stability", "as published"), "verdict"] == "not shown"
    assert cell.loc[("stability", "as published"), "cells"] == 16
    assert cell.loc[("contact state", "as published"), "verdict"] == "no"
    # a tie everywhere is "not shown", never "no"
    assert cell.loc[("service life", "as published"), "verdict"] == "not shown"
    assert cell.loc[("stability", "as a designer would make it"), "verdict"] == "not shown"
    assert cell.loc[("contact state", "as a designer would make it"), "verdict"] == (
        "no, the opposite")
    assert cell.loc[("service life", "as a designer would make it"), "verdict"] == "not tested"
    html = first_screen.matrix_html(matrix)
    assert html.count("<tr>") == 4 and "16 cells" in html and "1 cell<" in html
    assert first_screen.VERDICT_COLOURS["no"] in html
    assert "nan" not in html and "None" not in html
    sentence = first_screen.verdict_sentence(matrix)
    assert sentence.startswith("The paper's claims for the LSBG, as published: stability not "
                               "shown, contact state no, service life not shown;")
    with pytest.raises(ValueError, match="unknown"):
        first_screen.verdict_matrix({"later": published})


def test_the_legend_defines_every_verdict_word():
    legend = first_screen.legend_html()
    for word, meaning in claim_tables.VERDICT_WORDS.items():
        assert f"<b>{word}</b></span>: {meaning}" in legend
    assert "not tested" in legend and "tie" in claim_tables.VERDICT_WORDS["not shown"]


def test_coarse_is_decided_against_the_studys_defaults():
    defaults = first_screen.study_defaults()
    assert defaults["simulation"]["duration_s"] == 1.0 and defaults["tooth"]["face_points"] == 9
    runs = [xr.Dataset(attrs={"solver_duration_s": 0.05, "solver_samples": 25})]
    fe = [xr.Dataset(attrs={"fe_tooth_size": 0.52, "fe_body_size": 10.0, "fe_face_points": 9,
                            "fe_profile_points": 7, "phases": 200})]
    vh = [xr.Dataset({"x": (("E", "P"), [[0.0] * 3] * 3)}, attrs={"axes": "E P",
                                                                    "positions": 100})]
    recorded = first_screen.recorded_settings(runs=runs, fe_ltcas=fe, vh_maps=vh)
    coarse = first_screen.coarse_settings(recorded, defaults)
    assert [k for k, _, _ in coarse] == ["simulation.duration_s", "simulation.samples",
                                         "tooth.element_size_module",
                                         "tooth.rim_element_factor", "misalignment_map.steps"]
    banner = first_screen.coarse_banner(coarse, "this report")
    assert "are not the study's" in banner and "simulation.duration_s 0.05 (study: 1)" in banner
    # the study's own settings, or finer ones, are not coarse: no banner
    fine = first_screen.recorded_settings(
        runs=[xr.Dataset(attrs={"solver_duration_s": 2.0, "solver_samples": 500})],
        fe_ltcas=[xr.Dataset(attrs={"fe_tooth_size": 0.4, "fe_body_size": 6.0})])
    assert first_screen.coarse_settings(fine, defaults) == []
    assert first_screen.coarse_banner([]) == ""
    # files of one kind that differ: the coarsest counts
    mixed = first_screen.recorded_settings(runs=[
        xr.Dataset(attrs={"solver_duration_s": 1.0}), xr.Dataset(attrs={"solver_duration_s": 0.5})])
    assert mixed == {"simulation.duration_s": 0.5}
    with pytest.raises(ValueError, match="unknown kinds"):
        first_screen.recorded_settings(meshes=runs)


def test_the_test_configuration_is_coarse():
    from lsbg.config import resolve_config

    test = resolve_config([WORKFLOW / "config.yaml", WORKFLOW / "config-test.yaml"])
    recorded = {"simulation.duration_s": test["simulation"]["duration_s"],
                "tca.positions": test["tca"]["positions"],
                "optimise.population": test["optimise"]["population"]}
    assert len(first_screen.coarse_settings(recorded, first_screen.study_defaults())) == 3


def test_the_studys_defaults_are_the_workflows_configuration():
    """The banner compares with the schema's defaults (package data, no checkout needed):
    workflow/config.yaml must keep them for every setting the banner compares."""
    from lsbg.config import resolve_config

    workflow = resolve_config([WORKFLOW / "config.yaml"])
    defaults = first_screen.study_defaults()
    for key in first_screen.COMPARED_KEYS:
        section, name = key.split(".")
        assert workflow[section][name] == defaults[section][name], key


def test_the_screen_puts_the_banner_above_the_matrix_and_the_legend_below():
    matrix = first_screen.verdict_matrix({"published": ({"stability": verdict(["LSBG"])},
                                                        {"stability": 1})})
    screen = first_screen.screen_html(matrix, "<b>claims</b>", "<div>BANNER</div>")
    assert screen.index("BANNER") < screen.index("lsbg-verdicts") < screen.index("lsbg-legend")
    assert "<b>yes</b><br><small>1 cell</small>" in screen
    assert screen.count("not tested") == 1 + 2   # the legend's word; two claims not tested
