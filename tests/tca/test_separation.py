"""The line model on real flanks: the separation field on the conjugate contact lines.

The loaded TCA of the line model (:func:`lsbg.tca.loaded.loaded_tca`) subtracts the
initial separation of the flanks from each slice's approach. Checked here:

* conjugate, aligned flanks give no field, and the line model is then exactly
  what it was without one;
* a vanishing modification changes nothing measurable (the field is
  switched on, but its values are zero);
* on an aligned pair the field on the conjugate lines is the relief itself
  (the modification's polynomial at the line's ease-off coordinates);
* at zero load the line model's first touch reproduces the transmission
  error the surface TCA finds from the exact flanks, crowned or displaced
  into mesh (two independent computations of the same quantity);
* crowning localizes the loaded pattern away from the flank's edges.
"""

import numpy as np
import pytest

from lsbg.tca import loaded as ltca
from lsbg.contact import ContactParameters, MeshContact
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.tca.analysis import tooth_contact_analysis
from lsbg.tca.misalignment import Misalignment
from lsbg.tca.modification import FlankModification, field_profile_coordinate, lengthwise_coordinate
from lsbg.tca.separation import separation_field

LOAD = 1964.99
LINE = ContactParameters(model="line")
CROWNED = FlankModification(25e-6, 5e-6)
PHASES = 60


@pytest.fixture(scope="module", params=["logarithmic", "circular", "face_milled"])
def pair(request):
    return GearPair(GearPairDesign.from_config(dict(trace=request.param, spiral_angle_deg=35)))


@pytest.fixture(scope="module")
def conjugate(pair):
    return MeshContact(pair, LINE)


@pytest.fixture(scope="module")
def crowned(pair):
    return MeshContact(pair, LINE, separation=separation_field(pair, CROWNED))


def test_no_field_for_conjugate_aligned_flanks(pair, conjugate):
    assert separation_field(pair) is None
    assert separation_field(pair, FlankModification(), Misalignment()) is None
    explicit = MeshContact(pair, LINE, separation=None)
    for a, b in zip(explicit.arrays, conjugate.arrays):
        np.testing.assert_array_equal(a, b)
    one = ltca.loaded_tca(explicit, LOAD, phases=16)
    other = ltca.loaded_tca(conjugate, LOAD, phases=16)
    np.testing.assert_array_equal(one.transmission_error.values, other.transmission_error.values)
    np.testing.assert_array_equal(one.mesh_stiffness.values, other.mesh_stiffness.values)


def test_a_vanishing_modification_changes_nothing(pair, conjugate):
    tiny = MeshContact(pair, LINE, separation=separation_field(pair, FlankModification(1e-15)))
    assert tiny.separation is not None
    with_field = ltca.loaded_tca(tiny, LOAD, phases=32)
    without = ltca.loaded_tca(conjugate, LOAD, phases=32)
    for key in ("transmission_error_peak_to_peak_urad", "transmission_error_mean_urad",
                "mesh_stiffness_mean_N_per_um"):
        assert with_field.attrs[key] == pytest.approx(without.attrs[key], rel=0.01), key


def test_field_on_the_lines_is_the_relief(pair):
    """Aligned: the separation at a point of a conjugate line is the relief at
    its ease-off coordinates, u from the cone distance and v from the line's
    polar angle psi = Psi + theta_c(rho) in the plane of action."""
    modification = FlankModification(25e-6, 5e-6, 3e-6)
    separation = separation_field(pair, modification)
    design, plane = pair.design, pair.planes["drive"]
    turns = np.linspace(-0.3, 0.3, 121)
    checked = 0
    for rho in np.linspace(design.inner_cone_distance, design.outer_cone_distance, 5):
        psi = turns + plane.curve.polar_angle(rho)
        v = field_profile_coordinate(plane, psi)
        inside = np.abs(v) <= 1.0
        expected = modification.relief(lengthwise_coordinate(design, rho), v[inside])
        got = separation(turns[inside], rho)
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-8)
        checked += inside.sum()
    assert checked > 100
    # the relief is not small against the tolerance
    assert modification.largest_relief() > 3e-5


