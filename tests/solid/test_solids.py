"""Solid gears: section outlines, watertight meshes, mass properties, URDF in PyBullet."""

import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy import integrate

from lsbg.solid import mass, outline, solids
from lsbg.solid.urdf import write_urdf
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.gear.vectors import rotate

MEMBERS = (1, 2)


@pytest.fixture(scope="module", params=["logarithmic", "circular"])
def built(request):
    """A pair with both meshes and both kinds of mass properties, built once."""
    pair = GearPair(GearPairDesign(trace=request.param))
    meshes = solids.gear_meshes(pair)
    return SimpleNamespace(
        pair=pair, meshes=meshes,
        props={m: mass.mass_properties(meshes[m], pair, m) for m in MEMBERS},
        quad={m: mass.quadrature_mass_properties(pair, m) for m in MEMBERS})


@pytest.fixture(scope="module")
def lsbg_pair():
    return GearPair(GearPairDesign())


def pitch_crossings(pair, member, outline_row_polar, outline_row_azimuth):
    """Azimuths where the outline crosses the pitch cone, rising and falling."""
    theta = np.append(outline_row_polar, outline_row_polar[0])
    phi = np.append(outline_row_azimuth, outline_row_azimuth[0] + 2 * np.pi)
    s = theta - pair.design.pitch_angle(member)
    i = np.flatnonzero(np.sign(s[:-1]) != np.sign(s[1:]))
    at = phi[i] + s[i] / (s[i] - s[i + 1]) * (phi[i + 1] - phi[i])
    rising = s[i + 1] > s[i]
    return at[rising], at[~rising]


# ----------------------------------------------------------------- outlines
@pytest.mark.parametrize("member", MEMBERS)
def test_outline_is_a_closed_loop_by_azimuth_on_the_sphere(lsbg_pair, member):
    pair, d = lsbg_pair, lsbg_pair.design
    radii = np.array([d.inner_cone_distance, d.mean_cone_distance, d.outer_cone_distance])
    out = outline.section_outline(pair, member, radii)
    z = d.teeth[member - 1]
    assert out.points.shape == (3, z * out.per_tooth, 3)
    norm = np.linalg.norm(out.points, axis=-1)
    np.testing.assert_allclose(norm, np.broadcast_to(radii[:, None], norm.shape), rtol=1e-14)
    # azimuth never decreases and spans one turn
    assert np.all(np.diff(out.azimuth, axis=1) >= 0)
    assert np.all(out.azimuth[:, -1] - out.azimuth[:, 0] < 2 * np.pi)
    # the stored coordinates are those of the points (GearPair.azimuth convention)
    wrapped = (pair.azimuth(member, out.points) - out.azimuth + np.pi) % (2 * np.pi) - np.pi
    assert np.max(np.abs(wrapped)) < 1e-12
    polar = np.arccos(out.points @ pair.axis[member] / norm)
    np.testing.assert_allclose(polar, out.polar_angle, atol=1e-7)
    # between root and tip cones
    assert out.polar_angle.min() == pytest.approx(d.root_angle(member), abs=1e-15)
    assert out.polar_angle.max() == pytest.approx(d.tip_angle(member), abs=1e-15)


@pytest.mark.parametrize("member", MEMBERS)
def test_outline_has_z_teeth_of_the_design_thickness(built, member):
    pair, d = built.pair, built.pair.design
    expected = d.mean_tooth_thickness(member) / d.mean_pitch_radius(member)
    for resolution, rtol in ((outline.DEFAULT_RESOLUTION, 5e-4),
                             (outline.MeshResolution(chord_tolerance=1e-9), 2e-6)):
        out = outline.section_outline(pair, member, d.mean_cone_distance, resolution)
        rising, falling = pitch_crossings(pair, member, out.polar_angle[0], out.azimuth[0])
        assert rising.size == falling.size == d.teeth[member - 1]
        np.testing.assert_allclose(falling - rising, expected, rtol=rtol)


