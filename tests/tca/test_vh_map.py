"""V-H maps: a small grid of two displacements, checked cell by cell.

A 3 x 3 map over P (-0.1, 0, +0.1 mm) and G (-0.05, 0, +0.05 mm) of the
crowned LSBG (G = -0.1 mm would close most of the 0.1 mm backlash by itself,
and with P = -0.1 mm the members interfere, which the map must refuse): its cells
must be the unloaded TCA and the loaded TCA run directly at those
displacements, the pattern's shifts are measured from the aligned cell, and
the sensitivities are the least-squares slopes through the aligned cell,
which for three evenly spaced values -h, 0, h is the central difference
(y(h) - y(-h)) / (2 h), times 0.1 mm. Bad axes, values and steps are rejected
naming ``misalignment_map``.
"""

import numpy as np
import pytest

from lsbg.tca import loaded as ltca
from lsbg.contact import ContactParameters, MeshContact
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.tca.analysis import tooth_contact_analysis
from lsbg.tca.misalignment import Misalignment
from lsbg.tca.modification import FlankModification
from lsbg.tca.separation import separation_field
from lsbg.tca.vh_map import MAP_GRID, SENSITIVITY_QUANTITIES, axis_values, misalignment_map

CROWNED = FlankModification(25e-6, 5e-6)
VALUES = ([-0.1, 0.0, 0.1], [-0.05, 0.0, 0.05])
POSITIONS, PHASES, LOAD = 60, 32, 500.0


@pytest.fixture(scope="module")
def pair():
    return GearPair(GearPairDesign.from_config(dict(trace="logarithmic", spiral_angle_deg=35)))


@pytest.fixture(scope="module")
def vh(pair):
    return misalignment_map(pair, CROWNED, axes=("P", "G"), values=VALUES, load_torque=LOAD,
                            positions=POSITIONS, phases=PHASES)


def test_dimensions_and_units(vh):
    for letter, values in zip(("P", "G"), VALUES):
        assert vh[letter].attrs["units"] == "mm"
        np.testing.assert_array_equal(vh[letter].values, values)
    for name, variable in vh.data_vars.items():
        assert variable.dims == ("P", "G"), name
        assert "units" in variable.attrs and variable.attrs["long_name"], name
        assert np.all(np.isfinite(variable.values)), name


def test_cells_are_the_direct_analyses(pair, vh):
    for p, g in ((0.1, 0.0), (0.0, -0.05), (-0.1, 0.05)):
        shift = Misalignment(pinion_axial=p * 1e-3, gear_axial=g * 1e-3)
        direct = tooth_contact_analysis(pair, CROWNED, shift, POSITIONS, grid=MAP_GRID)
        cell = vh.sel(P=p, G=g)
        assert float(cell.pattern_cone_distance) == pytest.approx(
            direct.attrs["pattern_centre_cone_distance_mm"], rel=1e-12)
        assert float(cell.transmission_error_unloaded_pp) == pytest.approx(
            direct.attrs["transmission_error_peak_to_peak_urad"], rel=1e-12)
        contact = MeshContact(pair, ContactParameters(model="line"),
                              separation=separation_field(pair, CROWNED, shift))
        loaded = ltca.loaded_tca(contact, LOAD, PHASES)
        assert float(cell.transmission_error_loaded_pp) == pytest.approx(
            loaded.attrs["transmission_error_peak_to_peak_urad"], rel=1e-12)


def test_shifts_are_measured_from_the_aligned_cell(vh):
    for name in ("pattern_shift_lengthwise", "pattern_shift_profile"):
        assert float(vh[name].sel(P=0.0, G=0.0)) == 0.0
    np.testing.assert_allclose(vh.pattern_shift_lengthwise,
                               vh.pattern_cone_distance - vh.pattern_cone_distance.sel(P=0, G=0),
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(vh.pattern_shift_profile,
                               vh.pattern_height - vh.pattern_height.sel(P=0, G=0),
                               rtol=0, atol=1e-12)
    # the LSBG's pattern moves towards the heel when the pinion backs out
    assert float(vh.pattern_shift_lengthwise.sel(P=0.1, G=0.0)) > 0.5
    assert float(vh.pattern_shift_lengthwise.sel(P=-0.1, G=0.0)) < -0.5


def test_sensitivities_are_the_central_differences(vh):
    for letter, other, h in (("P", "G", 0.1), ("G", "P", 0.05)):
        for name in SENSITIVITY_QUANTITIES:
            key = f"{name}_per_0_1_{letter}"
            line = vh[name].sel({other: 0.0})
            expected = (float(line.sel({letter: h})) - float(line.sel({letter: -h}))) / (2 * h) * 0.1
            assert vh.attrs[key] == pytest.approx(expected, rel=1e-9, abs=1e-12), key
    shift = float(vh.pattern_shift_lengthwise.sel(P=0.1, G=0.0))
    assert np.sign(vh.attrs["pattern_shift_lengthwise_per_0_1_P"]) == np.sign(shift)


@pytest.mark.parametrize("kwargs", [
    dict(axes=("P", "P")),
    dict(axes=("X", "G")),
    dict(axes=("P",)),
    dict(values=([-0.1, 0.1], [-0.1, 0.0, 0.1])),
    dict(values=([-0.1, 0.0, 0.1], [0.05, 0.1])),
])
def test_bad_map_is_rejected(pair, kwargs):
    arguments = dict(axes=("P", "G"), values=VALUES, positions=8, phases=8)
    arguments.update(kwargs)
    with pytest.raises(ValueError, match="misalignment_map"):
        misalignment_map(pair, CROWNED, **arguments)


def test_an_interfering_cell_is_refused(pair):
    """P = G = -0.1 mm: both members pushed into mesh close the backlash. Each
    axial shift moves the flanks into depth by its share along the pitch
    cones' normal, and both flanks close by sin(alpha_n) of it: 2 x 0.1 mm x
    sin 20 deg x (cos 13.7 + sin 13.7 deg) = 0.083 mm, more than the normal
    backlash 0.1 mm x cos 20 deg x cos 35 deg = 0.077 mm."""
    with pytest.raises(ValueError, match=r"misalignment_map: P = -0\.1, G = -0\.1: .*interfere"):
        misalignment_map(pair, CROWNED, axes=("P", "G"), values=([-0.1, 0.0], [-0.1, 0.0]),
                         positions=16, phases=8)


def test_axis_values():
    np.testing.assert_allclose(axis_values(0.1, 5), [-0.1, -0.05, 0.0, 0.05, 0.1], atol=1e-15)
    assert 0.0 in axis_values(0.2, 3)
    for steps in (4, 2, 1, 0, 3.5, True):
        with pytest.raises(ValueError, match="misalignment_map.steps"):
            axis_values(0.1, steps)
    for half in (0.0, -0.1, float("nan")):
        with pytest.raises(ValueError, match="misalignment_map.range"):
            axis_values(half, 3)
