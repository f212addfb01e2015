"""Flank modification and assembly displacements: the inputs of the contact state.

Checked against values worked out by hand, not against the code's own output:
the relief is C_L u^2 + C_P v^2 + B u v (plus a topography read from a file
and interpolated bilinearly), the configuration speaks micrometres and
millimetres/degrees while the objects hold metres and radians, every bad
input is rejected with a message naming the key (or the file) and its value,
and the displacements move the members the way the docstring's sign
convention says (P along a1 away from the apex, G along a2, E along +z, Sigma
opening the shaft angle).
"""

import math
import re

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.tca.misalignment import Misalignment, member_frames
from lsbg.tca.modification import FlankModification, TopographyError, read_topography


@pytest.fixture(scope="module")
def pair():
    return GearPair(GearPairDesign.from_config(dict(trace="logarithmic", spiral_angle_deg=35)))


# ------------------------------------------------------------------ relief
def test_relief_is_the_ease_off_polynomial():
    mod = FlankModification(20e-6, 8e-6, 3e-6)
    # (u, v) -> 20 u^2 + 8 v^2 + 3 u v [um], worked out by hand
    cases = {(0.0, 0.0): 0.0, (1.0, 0.0): 20.0, (0.0, -1.0): 8.0, (1.0, 1.0): 31.0,
             (-1.0, 1.0): 25.0, (0.5, -0.25): 5.125, (-0.5, 1.0): 11.5}
    for (u, v), expected in cases.items():
        assert mod.relief(u, v) == pytest.approx(expected * 1e-6, rel=1e-12, abs=1e-18)
    # arrays broadcast
    u = np.array([0.0, 1.0, 0.5])
    np.testing.assert_allclose(mod.relief(u[:, None], np.array([0.0, -0.25])[None, :]),
                               [[0.0, 0.5e-6], [20e-6, 20e-6 + 0.5e-6 - 0.75e-6],
                                [5e-6, 5.125e-6]], rtol=1e-12, atol=1e-20)


def test_bias_twists_the_corners():
    """+B at (+1, +1) and (-1, -1), -B at the other two corners."""
    mod = FlankModification(0.0, 0.0, 4e-6)
    assert mod.relief(1, 1) == pytest.approx(4e-6) and mod.relief(-1, -1) == pytest.approx(4e-6)
    assert mod.relief(1, -1) == pytest.approx(-4e-6) and mod.relief(-1, 1) == pytest.approx(-4e-6)
    assert mod.relief(0.0, 1.0) == 0.0 and mod.relief(1.0, 0.0) == 0.0


def test_is_zero_and_largest_relief():
    assert FlankModification().is_zero
    assert not FlankModification(1e-15).is_zero
    assert not FlankModification(0.0, 0.0, -1e-6).is_zero
    assert not FlankModification(topography_file="somewhere.csv").is_zero
    # the largest |relief| is at a corner: 20 + 8 + 3 um, whichever sign the bias has
    assert FlankModification(20e-6, 8e-6, 3e-6).largest_relief() == pytest.approx(31e-6)
    assert FlankModification(20e-6, 8e-6, -3e-6).largest_relief() == pytest.approx(31e-6)
    # a pure negative twist: |-B| at two corners
    assert FlankModification(0.0, 0.0, -2e-6).largest_relief() == pytest.approx(2e-6)
    assert FlankModification().largest_relief() == 0.0