@pytest.mark.parametrize("member", MEMBERS)
def test_outline_follows_the_exact_flanks(lsbg_pair, member):
    """Flank vertices are points of GearPair.flank, tooth j turned by 2 pi j / z."""
    pair, d = lsbg_pair, lsbg_pair.design
    out = outline.section_outline(pair, member, d.mean_cone_distance)
    z = d.teeth[member - 1]
    start, tip = pair.flank_polar_range(member)
    low, high = outline.side_order(pair, member)
    for j in (0, z - 1):
        tooth = slice(j * out.per_tooth, (j + 1) * out.per_tooth)
        polar, points = out.polar_angle[0, tooth], out.points[0, tooth]
        on_flank = np.flatnonzero(polar >= start)
        # first run of involute vertices belongs to the low side
        first = on_flank[: np.argmax(np.diff(on_flank) > 1) + 1]
        exact, _ = pair.flank(member, low, d.mean_cone_distance, polar[first])
        exact = rotate(exact, pair.rotation_axis[member], 2 * np.pi * j / z)
        assert np.max(np.linalg.norm(points[first] - exact, axis=1)) < 1e-12


def test_pinion_flank_continues_radially_below_the_base_cone(lsbg_pair):
    """The paper's pinion: base cone (12.47 deg) above the root cone (10.55 deg)."""
    pair, d = lsbg_pair, lsbg_pair.design
    assert d.base_cone_angle(1) > d.root_angle(1)
    out = outline.section_outline(pair, 1, d.mean_cone_distance)
    polar, phi = out.polar_angle[0, :out.per_tooth], out.azimuth[0, :out.per_tooth]
    below = polar < d.base_cone_angle(1) - 1e-12
    above_root = below & (polar > d.root_angle(1) + 1e-12)
    assert above_root.sum() >= 2 * outline.DEFAULT_RESOLUTION.extension - 2
    start = np.flatnonzero(np.isclose(polar, d.base_cone_angle(1), rtol=0, atol=1e-14))
    for k in start:   # each involute start sits on a meridian with its continuation
        same = np.isclose(phi, phi[k], rtol=0, atol=0)
        assert same.sum() == outline.DEFAULT_RESOLUTION.extension + 1
    # the gear's base cone lies below its root: no continuation
    assert d.base_cone_angle(2) < d.root_angle(2)


# ------------------------------------------------------------------- meshes
@pytest.mark.parametrize("member", MEMBERS)
def test_mesh_is_a_closed_solid_with_one_bore(built, member):
    mesh = built.meshes[member]
    assert mesh.is_watertight
    assert mesh.is_winding_consistent
    assert mesh.volume > 0
    assert mesh.euler_number == 0          # a torus: one through hole (the bore)
    assert mesh.body_count == 1
    assert 20_000 <= len(mesh.faces) <= 60_000
    d = built.pair.design
    r = np.linalg.norm(mesh.vertices, axis=1)
    assert r.min() >= d.inner_cone_distance * (1 - 1e-12)
    assert r.max() <= d.outer_cone_distance * (1 + 1e-12)


@pytest.mark.parametrize("member", MEMBERS)
def test_end_faces_face_away_from_the_solid(built, member):
    """No folded triangles on the end spheres: normals along +-r (slivers allowed)."""
    d, mesh = built.pair.design, built.meshes[member]
    r = np.linalg.norm(mesh.vertices, axis=1)[mesh.faces]
    centre = mesh.triangles_center / np.linalg.norm(mesh.triangles_center, axis=1)[:, None]
    radial = np.sum(mesh.face_normals * centre, axis=1)
    outer = np.all(np.abs(r - d.outer_cone_distance) < 1e-12, axis=1)
    inner = np.all(np.abs(r - d.inner_cone_distance) < 1e-12, axis=1)
    assert outer.sum() > 1000 and inner.sum() > 1000
    assert radial[outer].min() > 0.3
    assert (-radial[inner]).min() > 0.3


