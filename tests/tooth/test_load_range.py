"""The FE loaded TCA over a range of torques (lsbg.tooth.load_range)."""

import math

import numpy as np
import pytest

from lsbg.contact import ContactParameters, MeshContact
from lsbg.gear.design import GearPairDesign
from lsbg.tca.modification import FlankModification
from lsbg.tca.separation import separation_field
from lsbg.tooth.elasticity import largest_principal, largest_principal_over_points
from lsbg.tooth.load_range import fe_load_range
from lsbg.tooth.ltca import fe_loaded_tca

RATED = 480.0  # about the pair's rated pitting torque on the gear (ISO 10300) [N m]
#: 10 %, 50 %, 100 % and 200 % of it: T and 2 T for the growth laws [N m]
TORQUES = RATED * np.array([0.1, 0.5, 1.0, 2.0])
PHASES = 16
#: What fe_load_range must reproduce of fe_loaded_tca at each torque, to a relative
#: tolerance of the variable's largest value: the same solver and tolerance, but
#: another start (the last torque's loads, not the last position's)
SAME = ("transmission_error", "max_contact_pressure", "max_flank_pressure",
        "root_stress_pinion", "root_stress_gear", "edge_load_share", "edge_line_load",
        "relief_start_load_share", "relief_start_line_load")


@pytest.fixture(scope="module")
def contact(pair):
    # crowned flanks: the pattern grows with the load
    return MeshContact(pair, ContactParameters(model="line"),
                       separation=separation_field(pair, FlankModification(25e-6, 5e-6)))


@pytest.fixture(scope="module")
def load_range(contact, compliance):
    # given unsorted: solved and returned in ascending order
    return fe_load_range(contact, compliance, TORQUES[::-1], phases=PHASES)


@pytest.mark.parametrize("torque", TORQUES)
def test_each_torque_is_the_single_torque_ltca(load_range, contact, compliance, torque):
    """The unique solution, found from another start (the last torque's loads at the
    position, not the last position's): the same solver stops when the loads change
    by less than 1e-10 of the largest. Transmission error, pressures and root
    stresses agree to 1e-9 at every position (measured: 5e-13). The edge loads to
    1e-8 of their largest value: a band cut to a sliver by the field's edge turns
    a load's last digits into a line load's (measured: 2e-10 here, 2e-9 on the
    default mesh at 200 positions)."""
    one = fe_loaded_tca(contact, compliance, torque, phases=PHASES)
    ours = load_range.sel(torque=torque)
    for name in SAME:
        expected = one[name].values
        scale = max(np.abs(expected).max(), 1e-300)
        np.testing.assert_allclose(ours[name].values, expected, rtol=0, atol=1e-8 * scale,
                                   err_msg=name)
    for name in ("transmission_error", "max_contact_pressure", "root_stress_pinion",
                 "root_stress_gear"):
        np.testing.assert_allclose(ours[name].values, one[name].values, rtol=1e-9, atol=0,
                                   err_msg=name)
    # the tangent of the solution's linear system against fe_loaded_tca's central
    # difference at +-0.1 % of the torque: the same but where a point enters
    # contact within the step (a kink that the difference averages over)
    tangent, difference = ours["mesh_stiffness"].values, one["mesh_stiffness"].values
    relative = np.abs(tangent / difference - 1)
    assert np.median(relative) < 1e-6 and relative.max() < 1e-2
    assert float(ours["mesh_stiffness_mean"]) == pytest.approx(
        one.attrs["mesh_stiffness_mean_N_per_um"], rel=1e-3)
    assert float(ours["transmission_error_peak_to_peak"]) == pytest.approx(
        one.attrs["transmission_error_peak_to_peak_urad"], rel=1e-9)
    assert float(ours["transmission_error_first_harmonic"]) == pytest.approx(
        one.attrs["transmission_error_harmonic_1_urad"], rel=1e-9)
    assert float(ours["cycle_max_root_stress_gear"]) == pytest.approx(
        one.attrs["max_root_stress_gear_MPa"], rel=1e-9)


def test_every_position_carries_the_torque(load_range):
    # e2 sum of lever x load over each tooth pair's points, summed over the pairs
    carried = load_range["pair_torque"].sum("tooth_pair")
    torque = load_range["torque"]
    np.testing.assert_allclose(carried.values, np.broadcast_to(torque.values[:, None],
                                                               carried.shape), rtol=1e-9)
    assert np.all(load_range["pair_torque"].values >= 0)
    # more than one pair shares the load somewhere in the cycle
    assert np.any((load_range["pair_torque"] > 0).sum("tooth_pair") >= 2)