@pytest.fixture(scope="module")
def unloaded(pair, crowned):
    return ltca.loaded_tca(crowned, 0.0, phases=PHASES)


@pytest.fixture(scope="module")
def surface_tca(pair):
    return tooth_contact_analysis(pair, CROWNED, positions=PHASES)


def test_line_model_first_touch_is_the_surface_tca(unloaded, surface_tca):
    # mesh_phase of the loaded TCA is a fraction of a base pitch, one mesh
    # cycle: both start at pinion angle 0 and step alike
    np.testing.assert_allclose(unloaded.pinion_angle.values, surface_tca.pinion_angle.values,
                               rtol=1e-12, atol=1e-12)
    line, exact = unloaded.transmission_error.values, surface_tca.transmission_error.values
    assert np.ptp(exact) > 10  # urad: a real parabola
    assert np.ptp(line) == pytest.approx(np.ptp(exact), rel=0.05)
    assert line.mean() == pytest.approx(exact.mean(), rel=0.05)
    # the same curve, position by position
    assert np.abs(line - exact).max() < 0.1 * np.ptp(exact)
    assert int(np.argmax(line)) == pytest.approx(int(np.argmax(exact)), abs=2)


def test_into_mesh_interference(pair):
    shift = Misalignment(pinion_axial=-1e-4)
    contact = MeshContact(pair, LINE, separation=separation_field(pair, CROWNED, shift))
    unloaded = ltca.loaded_tca(contact, 0.0, phases=32)
    exact = tooth_contact_analysis(pair, CROWNED, shift, positions=32)
    te = unloaded.transmission_error.values
    assert np.all(np.isfinite(te))
    assert te.mean() < -100  # urad: the gear leads, the flanks interfere
    assert te.mean() == pytest.approx(exact.transmission_error.values.mean(), rel=0.05)
    loaded = ltca.loaded_tca(contact, LOAD, phases=32)
    assert np.all(np.isfinite(loaded.transmission_error.values))
    # the load adds its elastic approach: the gear lags more than unloaded
    assert np.all(loaded.transmission_error.values > te)


def test_crowning_localizes_the_loaded_pattern(crowned, conjugate):
    light = ltca.loaded_tca(crowned, 100.0, phases=32)
    reference = ltca.loaded_tca(conjugate, 100.0, phases=32)
    assert light.attrs["loaded_pattern_length_per_face_width"] < 1.0
    assert reference.attrs["loaded_pattern_length_per_face_width"] == pytest.approx(1.0)
    assert light.attrs["edge_load_share"] < reference.attrs["edge_load_share"]


def test_a_grids_separations_are_each_points_own(pair):
    """The kernel builds a row's pinion rotation once for the row's points: each point's
    separation is the one it gets alone, bit for bit, whatever its neighbours' angles."""
    from lsbg.tca import surface

    captured = []
    kernel = surface.point_separations

    def keep(*args):
        captured.append(args)
        return kernel(*args)

    field = separation_field(pair, CROWNED, Misalignment(offset=20e-6))
    surface.point_separations = keep
    try:
        field(np.linspace(-0.2, 0.2, 5)[:, None], np.linspace(0.064, 0.082, 4)[None, :])
    finally:
        surface.point_separations = kernel
    angles, points, normals, g = captured[0]
    assert angles.size == 20 and np.unique(angles).size == 5     # rows of equal angles
    together = kernel(angles, points, normals, g)
    alone = [kernel(angles[i:i + 1], points[i:i + 1], normals[i:i + 1], g)[0]
             for i in range(angles.size)]
    assert np.isfinite(together).all()
    np.testing.assert_array_equal(together, alone)
    # and column by column, where every angle differs from the one before
    order = np.arange(20).reshape(5, 4).T.ravel()
    np.testing.assert_array_equal(
        kernel(angles[order], points[order], normals[order], g), together[order])