# ------------------------------------- vectorised end-face columns vs the loops
def _chain_zip_loop(left, left_polar, right, right_polar):
    """The per-pair reference (lsbg 21acaf0): one column at a time."""
    nl, nr = left.size, right.size
    keys = np.concatenate([left_polar[1:], right_polar[1:]])
    is_left = np.concatenate([np.ones(nl - 1, bool), np.zeros(nr - 1, bool)])
    step_l = is_left[np.argsort(keys, kind="stable")]
    i0 = np.cumsum(step_l) - step_l
    j0 = np.cumsum(~step_l) - ~step_l
    third = np.where(step_l, left[np.minimum(i0 + 1, nl - 1)], right[np.minimum(j0 + 1, nr - 1)])
    return np.stack([left[i0], right[j0], third], axis=1)


def _tooth_region_loop(index, polar, azimuth, root, step, new_points):
    """The loop reference (lsbg 21acaf0) of :func:`solids._tooth_region`."""
    starts = solids._line_starts(azimuth)
    ends = np.append(starts[1:], index.size)
    at_root = np.isclose(polar, root, rtol=0, atol=1e-12)
    lines, new_theta, new_phi, owner = [], [], [], []
    for g, (s, e) in enumerate(zip(starts, ends)):
        members = np.arange(s, e)
        lowest = members[np.argmin(polar[s:e])]
        levels = np.empty(0)
        if not at_root[lowest]:
            n = int(math.ceil((polar[lowest] - root) / step))
            levels = root + (polar[lowest] - root) * np.arange(n) / n
        new_theta.append(levels)
        new_phi.append(np.full(levels.size, azimuth[s]))
        owner.append(np.full(levels.size, g))
        lines.append(members)
    new_theta = np.concatenate(new_theta)
    added = new_points(new_theta, np.concatenate(new_phi))
    split = np.searchsorted(np.concatenate(owner), np.arange(len(lines) + 1))
    chains, chain_polar = [], []
    for g, members in enumerate(lines):
        extra = slice(split[g], split[g + 1])
        theta = np.concatenate([new_theta[extra], polar[members]])
        order = np.argsort(theta, kind="stable")
        chains.append(np.concatenate([added[extra], index[members]])[order])
        chain_polar.append(theta[order])
    faces = []
    for g in range(len(lines)):
        h = (g + 1) % len(lines)
        left = chain_polar[g] <= polar[ends[g] - 1]
        right = chain_polar[h] <= polar[starts[h]]
        if left.sum() > 1 or right.sum() > 1:
            faces.append(_chain_zip_loop(chains[g][left], chain_polar[g][left],
                                         chains[h][right], chain_polar[h][right]))
    return np.array([c[0] for c in chains]), np.concatenate(faces)


def _same(a, b):
    return a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b)


def test_chain_zip_zips_every_pair_as_the_loop_does():
    rng = np.random.default_rng(7)
    chains, polar, lengths = [], [], []
    for _ in range(60):
        n = int(rng.choice([1, 1, 2, 3, 7]))
        # coarse values: ties inside a chain and across chains
        polar.append(np.sort(rng.integers(0, 5, n)) * 0.25)
        chains.append(rng.integers(0, 10_000, n))
        lengths.append(n)
    start = np.cumsum(lengths) - lengths
    vertex, polar_all = np.concatenate(chains), np.concatenate(polar)
    left, right = rng.integers(0, 60, 200), rng.integers(0, 60, 200)
    count_l = np.array([rng.integers(1, lengths[g] + 1) for g in left])
    count_r = np.array([rng.integers(1, lengths[g] + 1) for g in right])
    faces = solids._chain_zip(vertex, polar_all, start[left], count_l, start[right], count_r)
    expected = np.concatenate([
        _chain_zip_loop(chains[g][:nl], polar[g][:nl], chains[h][:nr], polar[h][:nr])
        for g, h, nl, nr in zip(left, right, count_l, count_r)])
    assert _same(faces, expected)
    # a single pair, and a pair with one vertex on each side (no triangle)
    one = solids._chain_zip(vertex, polar_all, start[:1], count_l[:1], start[1:2], count_r[:1])
    assert _same(one, _chain_zip_loop(chains[0][:count_l[0]], polar[0][:count_l[0]],
                                      chains[1][:count_r[0]], polar[1][:count_r[0]]))
    assert solids._chain_zip(vertex, polar_all, *(np.array([0, 1, 0, 1][k:k + 1])
                                                  for k in range(4))).shape == (0, 3)


