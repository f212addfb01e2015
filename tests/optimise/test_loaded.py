"""The line model's loaded points are loaded_tca's equilibrium, point by point."""

import numpy as np
import pytest

from lsbg.contact import ContactParameters, MeshContact
from lsbg.optimise.loaded import MeshPoints, SeparationCache, loaded_points, mesh_points
from lsbg.tca.loaded import loaded_tca
from lsbg.tca.misalignment import Misalignment
from lsbg.tca.modification import FlankModification
from lsbg.tca.separation import separation_field
from lsbg.tooth.contact_points import contact_points

from tests.optimise.conftest import RATED

CROWNED = FlankModification(lengthwise_crowning=25e-6, profile_crowning=5e-6)
DISPLACED = Misalignment(offset=-5e-5, pinion_axial=1e-4)
LINE = ContactParameters(model="line")


@pytest.fixture(scope="module")
def contact(pairs):
    pair = pairs["logarithmic"]
    return MeshContact(pair, LINE, separation=separation_field(pair, CROWNED, DISPLACED))


def test_transmission_error_is_loaded_tcas_bit_for_bit(contact):
    state = loaded_points(contact, [0.5 * RATED, RATED], 16)
    reference = loaded_tca(contact, RATED, 16)
    np.testing.assert_array_equal(state.transmission_error[1] * 1e6,
                                  reference["transmission_error"].values)


def test_point_loads_carry_the_torque(contact):
    state = loaded_points(contact, [0.5 * RATED, RATED, 1.5 * RATED], 16)
    carried = state.carried_torque() / state.torque[:, None]
    # the kernel interpolates the separation from its table, the points take it exactly
    np.testing.assert_allclose(carried, 1.0, atol=2e-3)


def test_points_are_the_fe_ltcas_contact_points(contact):
    points = mesh_points(contact, [0.0, 0.013])
    for n, phi1 in enumerate(points.pinion_angle):
        expected = contact_points(contact, contact.orientation * phi1 * contact.e1)
        inside = points.inside[n]
        order, mine = np.argsort(expected.rho), np.argsort(points.rho[n][inside])
        np.testing.assert_allclose(points.rho[n][inside][mine], expected.rho[order], rtol=1e-14)
        np.testing.assert_allclose(points.separation[n][inside][mine],
                                   expected.separation[order], rtol=1e-12, atol=1e-18)
        np.testing.assert_array_equal(np.sort(points.edge[n][inside]), np.sort(expected.edge))


def test_separation_cache_gives_the_separation_fields_table(pairs):
    pair = pairs["circular"]
    modification = FlankModification(lengthwise_crowning=30e-6, profile_crowning=8e-6,
                                     bias=3e-6, gear_tip_relief=10e-6,
                                     spiral_angle_correction=-4e-6)
    cache = SeparationCache(pair)
    for misalignment in (Misalignment(), DISPLACED):
        exact = MeshContact(pair, LINE, separation=separation_field(pair, modification,
                                                                    misalignment))
        cached = MeshContact(pair, LINE, separation=cache.field(modification, misalignment))
        np.testing.assert_array_equal(cached.arrays[2], exact.arrays[2])
    assert cache.field(FlankModification(), Misalignment()) is None


def test_conjugate_flanks_just_touching_have_no_transmission_error(pairs):
    state = loaded_points(MeshContact(pairs["logarithmic"], LINE), [0.0], 8)
    assert np.abs(state.transmission_error).max() < 1e-12
    assert not np.any(state.line_load)


def test_bad_input_is_refused(pairs, contact):
    with pytest.raises(ValueError, match="line model"):
        loaded_points(MeshContact(pairs["logarithmic"]), [RATED], 8)
    with pytest.raises(ValueError, match="phases = 2"):
        loaded_points(contact, [RATED], 2)
    with pytest.raises(ValueError, match="torques"):
        loaded_points(contact, [-1.0], 8)


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def test_contacts_with_a_separation_are_built_ones_bit_for_bit(pairs):
    pair = pairs["circular"]
    conjugate = MeshContact(pair, LINE)
    cache = SeparationCache(pair)
    for modification in (CROWNED, FlankModification(profile_crowning=6e-6, bias=4e-6)):
        for misalignment in (Misalignment(), DISPLACED):
            field = cache.field(modification, misalignment)
            built = MeshContact(pair, LINE, separation=field)
            shared = conjugate.with_separation(field)
            assert all(same_bits(a, b) for a, b in zip(shared.arrays, built.arrays))
            assert shared.separation is field
    assert all(same_bits(a, b) for a, b in zip(conjugate.with_separation(None).arrays,
                                               conjugate.arrays))
    with pytest.raises(ValueError, match="line model"):
        MeshContact(pair).with_separation(None)


def test_separation_cache_is_keyed_on_the_design_and_the_displacement(pairs):
    pair = pairs["logarithmic"]
    turn = np.linspace(-0.3, 0.3, 7)[:, None]
    rho = np.linspace(0.062, 0.084, 5)[None, :]
    used = SeparationCache(pair)  # keeps the grid and each design's relieved points
    for modification in (FlankModification(bias=5e-6), CROWNED):
        for misalignment in (Misalignment(), DISPLACED):
            kept = used.field(modification, misalignment)(turn, rho)
            afresh = SeparationCache(pair).field(modification, misalignment)(turn, rho)
            assert same_bits(kept, afresh)
            exact = separation_field(pair, modification, misalignment)(turn, rho)
            np.testing.assert_allclose(kept, exact, rtol=0, atol=1e-15)


def test_points_from_a_layout_are_the_contacts_own(pairs, contact):
    angles = [0.0, 0.013]
    layout = mesh_points(MeshContact(pairs["logarithmic"], LINE), angles)
    direct, shared = mesh_points(contact, angles), mesh_points(contact, angles, layout)
    for name in MeshPoints.__dataclass_fields__:
        assert same_bits(getattr(shared, name), getattr(direct, name)), name
    with pytest.raises(ValueError, match="other pinion rotations"):
        mesh_points(contact, [0.0], layout)
