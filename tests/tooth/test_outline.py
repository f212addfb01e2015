"""The FE segment's section outlines and their root fillets (lsbg.tooth.outline)."""

import math

import numpy as np
import pytest

from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.tooth.outline import ARC_POINTS, round_corners, segment_sections


def rotation_x(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def straight_corner(angle, tilt, radius=1e3, length=4e-3, points=9):
    """Two straight pieces meeting at angle ``angle`` at the pole of a huge sphere
    (flat to 1e-8 m over their length), and the corner line tilted by ``tilt``
    from the sphere's normal about the first piece's direction."""
    corner = np.array([0.0, 0.0, radius])
    s = np.linspace(0.0, length, points)[:, None]
    first = corner + s * np.array([1.0, 0.0, 0.0])
    second = corner + s * np.array([math.cos(angle), math.sin(angle), 0.0])
    spine = rotation_x(tilt) @ np.array([0.0, 0.0, 1.0])
    return first, second, spine


@pytest.mark.parametrize("angle_deg, tilt_deg", [(90, 0), (110, 0), (70, 0), (90, 35), (115, 45)])
def test_a_straight_corner_gets_the_circle_of_radius_rho_in_the_plane_normal_to_its_line(
        angle_deg, tilt_deg):
    rho = 0.8e-3
    first, second, spine = straight_corner(math.radians(angle_deg), math.radians(tilt_deg))
    pieces = round_corners([first[::-1], second], [0], spine[None], 1e3, rho)
    assert len(pieces) == 3
    arc = pieces[1]
    assert arc.shape == (ARC_POINTS, 3)
    # shared end points: the pieces stay one chain
    assert np.array_equal(pieces[0][-1], arc[0]) and np.array_equal(arc[-1], pieces[2][0])
    # seen along the corner line: a circle of radius rho tangent to both lines
    b1 = np.cross(spine, [0.0, 1.0, 0.0])
    b1 /= np.linalg.norm(b1)
    b2 = np.cross(spine, b1)
    corner = first[0]
    flat = (arc - corner) @ np.stack([b1, b2]).T
    lines = [(p[-1] - corner) @ np.stack([b1, b2]).T for p in (first, second)]
    units = [v / np.linalg.norm(v) for v in lines]
    theta = math.acos(units[0] @ units[1])
    bisector = (units[0] + units[1]) / np.linalg.norm(units[0] + units[1])
    centre = bisector * rho / math.sin(theta / 2)  # the closed form
    assert np.linalg.norm(flat - centre, axis=1) == pytest.approx(rho, rel=2e-3)
    # its ends on the lines, at rho / tan(theta / 2) from the corner
    for end, unit in ((flat[0], units[0]), (flat[-1], units[1])):
        assert abs(end[0] * unit[1] - end[1] * unit[0]) < 1e-3 * rho
        assert np.linalg.norm(end) == pytest.approx(rho / math.tan(theta / 2), rel=5e-3)
    # on the section's sphere
    assert np.linalg.norm(arc, axis=1) == pytest.approx(1e3, abs=1e-9)
    # the neighbours lose the points the fillet covers, and keep the rest
    assert pieces[0].shape[0] < first.shape[0] and pieces[2].shape[0] < second.shape[0]


def test_a_gap_too_narrow_for_its_two_fillets_is_an_error():
    """A root 1.5 mm wide between two square corners holds two fillets of
    0.7 mm (1.4 mm), not of 0.8 mm."""
    top = np.array([0.0, 0.0, 1e3])
    s = np.linspace(0.0, 1.0, 9)[:, None]
    flank_a = top + (1 - s) * np.array([0.0, 4e-3, 0.0])
    root = top + s * np.array([1.5e-3, 0.0, 0.0])
    flank_b = top + np.array([1.5e-3, 0.0, 0.0]) + s * np.array([0.0, 4e-3, 0.0])
    spines = np.array([[0.0, 0.0, 1.0]] * 2)
    pieces = round_corners([flank_a, root, flank_b], [0, 1], spines, 1e3, 0.7e-3)
    assert len(pieces) == 5 and pieces[2].shape[0] == 2  # the root's middle: ends only
    with pytest.raises(ValueError, match=r"rho = 0\.8 mm reaches past a 1\.5 mm piece"):
        round_corners([flank_a, root, flank_b], [0, 1], spines, 1e3, 0.8e-3)


@pytest.fixture(scope="module")
def pairs():
    return {spiral: GearPair(GearPairDesign.from_config({"spiral_angle_deg": spiral}))
            for spiral in (20, 35, 45)}


@pytest.mark.parametrize("spiral", [20, 35, 45])
@pytest.mark.parametrize("member", [1, 2])
def test_segment_outlines_over_the_sweep(pairs, spiral, member):
    """Over the sweep's range (where OCC's own fillet failed: the pinion at
    20-32.5 deg, the gear at 42.5-45 deg) every section gets its four fillets,
    tangent to both neighbours, on the sphere, the outline a chain in
    increasing azimuth from the middle of one gap's root to another's."""
    pair = pairs[spiral]
    d = pair.design
    rho = 0.25 * d.mean_module * math.cos(d.spiral_angle)
    radii, outlines = segment_sections(pair, member, 7, rho)
    z = d.teeth[member - 1]
    for radius, pieces in zip(radii, outlines):
        for a, b in zip(pieces[:-1], pieces[1:]):
            assert np.array_equal(a[-1], b[0])
        chain = np.concatenate([p[:-1] for p in pieces] + [pieces[-1][-1:]])
        assert np.linalg.norm(chain, axis=1) == pytest.approx(radius, rel=1e-9)
        azimuth = np.unwrap(pair.azimuth(member, chain))
        # seven teeth and the two half gaps: seven pitches
        assert azimuth[-1] - azimuth[0] == pytest.approx(7 * 2 * math.pi / z, rel=1e-6)
        # ends on the root cone
        root = d.root_angle(member)
        axis = pair.axis[member]
        for end in (chain[0], chain[-1]):
            assert math.acos(end @ axis / radius) == pytest.approx(root, abs=1e-9)
        # the fillet arcs: ARC_POINTS each, tangent to their neighbours (the
        # chord directions at the joins agree to a few degrees)
        arcs = [k for k, p in enumerate(pieces) if p.shape[0] == ARC_POINTS
                and np.ptp(np.linalg.norm(p - p.mean(axis=0), axis=1)) < rho]
        assert len(arcs) >= 4
        for k in arcs[:4]:
            # the rounded corner advances in azimuth from the root to the flank
            # or back, without a turn (to 2 um: the interpolating spline through a
            # pinion's radial extension and involute, on which the tangent point
            # lies as on the loft, strays ~1 um from the extension's plane)
            around = np.concatenate([pieces[k - 1][-2:-1], pieces[k], pieces[k + 1][1:2]])
            steps = np.diff(np.unwrap(pair.azimuth(member, around))) * radius * math.sin(root)
            assert np.all(steps >= -2e-6) or np.all(steps <= 2e-6)
            for joint, before, after in ((pieces[k][0], pieces[k - 1][-2], pieces[k][1]),
                                         (pieces[k][-1], pieces[k][-2], pieces[k + 1][1])):
                u, v = joint - before, after - joint
                turn = math.degrees(math.acos(u @ v / np.linalg.norm(u) / np.linalg.norm(v)))
                assert turn < 20  # the arc's own chords turn by up to ~15 deg a step