def _outlines(rng):
    """Outlines with meridians of several vertices, vertices on the root, ties."""
    root, step = 0.2, 0.03
    for trial in range(40):
        n_lines = int(rng.integers(1, 12))
        per_line = rng.integers(1, 5, n_lines)
        azimuth = np.repeat(np.sort(rng.choice(100, n_lines, replace=False)) * 0.05, per_line)
        height = rng.choice([0.0, 0.0, 1e-13, 0.015, 0.03, 0.06, 0.1, 0.1234567], azimuth.size)
        if trial % 2:  # arbitrary heights: rounding of the levels shows
            height = np.where(height > 1e-12, rng.uniform(0, 0.2, azimuth.size), height)
        polar = root + height
        index = rng.permutation(10_000)[:azimuth.size]
        yield index, polar, azimuth, root, step


def test_tooth_region_matches_the_loop_on_outlines_and_gears(lsbg_pair):
    rng = np.random.default_rng(11)
    cases = list(_outlines(rng))
    pair, d = lsbg_pair, lsbg_pair.design
    for member in MEMBERS:        # the pinion has the radial continuation
        radii = [d.inner_cone_distance, d.outer_cone_distance]
        out = outline.section_outline(pair, member, radii)
        for k in range(2):
            cases.append((np.arange(out.azimuth.shape[1]) + 50, out.polar_angle[k],
                          out.azimuth[k], d.root_angle(member), 0.03))
    for index, polar, azimuth, root, step in cases:
        results, made = [], []
        for region in (solids._tooth_region, _tooth_region_loop):
            calls = []

            def new_points(theta, phi):
                calls.append((theta, phi))
                return 20_000 + np.arange(theta.size)

            results.append(region(index, polar, azimuth, root, step, new_points))
            made.append(calls)
        (bottom, faces), (bottom_ref, faces_ref) = results
        assert len(made[0]) == len(made[1]) == 1
        assert all(_same(a, b) for a, b in zip(made[0][0], made[1][0]))
        assert _same(bottom, bottom_ref) and _same(faces, faces_ref)


# ---------------------------------------------------------- mass properties
@pytest.mark.parametrize("member", MEMBERS)
def test_mesh_mass_and_axial_inertia_match_the_quadrature(built, member):
    p, q = built.props[member], built.quad[member]
    assert p.mass == pytest.approx(q.mass, rel=5e-3)
    assert p.axial_inertia == pytest.approx(q.axial_inertia, rel=5e-3)
    # measured: the defaults keep the volume within 0.1 % (chords lie inside)
    assert -1e-3 < p.volume / q.volume - 1 < 0
    assert p.principal_moments[0] == pytest.approx(q.transverse_inertia, rel=5e-3)
    axial_com = p.centre_of_mass @ built.pair.axis[member]
    assert axial_com == pytest.approx(q.centre_of_mass_distance, rel=1e-3)


@pytest.mark.parametrize("member", MEMBERS)
def test_quadrature_is_converged(lsbg_pair, member):
    coarse = mass.quadrature_mass_properties(lsbg_pair, member)
    fine = mass.quadrature_mass_properties(lsbg_pair, member, n_radial=32, n_profile=96)
    assert coarse.mass == pytest.approx(fine.mass, rel=1e-10)
    assert coarse.axial_inertia == pytest.approx(fine.axial_inertia, rel=1e-10)