def test_tip_reliefs_run_out_linearly_from_each_tip():
    """C_a1 at the pinion's tip end (v = -1 here), 0 from L_1 of the profile on; the
    gear's C_a2 from the other end; worked out by hand."""
    mod = FlankModification(pinion_tip_relief=20e-6, pinion_tip_relief_length=0.25,
                            gear_tip_relief=10e-6, gear_tip_relief_length=0.5)
    # v = -1: w_1 = 0 -> 20; v = -0.75: w_1 = 0.125 -> 10; v = -0.5: w_1 = 0.25 -> 0
    # gear: w_2 = (1 + v) / 2, relief 10 (1 - w_2 / 0.5) where w_2 < 0.5
    cases = {-1.0: 20.0, -0.75: 10.0, -0.5: 0.0, 0.0: 0.0, 0.5: 5.0, 1.0: 10.0}
    for v, expected in cases.items():
        assert mod.relief(0.3, v) == pytest.approx(expected * 1e-6, abs=1e-18)
    # the other sense: the pinion's tip at v = +1
    assert mod.relief(0.0, 1.0, pinion_tip=1.0) == pytest.approx(20e-6)
    assert mod.relief(0.0, -1.0, pinion_tip=1.0) == pytest.approx(10e-6)
    assert mod.relief_starts() == {"pinion": pytest.approx(-0.5), "gear": pytest.approx(0.0)}
    assert not mod.is_zero and mod.has_tip_relief
    assert mod.largest_relief() == pytest.approx(20e-6)


def test_the_pinion_tip_relief_sits_on_the_pinion_tip(pair):
    """On the real flank: the point at the pinion's tip angle carries C_a1, the one
    at the start of the active profile C_a2 (the gear's tip meets it there)."""
    from lsbg.tca.modification import pinion_relief, pinion_tip_end, profile_coordinate

    assert pinion_tip_end(pair) == -1.0
    mod = FlankModification(pinion_tip_relief=12e-6, gear_tip_relief=7e-6)
    rho = pair.design.mean_cone_distance
    assert pinion_relief(pair, mod, rho, pair.design.tip_angle(1)) == pytest.approx(12e-6)
    # the polar angle at which the field's other end (v = +1) meets the pinion
    plane = pair.planes["drive"]
    chi = plane.roll_sign[1] * (plane.field[1] - plane.tangency_angle[1])
    theta = math.acos(math.cos(pair.design.base_cone_angle(1)) * math.cos(chi))
    assert float(profile_coordinate(pair, theta)) == pytest.approx(1.0, abs=1e-9)
    assert pinion_relief(pair, mod, rho, theta) == pytest.approx(7e-6, rel=1e-6)


def test_first_order_corrections_tilt_the_flank():
    mod = FlankModification(spiral_angle_correction=4e-6, pressure_angle_correction=-3e-6)
    # C_beta u + C_alpha v [um], by hand
    for (u, v), expected in {(1, 0): 4, (-1, 0): -4, (0, 1): -3, (0.5, -1): 5}.items():
        assert mod.relief(u, v) == pytest.approx(expected * 1e-6)
    back = FlankModification.from_config(mod.to_config())
    assert back == mod and not mod.is_zero and mod.has_linear_terms
    with pytest.raises(ValueError, match=re.escape(
            "flank_modification.pressure_angle_correction_um = inf")):
        FlankModification.from_config({"pressure_angle_correction_um": float("inf")})


def test_tip_relief_config_round_trip():
    config = {"pinion_tip_relief_um": 15, "pinion_tip_relief_length": 0.3,
              "gear_tip_relief_um": 25, "gear_tip_relief_length": 0.2}
    mod = FlankModification.from_config(config)
    assert (mod.pinion_tip_relief, mod.gear_tip_relief) == (pytest.approx(15e-6),
                                                            pytest.approx(25e-6))
    assert (mod.pinion_tip_relief_length, mod.gear_tip_relief_length) == (0.3, 0.2)
    assert FlankModification.from_config(mod.to_config()) == mod
    # without tip relief the keys stay the four they were
    assert set(FlankModification(25e-6).to_config()) == {
        "lengthwise_crowning_um", "profile_crowning_um", "bias_um", "topography_file"}


