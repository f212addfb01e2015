"""Tables and the plain statement of the contact state (lsbg.tables.contact_state).

The numbers in the tables are the datasets' own (nothing recomputed), the
statement names the type whose pattern really moves less, and the per-angle
table picks, at each spiral angle, the type with the smaller movement.
"""

import math

import pytest

from lsbg.gear.design import GearPairDesign
from lsbg.figures import contact_state as contact_figures
from lsbg.gear.geometry import GearPair
from lsbg.tables import contact_state as tables
from lsbg.tca.analysis import tooth_contact_analysis
from lsbg.tca.modification import FlankModification
from lsbg.tca.vh_map import misalignment_map

CROWNED = FlankModification(25e-6, 5e-6)


@pytest.fixture(scope="module")
def maps():
    out = {}
    for spiral in (30, 35):
        for trace in ("logarithmic", "circular"):
            pair = GearPair(GearPairDesign.from_config({"trace": trace, "spiral_angle_deg": spiral}))
            out[(trace, spiral)] = misalignment_map(pair, CROWNED, values=([-0.1, 0, 0.1],) * 2,
                                                    load_torque=500.0, positions=24, phases=16)
    return out


def test_sensitivity_table_is_the_maps_attributes(maps):
    at35 = {"LSBG": maps[("logarithmic", 35)], "SBG": maps[("circular", 35)]}
    table = tables.sensitivity_table(at35)
    assert len(table) == len(tables.SENSITIVITIES) * 2
    row = table[(table.quantity == "pattern moves towards the heel") & (table.displacement == "P")]
    assert float(row["LSBG"].iloc[0]) == at35["LSBG"].attrs["pattern_shift_lengthwise_per_0_1_P"]
    assert set(table.unit) >= {"mm per 0.1 mm", "µrad per 0.1 mm"}


def test_pattern_movement_is_the_length_of_the_shift(maps):
    ds = maps[("logarithmic", 35)]
    move = tables.pattern_movement(ds)
    lengthwise, profile = (ds.attrs["pattern_shift_lengthwise_per_0_1_P"],
                           ds.attrs["pattern_shift_profile_per_0_1_P"])
    assert move["P"] == pytest.approx(math.hypot(lengthwise, profile))
    assert move["total"] == pytest.approx(math.hypot(move["E"], move["P"]))


def test_statement_names_the_type_that_moves_less(maps):
    at35 = {"LSBG": maps[("logarithmic", 35)], "SBG": maps[("circular", 35)]}
    totals = {t: tables.pattern_movement(ds)["total"] for t, ds in at35.items()}
    steadier = min(totals, key=totals.get)
    text = tables.movement_statement(at35, where="at 35°")
    assert f"the **{steadier}**'s bearing pattern moves less" in text
    assert f"{totals[steadier]:.2g} mm" in text and "at 35°" in text


def test_per_angle_table_and_its_figure(maps):
    table = tables.sensitivity_by_angle(maps.values())
    assert sorted(table.spiral_angle.unique()) == [30.0, 35.0]
    steadier = tables.steadier_by_angle(table)
    for row in steadier.itertuples():
        assert row.steadier == ("SBG" if abs(row.SBG) < abs(row.LSBG) else "LSBG")
    fig = contact_figures.sensitivity_against_angle(table)
    assert len(fig.axes) == 2
    assert all("[" in ax.get_ylabel() and "[deg]" in ax.get_xlabel() for ax in fig.axes)


def test_tca_table_reads_the_analysis(maps):
    pair = GearPair(GearPairDesign())
    ds = tooth_contact_analysis(pair, CROWNED, positions=40)
    table = tables.tca_table({"LSBG": ds})
    assert table.loc[0, "transmission_error_pp_urad"] == ds.attrs[
        "transmission_error_peak_to_peak_urad"]
    assert table.loc[0, "pattern_length_percent"] == pytest.approx(
        100 * ds.attrs["pattern_length_mm"] / 25.0)
