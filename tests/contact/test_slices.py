"""The line model's slice stiffness (the tooth's own compliance in the kernels): a table of
ones is the uniform bed, a uniform factor scales the static approach exactly, the damping
ratio is kept, and bad tables are refused."""

import math

import numpy as np
import pytest

from lsbg.tca import loaded as ltca
from lsbg.contact import ContactParameters, MeshContact
from lsbg.contact import kernels as k
from lsbg.contact.slices import SliceStiffness
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair

LOAD = 1964.99
LINE = ContactParameters(model="line")


@pytest.fixture(scope="module")
def pair():
    return GearPair(GearPairDesign(trace="logarithmic"))


def table(contact, factor, rows=64):
    """A slice-stiffness table over the whole range of line turns, ``factor`` x k_l,
    on cone distances beyond the bands (held at the ends)."""
    sides = contact.arrays[1]
    first, last = sides[0, k.S_FIRST], sides[0, k.S_LAST]
    turns = np.linspace(first - 0.01, last + 0.01, rows)
    design = contact.pair.design
    rho = np.linspace(design.inner_cone_distance, design.outer_cone_distance, 5)
    value = np.broadcast_to(np.asarray(factor, float), (rows, rho.size))
    return SliceStiffness(turns, rho, value * LINE.line_stiffness, {"compliance": "fe"})


def test_a_table_of_ones_is_the_uniform_bed(pair):
    uniform = MeshContact(pair, LINE)
    ones = MeshContact(pair, LINE, slice_stiffness=table(uniform, 1.0))
    a = ltca.loaded_tca(uniform, LOAD, phases=32)
    b = ltca.loaded_tca(ones, LOAD, phases=32)
    np.testing.assert_allclose(b.transmission_error, a.transmission_error, rtol=1e-12)
    np.testing.assert_allclose(b.mesh_stiffness, a.mesh_stiffness, rtol=1e-9)
    assert ones.mean_torsional_stiffness() == pytest.approx(uniform.mean_torsional_stiffness(),
                                                            rel=1e-12)


def test_twice_the_stiffness_halves_the_static_approach_of_conjugate_flanks(pair):
    """Linear slices on conjugate flanks: the approach that carries a torque is
    inversely proportional to the stiffness, slice by slice."""
    uniform = MeshContact(pair, LINE)
    double = MeshContact(pair, LINE, slice_stiffness=table(uniform, 2.0))
    for pinion in (0.0, 0.013, 0.031):
        g1 = uniform.static_gear_angle(LOAD, pinion)
        g2 = double.static_gear_angle(LOAD, pinion)
        base = pinion * uniform.e1 / uniform.e2
        assert (g2 - base) == pytest.approx(0.5 * (g1 - base), rel=1e-9)
    assert double.mean_mesh_stiffness() == pytest.approx(2 * uniform.mean_mesh_stiffness(),
                                                         rel=1e-12)


def test_the_damping_ratio_is_kept(pair):
    """Stiffness-proportional damping: the slices' c / k over the mesh mode's
    natural frequency gives the configured damping ratio at the FE mean stiffness."""
    inertia = 0.05
    for factor in (1.0, 0.7, 2.5):
        contact = MeshContact(pair, LINE, gear_inertia=inertia,
                              slice_stiffness=table(MeshContact(pair, LINE), factor))
        omega = 2 * math.pi * contact.natural_frequency(inertia)
        # slice: load = f (k_l x + c x_dot): its damping ratio is c omega / (2 k_l)
        zeta = contact.damping_coefficient * omega / (2 * LINE.line_stiffness)
        assert zeta == pytest.approx(LINE.damping_ratio, rel=1e-12)


def test_a_varying_table_is_interpolated_in_the_line_turn(pair):
    """A factor that grows with the line's turn: a slice's load follows the table at
    the line's turn (the kernel's linear interpolation between rows)."""
    uniform = MeshContact(pair, LINE)
    sides = uniform.arrays[1]
    first, last = sides[0, k.S_FIRST], sides[0, k.S_LAST]
    turns = np.linspace(first, last, 41)
    design = pair.design
    rho = np.array([design.inner_cone_distance, design.outer_cone_distance])
    factor = 1.0 + (turns - first) / (last - first)
    ramp = SliceStiffness(turns, rho, np.outer(factor, [1.0, 1.0]) * LINE.line_stiffness)
    varying = MeshContact(pair, LINE, slice_stiffness=ramp)
    pinion = 0.0
    gear = uniform.static_gear_angle(LOAD, pinion)
    pairs_u, loads_u = uniform.pair_contacts(pinion, gear, slice_loads=True)
    pairs_v, loads_v = varying.pair_contacts(pinion, gear, slice_loads=True)
    for pu, lu, lv in zip(pairs_u, loads_u, loads_v):
        if pu.side != "drive":
            continue
        expected = np.interp(pu.phase, turns, factor)
        on = lu > 0
        np.testing.assert_allclose(lv[on] / lu[on], expected, rtol=1e-9)


def test_bad_tables_are_refused(pair):
    rho = np.array([0.1, 0.12])
    good = np.full((3, 2), 2e10)
    with pytest.raises(ValueError, match="evenly spaced"):
        SliceStiffness(np.array([0.0, 0.1, 0.3]), rho, good)
    with pytest.raises(ValueError, match="finite and > 0"):
        SliceStiffness(np.array([0.0, 0.1, 0.2]), rho, np.where(good > 0, -1.0, 0.0))
    with pytest.raises(ValueError, match="shape"):
        SliceStiffness(np.array([0.0, 0.1, 0.2]), rho, good[:, :1])
    with pytest.raises(ValueError, match="line model"):
        MeshContact(pair, ContactParameters(), slice_stiffness=table(MeshContact(pair, LINE), 1))