@pytest.mark.parametrize("config, key, shown", [
    ({"pinion_tip_relief_um": -1}, "pinion_tip_relief_um", "-1"),
    ({"gear_tip_relief_um": "a lot"}, "gear_tip_relief_um", "'a lot'"),
    ({"gear_tip_relief_length": 0}, "gear_tip_relief_length", "0.0"),
    ({"pinion_tip_relief_length": 1.5}, "pinion_tip_relief_length", "1.5"),
])
def test_bad_tip_relief_names_key_and_value(config, key, shown):
    with pytest.raises(ValueError, match=re.escape(f"flank_modification.{key} = {shown}")):
        FlankModification.from_config(config)


# ------------------------------------------------------------------ configuration
def test_config_round_trip_in_micrometres():
    config = {"lengthwise_crowning_um": 25, "profile_crowning_um": 5.5, "bias_um": -2,
              "topography_file": None}
    mod = FlankModification.from_config(config)
    assert mod.lengthwise_crowning == pytest.approx(25e-6, rel=1e-12)
    assert mod.profile_crowning == pytest.approx(5.5e-6, rel=1e-12)
    assert mod.bias == pytest.approx(-2e-6, rel=1e-12)
    back = mod.to_config()
    assert set(back) == set(config)
    for key, value in config.items():
        assert back[key] == (None if value is None else pytest.approx(value, rel=1e-12))
    assert FlankModification.from_config(back) == mod
    assert FlankModification.from_config(None).is_zero
    assert FlankModification.from_config({}).is_zero


@pytest.mark.parametrize("config, key, shown", [
    ({"crowning_um": 3}, "crowning_um", "3"),
    ({"lengthwise_crowning_um": -5}, "lengthwise_crowning_um", "-5"),
    ({"profile_crowning_um": -0.5}, "profile_crowning_um", "-0.5"),
    ({"profile_crowning_um": "five"}, "profile_crowning_um", "'five'"),
    ({"bias_um": True}, "bias_um", "True"),
    ({"bias_um": float("nan")}, "bias_um", "nan"),
    ({"lengthwise_crowning_um": float("inf")}, "lengthwise_crowning_um", "inf"),
    ({"topography_file": 3}, "topography_file", "3"),
])
def test_bad_configuration_names_key_and_value(config, key, shown):
    with pytest.raises(ValueError, match=re.escape(f"flank_modification.{key} = {shown}")):
        FlankModification.from_config(config)


# ------------------------------------------------------------------ topography
def _field(u, v):
    """A topography that is not bilinear, so interpolation has something to do [um]."""
    return u**2 + 0.5 * u * v - v**3 + 1.0


U_GRID = np.array([-1.0, -0.5, 0.0, 0.5, 1.0])
V_GRID = np.array([-1.0, -0.2, 0.4, 1.0])


def _table():
    u, v = np.meshgrid(U_GRID, V_GRID, indexing="ij")
    return pd.DataFrame({"u": u.ravel(), "v": v.ravel(), "relief_um": _field(u, v).ravel()})


@pytest.fixture
def csv_file(tmp_path):
    path = tmp_path / "topography.csv"
    # rows shuffled: the reader must sort them onto the grid
    _table().sample(frac=1.0, random_state=3).to_csv(path, index=False)
    return path


@pytest.fixture
def netcdf_file(tmp_path):
    path = tmp_path / "topography.nc"
    u, v = np.meshgrid(U_GRID, V_GRID, indexing="ij")
    # stored as (v, u): the reader must transpose it
    xr.Dataset({"relief": (("v", "u"), _field(u, v).T, {"units": "um"})},
               coords={"u": U_GRID, "v": V_GRID}).to_netcdf(path)
    return path