def test_loads_grow_as_hertz_and_beam_theory_say(load_range):
    """Doubling the torque (T, the rated torque, to 2 T). Hertz: p ~ sqrt(q). On a
    line of fixed length q doubles (a factor sqrt 2), on a crowned flank the contact
    grows in both directions (p ~ T^(1/3), 1.26): the largest pressure grows
    sub-linearly, by more than 0.8 sqrt 2; less than 2, though a band at the
    profile's edge takes a growing share of the load (its q grows faster than T:
    up to 1.76 for this pair from 2 to 4 times the rated torque). Off the edges,
    where Hertz's line contact holds, near sqrt 2. The root stress is linear in
    the loads (superposed FE stresses), which grow as T but spread over the
    growing pattern, or move towards the tip with the edge's share: nearly
    linear, a factor 1.6-2.1 (1.62-1.90 for this pair from 0.5 to 4 times)."""
    at = load_range.sel
    t, t2 = RATED, 2 * RATED
    for name in ("cycle_max_contact_pressure", "cycle_max_flank_pressure"):
        ratio = float(at(torque=t2)[name] / at(torque=t)[name])
        assert 0.8 * math.sqrt(2) < ratio < 2, (name, ratio)
    ratio = float(at(torque=t2)["cycle_max_flank_pressure"]
                  / at(torque=t)["cycle_max_flank_pressure"])
    assert ratio == pytest.approx(math.sqrt(2), rel=0.1)
    for member in ("pinion", "gear"):
        ratio = float(at(torque=t2)[f"cycle_max_root_stress_{member}"]
                      / at(torque=t)[f"cycle_max_root_stress_{member}"])
        assert 1.6 < ratio < 2.1, (member, ratio)
    # every figure grows with the torque; the pattern from a short one at 10 %
    for name in ("cycle_max_contact_pressure", "cycle_max_root_stress_pinion",
                 "cycle_max_root_stress_gear", "transmission_error_mean", "pattern_length",
                 "pattern_width"):
        assert np.all(np.diff(load_range[name].values) >= 0), name
    length = load_range["pattern_length"].values
    assert length[0] < length[-1]
    assert length[-1] <= GearPairDesign().face_width * 1e3 + 1e-9
    assert 0 < load_range["pattern_width"].values[0]


def test_dataset_speaks_units_and_short_labels(load_range, contact, compliance):
    for name, variable in load_range.data_vars.items():
        assert "units" in variable.attrs, name
        assert len(variable.attrs["long_name"]) <= 40, name
    assert load_range["torque"].attrs["units"] == "N m"
    assert list(load_range["torque"].values) == sorted(TORQUES)
    assert load_range["transmission_error"].dims == ("torque", "mesh_phase")
    attrs = load_range.attrs
    assert attrs["phases"] == PHASES
    assert attrs["form_limit"] == "generated flanks"
    assert attrs["compliance_inputs_hash"] == str(compliance.attrs["inputs_hash"])
    for key, value in contact.separation.attrs.items():
        assert attrs[key] == value


def test_one_torque_is_a_range_too(contact, compliance):
    out = fe_load_range(contact, compliance, RATED, phases=8, form_limit=False)
    assert out.sizes["torque"] == 1 and out.attrs["form_limit"] == "lsbg field"
    one = fe_loaded_tca(contact, compliance, RATED, phases=8, form_limit=False)
    np.testing.assert_allclose(out["transmission_error"].values[0],
                               one["transmission_error"].values, rtol=1e-9)


@pytest.mark.parametrize("kwargs, key", [
    ({"torques": []}, "torques"),
    ({"torques": [100.0, -1.0]}, "torques"),
    ({"torques": [100.0, math.nan]}, "torques"),
    ({"torques": [100.0, math.inf]}, "torques"),
    ({"torques": [100.0, 100.0]}, "torques"),
    ({"torques": [[100.0, 200.0]]}, "torques"),
    ({"torques": ["a lot"]}, "torques"),
    ({"torques": [100.0], "phases": 7}, "phases"),
    ({"torques": [100.0], "phases": 8.5}, "phases"),
])
def test_bad_input_is_named(contact, compliance, kwargs, key):
    with pytest.raises(ValueError, match=key):
        fe_load_range(contact, compliance, **kwargs)


def test_largest_principal_over_points_is_the_full_maximum():
    """The bounds leave out only points that cannot hold a row's maximum: the same
    value to the last bit, in tension, compression and with repeated eigenvalues."""
    rng = np.random.default_rng(7)
    stress = rng.standard_normal((40, 300, 3, 3)) * 1e8
    stress = stress + np.swapaxes(stress, -1, -2)
    stress[:10] -= 5e8 * np.eye(3)               # rows in compression
    stress[10:20, :50] = np.diag([3e8, 3e8, -1e8])  # a repeated largest eigenvalue
    stress[20:30, 100:] *= 1e-3                   # most points nearly unloaded
    expected = largest_principal(stress).max(axis=1)
    assert np.array_equal(largest_principal_over_points(stress), expected)