def cone_shell(design, member, polar, density):
    """Mass and axial inertia of the solid of revolution between the bore and
    the cone of half-angle ``polar``, cut by the spheres R_i and R_e (scipy)."""
    bore = (design.pinion_bore if member == 1 else design.gear_bore) / 2
    lo = lambda r: math.asin(bore / r)  # noqa: E731
    r_in, r_out = design.inner_cone_distance, design.outer_cone_distance
    volume = integrate.dblquad(lambda t, r: 2 * math.pi * r**2 * math.sin(t),
                               r_in, r_out, lo, lambda r: polar)[0]
    inertia = integrate.dblquad(lambda t, r: 2 * math.pi * r**4 * math.sin(t) ** 3,
                                r_in, r_out, lo, lambda r: polar)[0]
    return density * volume, density * inertia


@pytest.mark.parametrize("member", MEMBERS)
def test_mass_lies_between_root_and_tip_cone_solids(built, member):
    d, p = built.pair.design, built.props[member]
    m_root, i_root = cone_shell(d, member, d.root_angle(member), d.density)
    m_tip, i_tip = cone_shell(d, member, d.tip_angle(member), d.density)
    assert m_root < p.mass < m_tip
    assert i_root < p.axial_inertia < i_tip
    # teeth about as wide as the gaps on the pitch cone: about half the tooth band is full
    assert 0.3 < (p.mass - m_root) / (m_tip - m_root) < 0.7


def test_section_integral_lies_between_root_and_tip_caps(lsbg_pair):
    """On one sphere, the Green's-theorem area lies between the spherical caps
    of the root and tip cones (less the bore), about halfway."""
    d = lsbg_pair.design
    for member in MEMBERS:
        bore = (d.pinion_bore if member == 1 else d.gear_bore) / 2
        radius = d.mean_cone_distance
        area = mass.section_integrals(lsbg_pair, member, [radius])["volume"][0]
        t_b = math.asin(bore / radius)
        root = 2 * math.pi * (math.cos(t_b) - math.cos(d.root_angle(member)))
        tip = 2 * math.pi * (math.cos(t_b) - math.cos(d.tip_angle(member)))
        assert 0.3 < (area - root) / (tip - root) < 0.7


@pytest.mark.parametrize("member", MEMBERS)
def test_centre_of_mass_on_the_axis(built, member):
    pair, p = built.pair, built.props[member]
    off_axis = p.centre_of_mass - (p.centre_of_mass @ pair.axis[member]) * pair.axis[member]
    assert np.linalg.norm(off_axis) < 1e-6
    # principal frame: z along the rotation axis, the tensor diagonal there
    axes = p.principal_axes
    np.testing.assert_allclose(axes.T @ axes, np.eye(3), atol=1e-15)
    assert np.linalg.det(axes) == pytest.approx(1.0)
    np.testing.assert_allclose(axes[:, 2], pair.rotation_axis[member])
    local = axes.T @ p.inertia @ axes
    assert np.max(np.abs(local - np.diag(np.diag(local)))) < 1e-6 * p.axial_inertia
    assert p.axial_inertia == pytest.approx(p.principal_moments[2], rel=1e-12)


# --------------------------------------------------------------------- URDF
@pytest.fixture(scope="module")
def urdf(built, tmp_path_factory):
    out = tmp_path_factory.mktemp(f"urdf_{built.pair.design.trace}")
    files = {}
    for member in MEMBERS:
        files[member] = out / f"{member}.obj"
        built.meshes[member].export(files[member])
    return write_urdf(out / "pair.urdf", built.pair, built.props, files)