def _check_interpolation(mod, extra=lambda u, v: 0.0):
    # at every grid node the file's value (um -> m)
    for a in U_GRID:
        for b in V_GRID:
            assert mod.relief(a, b) == pytest.approx((_field(a, b) + extra(a, b)) * 1e-6,
                                                     rel=1e-12, abs=1e-18)
    # bilinear: a cell's centre is the mean of its four corners, the middle of an
    # edge the mean of its two ends
    for i in range(U_GRID.size - 1):
        for j in range(V_GRID.size - 1):
            uc, vc = 0.5 * (U_GRID[i] + U_GRID[i + 1]), 0.5 * (V_GRID[j] + V_GRID[j + 1])
            corners = np.mean([_field(U_GRID[i + a], V_GRID[j + b]) for a in (0, 1)
                               for b in (0, 1)])
            assert mod.relief(uc, vc) == pytest.approx((corners + extra(uc, vc)) * 1e-6,
                                                       rel=1e-12)
            edge = 0.5 * (_field(U_GRID[i], V_GRID[j]) + _field(U_GRID[i], V_GRID[j + 1]))
            assert mod.relief(U_GRID[i], vc) == pytest.approx(
                (edge + extra(U_GRID[i], vc)) * 1e-6, rel=1e-12)


def test_csv_topography_is_interpolated_bilinearly(csv_file):
    mod = FlankModification.from_config({"topography_file": csv_file.name},
                                        base=csv_file.parent)
    assert mod.topography is not None and not mod.is_zero
    assert mod.topography_file == str(csv_file)
    _check_interpolation(mod)
    grid_u, grid_v, values = mod.topography
    np.testing.assert_array_equal(grid_u, U_GRID)
    np.testing.assert_array_equal(grid_v, V_GRID)
    # the largest |relief| over the flank is at a node here (u = +-1, v = -1: 1 + 1 -+ 0.5 + 1)
    assert mod.largest_relief() == pytest.approx(3.5e-6, rel=1e-9)


def test_netcdf_topography_adds_to_the_crowning(netcdf_file):
    mod = FlankModification.from_config({"lengthwise_crowning_um": 10,
                                         "topography_file": str(netcdf_file)})
    _check_interpolation(mod, extra=lambda u, v: 10.0 * u**2)


def _write(path, table):
    table.to_csv(path, index=False)
    return path


@pytest.mark.parametrize("spoil, words", [
    ("missing", "no such file"),
    ("column", "missing"),
    ("row", "not a full grid"),
    ("nan", "NaN"),
    ("short", "must cover -1..1"),
    ("netcdf", "relief"),
])
def test_bad_topography_names_the_file(tmp_path, spoil, words):
    path = tmp_path / "bad.csv"
    table = _table()
    if spoil == "column":
        _write(path, table.rename(columns={"relief_um": "relief"}))
    elif spoil == "row":
        _write(path, table.drop(index=5))
    elif spoil == "nan":
        table.loc[7, "relief_um"] = np.nan
        _write(path, table)
    elif spoil == "short":
        _write(path, table[table["u"] > -1.0])  # covers u -0.5..1 only
    elif spoil == "netcdf":
        path = tmp_path / "bad.nc"
        xr.Dataset({"height": (("u", "v"), np.zeros((U_GRID.size, V_GRID.size)))},
                   coords={"u": U_GRID, "v": V_GRID}).to_netcdf(path)
    with pytest.raises(TopographyError, match=re.escape(str(path))) as err:
        read_topography(path)
    assert words in str(err.value)
    assert "flank_modification.topography_file" in str(err.value)
    # through the configuration too, and as a ValueError
    with pytest.raises(ValueError, match=re.escape(str(path))):
        FlankModification.from_config({"topography_file": str(path)})


