"""Tables of the service life (lsbg.tables.rating) on ratings built from known stresses."""

import math

import numpy as np
import pytest
import xarray as xr

from lsbg.gear.design import GearPairDesign
from lsbg.rating.dataset import rating_dataset
from lsbg.rating.iso10300 import RatingConditions, RatingMaterial, rate
from lsbg.rating.virtual import rating_geometry
from lsbg.tables.rating import life_statement, life_table, rating_table
from lsbg.tca.misalignment import envelope_corners


def fe_ltca(pressure, pinion, gear):
    """A stand-in FE loaded TCA: per-position largest pressure and root stresses [MPa]."""
    phases = np.linspace(0, 1, 5)
    shape = np.array([0.6, 0.8, 1.0, 0.8, 0.6])
    return xr.Dataset({"max_contact_pressure": ("mesh_phase", pressure * shape),
                       "root_stress_pinion": ("mesh_phase", pinion * shape),
                       "root_stress_gear": ("mesh_phase", gear * shape)},
                      coords={"mesh_phase": phases}, attrs={"load_torque_N_m": 1964.99})


def rating(trace, pressure, pinion, gear, displaced_factor=1.2):
    design = GearPairDesign.from_config({"trace": trace})
    material, conditions = RatingMaterial(), RatingConditions(dynamic_factor=1.01)
    result = rate(rating_geometry(design), 1964.99 * 9 / 37, math.radians(7703), material,
                  conditions)
    corners = envelope_corners(["E", "P"], 0.1)
    ltcas = [fe_ltca(pressure * displaced_factor ** k, pinion, gear) for k in range(4)]
    envelope = xr.Dataset(
        {name: (("corner", "mesh_phase"), np.stack([ds[name].values for ds in ltcas]))
         for name in ("max_contact_pressure", "root_stress_pinion", "root_stress_gear")},
        coords={"corner": list(corners), "axis": ["E", "P"]})
    envelope["displacement"] = (("corner", "axis"),
                                np.array([list(v.values()) for v in corners.values()]))
    return rating_dataset(result, design, material, conditions, "test",
                          fe_ltca(pressure, pinion, gear), envelope)


def test_envelope_corners_are_every_sign():
    corners = envelope_corners(["E", "P"], 0.1)
    assert corners == {"E+0.1 P+0.1": {"E": 0.1, "P": 0.1}, "E+0.1 P-0.1": {"E": 0.1, "P": -0.1},
                       "E-0.1 P+0.1": {"E": -0.1, "P": 0.1}, "E-0.1 P-0.1": {"E": -0.1, "P": -0.1}}


def test_rating_table_shows_the_standard_and_the_worst_corner():
    ratings = {"SBG": rating("circular", 3000.0, 2000.0, 1000.0),
               "LSBG": rating("logarithmic", 3000.0, 2000.0, 1000.0)}
    table = rating_table(ratings).set_index("figure")
    assert list(table.columns) == ["unit", "SBG", "LSBG"]
    iso = float(ratings["SBG"]["contact_stress"])
    assert table.loc["contact stress σ_H (ISO 10300-2)", "SBG"] == pytest.approx(iso)
    assert table.loc["FE: largest Hertz pressure over the cycle", "LSBG"] == pytest.approx(3000.0)
    assert table.loc["FE: its median over the positions", "LSBG"] == pytest.approx(2400.0)
    # the worst of the four corners: the fourth, 1.2^3 times the aligned pressure
    worst = table.loc["FE, displaced (worst corner): largest Hertz pressure", "SBG"]
    assert worst == pytest.approx(3000.0 * 1.2 ** 3)
    assert table.loc["rated gear torque, pitting (S_H = 1)", "SBG"] < 1964.99


def test_life_ratio_follows_the_stress_ratio_to_the_exponent():
    ratings = {"SBG": rating("circular", 3000.0, 2000.0, 1000.0),
               "LSBG": rating("logarithmic", 2700.0, 1800.0, 900.0)}
    life = life_table(ratings).set_index("stress")
    row = life.loc["root, pinion, FE largest stress"]
    assert row["stress ratio LSBG/SBG"] == pytest.approx(0.9)
    assert row["life ratio LSBG/SBG"] == pytest.approx(0.9 ** -row["exponent p"])
    assert row["least over the p range"] <= row["life ratio LSBG/SBG"] <= row["most over the p range"]
    assert "pitting, displaced, FE largest pressure" in life.index


def test_life_statement_names_a_ranking_only_where_every_stress_agrees():
    sbg = rating("circular", 3000.0, 2000.0, 1000.0)
    lower = {"SBG": sbg, "LSBG": rating("logarithmic", 2700.0, 1800.0, 900.0)}
    assert life_statement(lower).startswith("The **LSBG** lives longer in every comparison")
    ties = {"SBG": sbg, "LSBG": rating("logarithmic", 3030.0, 2010.0, 995.0)}
    assert life_statement(ties).startswith("Neither lives measurably longer")
    mixed = {"SBG": sbg, "LSBG": rating("logarithmic", 2700.0, 2300.0, 1000.0)}
    text = life_statement(mixed, "at 35°")
    assert text.startswith("At 35°, **neither** type lives longer in every comparison (the "
                           "LSBG in")
    # only higher or tied: the other type never loses
    one_sided = {"SBG": sbg, "LSBG": rating("logarithmic", 3000.0, 2300.0, 1000.0)}
    assert life_statement(one_sided).startswith("The LSBG lives longer in no comparison; the **SBG** in")


def test_the_brief_statement_keeps_the_verdict_and_the_ratios():
    ratings = {"SBG": rating("circular", 3000.0, 2000.0, 1000.0),
               "LSBG": rating("logarithmic", 2700.0, 1800.0, 900.0)}
    brief = life_statement(ratings, "at 35°", brief=True)
    assert brief.startswith("At 35°, the **LSBG** lives longer in every comparison.")
    assert "pinion root ×0.9" in brief and "life ×" not in brief
    assert len(brief) < len(life_statement(ratings, "at 35°")) / 2