def test_urdf_loads_in_pybullet_with_the_mesh_inertia(built, urdf):
    p = pytest.importorskip("pybullet")
    client = p.connect(p.DIRECT)
    try:
        body = p.loadURDF(str(urdf), useFixedBase=True, flags=p.URDF_USE_INERTIA_FROM_FILE,
                          physicsClientId=client)
        assert p.getNumJoints(body, physicsClientId=client) == 2
        p.setGravity(0, 0, 0, physicsClientId=client)
        p.setPhysicsEngineParameter(fixedTimeStep=1e-4, physicsClientId=client)
        # DESIGN.md §3: damping is a body setting (on the base), in a call of its
        # own. getDynamicsInfo does not report it: the one-step response below
        # reads it back (the default 0.04 would make it 4e-6 short).
        p.changeDynamics(body, -1, linearDamping=0, angularDamping=0, physicsClientId=client)
        torque = {1: 0.5, 2: 3.0}
        for j, member in enumerate(MEMBERS):
            props = built.props[member]
            info = p.getJointInfo(body, j, physicsClientId=client)
            assert info[1].decode() == f"{('pinion', 'gear')[j]}_joint"
            assert info[2] == p.JOINT_REVOLUTE
            assert info[6] == 0 and info[7] == 0          # joint damping, friction
            assert info[11] >= 1000                       # URDF velocity limit
            dyn = p.getDynamicsInfo(body, j, physicsClientId=client)
            assert dyn[0] == pytest.approx(props.mass, rel=1e-12)
            np.testing.assert_allclose(dyn[2], props.principal_moments, rtol=1e-9)
            assert dyn[2][2] == pytest.approx(props.axial_inertia, rel=1e-6)
            np.testing.assert_allclose(dyn[3], props.centre_of_mass, atol=1e-12)
            # joint axis is given in the link's (inertial) frame
            frame = np.array(p.getMatrixFromQuaternion(dyn[4])).reshape(3, 3)
            np.testing.assert_allclose(frame @ np.array(info[13]), built.pair.rotation_axis[member],
                                       atol=1e-12)
            p.setJointMotorControl2(body, j, p.VELOCITY_CONTROL, force=0, physicsClientId=client)
            p.applyExternalTorque(body, j, list(torque[member] * built.pair.rotation_axis[member]),
                                  p.WORLD_FRAME, physicsClientId=client)
        p.stepSimulation(physicsClientId=client)
        for j, member in enumerate(MEMBERS):
            speed = p.getJointState(body, j, physicsClientId=client)[1]
            expected = torque[member] / built.props[member].axial_inertia
            assert speed / 1e-4 == pytest.approx(expected, rel=1e-9)
    finally:
        p.disconnect(client)


def test_urdf_inertial_frames_are_principal(built, urdf):
    """rpy turns the link frame onto the principal axes; ixy = ixz = iyz = 0."""
    from xml.etree import ElementTree

    robot = ElementTree.parse(urdf).getroot()
    for member, name in zip(MEMBERS, ("pinion", "gear")):
        link = robot.find(f"link[@name='{name}']")
        assert link.find("collision") is None
        inertia = link.find("inertial/inertia").attrib
        assert all(float(inertia[k]) == 0 for k in ("ixy", "ixz", "iyz"))
        roll, pitch, yaw = map(float, link.find("inertial/origin").attrib["rpy"].split())
        # R = Rz(yaw) Ry(pitch) Rx(roll): columns are the frame's axes
        frame = rotate(rotate(np.eye(3), [1, 0, 0], roll), [0, 1, 0], pitch)
        frame = rotate(frame, [0, 0, 1], yaw).T
        np.testing.assert_allclose(frame, built.props[member].principal_axes, atol=1e-12)
        joint = robot.find(f"joint[@name='{name}_joint']")
        axis = np.array(joint.find("axis").attrib["xyz"].split(), float)
        np.testing.assert_allclose(axis, built.pair.rotation_axis[member], atol=1e-15)