# ------------------------------------------------------------------ misalignment
def test_misalignment_config_units():
    config = {"offset_E_mm": 0.2, "pinion_axial_P_mm": -0.1, "gear_axial_G_mm": 0.05,
              "shaft_angle_error_deg": 0.1}
    mis = Misalignment.from_config(config)
    assert mis.offset == pytest.approx(2e-4, rel=1e-12)
    assert mis.pinion_axial == pytest.approx(-1e-4, rel=1e-12)
    assert mis.gear_axial == pytest.approx(5e-5, rel=1e-12)
    assert mis.shaft_angle_error == pytest.approx(0.1 * math.pi / 180, rel=1e-12)
    back = mis.to_config()
    assert set(back) == set(config)
    for key, value in config.items():
        assert back[key] == pytest.approx(value, rel=1e-12)
    assert Misalignment.from_config(None).is_zero and not mis.is_zero
    assert Misalignment().replace(P=1e-4) == Misalignment(pinion_axial=1e-4)
    assert Misalignment().replace(Sigma=0.01, E=2e-4) == Misalignment(offset=2e-4,
                                                                      shaft_angle_error=0.01)


@pytest.mark.parametrize("config, text", [
    ({"P_mm": 0.1}, "misalignment.P_mm = 0.1: unknown key"),
    ({"offset_E_mm": "x"}, "misalignment.offset_E_mm = 'x'"),
    ({"gear_axial_G_mm": float("nan")}, "misalignment.gear_axial_G_mm = nan"),
    ({"shaft_angle_error_deg": True}, "misalignment.shaft_angle_error_deg = True"),
])
def test_misalignment_bad_configuration(config, text):
    with pytest.raises(ValueError, match=re.escape(text)):
        Misalignment.from_config(config)


def test_misalignment_replace_rejects_unknown_letters():
    with pytest.raises(ValueError, match="'X'"):
        Misalignment().replace(X=1.0)


def _angle(a, b):
    return math.acos(max(-1.0, min(1.0, float(a @ b) / (np.linalg.norm(a) * np.linalg.norm(b)))))


def test_member_frames_follow_the_sign_convention(pair):
    a1, a2, z = pair.axis[1], pair.axis[2], np.array([0.0, 0.0, 1.0])
    # a pinion flank point sits on the side of the apex a1 points to
    design = pair.design
    lo, hi = pair.flank_polar_range(1)
    point, _ = pair.flank(1, "drive", design.mean_cone_distance, 0.5 * (lo + hi))
    assert point @ a1 > 0

    shift, turn, gear_shift = member_frames(pair, Misalignment(pinion_axial=1e-4))
    np.testing.assert_allclose(shift, 1e-4 * a1, atol=1e-18)
    np.testing.assert_array_equal(turn, np.eye(3))
    np.testing.assert_array_equal(gear_shift, np.zeros(3))
    # P > 0: the pinion's points move away from the apex
    assert np.linalg.norm(point + shift) > np.linalg.norm(point)

    shift, turn, gear_shift = member_frames(pair, Misalignment(gear_axial=-2e-4))
    np.testing.assert_array_equal(shift, np.zeros(3))
    np.testing.assert_allclose(gear_shift, -2e-4 * a2, atol=1e-18)

    shift, _, _ = member_frames(pair, Misalignment(offset=3e-4))
    np.testing.assert_allclose(shift, 3e-4 * z, atol=1e-18)

    nominal = _angle(a1, a2)
    for sigma in (1e-3, -2e-3, 0.05):
        _, turn, gear_shift = member_frames(pair, Misalignment(shaft_angle_error=sigma))
        np.testing.assert_allclose(turn @ turn.T, np.eye(3), atol=1e-15)
        assert np.linalg.det(turn) == pytest.approx(1.0, abs=1e-15)
        np.testing.assert_allclose(turn @ z, z, atol=1e-15)  # a turn about z
        np.testing.assert_array_equal(gear_shift, np.zeros(3))
        assert _angle(a1, turn @ a2) - nominal == pytest.approx(sigma, abs=1e-12)

    # G after the turn: along the turned gear axis
    _, turn, gear_shift = member_frames(pair, Misalignment(gear_axial=1e-4,
                                                           shaft_angle_error=0.01))
    np.testing.assert_allclose(gear_shift, 1e-4 * (turn @ a2), atol=1e-18)
