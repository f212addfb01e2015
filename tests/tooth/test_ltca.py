"""The tooth stage: FE segment, compliance, local contact and the LTCA on them."""

import math

import numpy as np
import pytest

from lsbg.contact import ContactParameters, MeshContact
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.tooth.compliance import FEMeshSettings, ToothMaterial
from lsbg.tooth.local import HertzLines, local_approach, normal_curvature_across
from lsbg.tooth.field import active_field, undercut_roll
from lsbg.tooth.contact_points import FECompliance, contact_points
from lsbg.tooth.ltca import fe_loaded_tca, solve_contact

TORQUE = 1964.99  # the paper's gear torque [N m]
RATED = 480.0  # about the pair's rated pitting torque on the gear (ISO 10300) [N m]


@pytest.fixture(scope="module")
def contact(pair):
    return MeshContact(pair, ContactParameters(model="line"))


def tetrahedra_volume(nodes, tets):
    a, b, c, d = (nodes[:, t] for t in tets)
    return np.abs(np.einsum("ij,ij->j", b - a, np.cross(c - a, d - a, axis=0))).sum() / 6


def test_segment_holds_three_teeth_of_the_blank(pair):
    from lsbg.solid.mass import quadrature_mass_properties
    from lsbg.tooth.segment import segment_mesh

    mesh = segment_mesh(pair, 1, 2e-3)
    volume = tetrahedra_volume(mesh.nodes, mesh.tetrahedra)
    whole = quadrature_mass_properties(pair, 1).volume
    # three of nine teeth and their rim; the root fillets add a little material
    assert volume == pytest.approx(3 / 9 * whole, rel=0.02)
    assert mesh.clamped.size > 50


@pytest.mark.parametrize("spiral, member", [(20, 1), (45, 2)])
def test_segments_mesh_at_the_ends_of_the_sweep(spiral, member):
    """Where OCC's own root fillet failed (the pinion at 20-32.5 deg, the gear at
    42.5-45 deg), the sections' fillets give a 7-tooth segment of the blank."""
    from lsbg.solid.mass import quadrature_mass_properties
    from lsbg.tooth.segment import segment_mesh

    pair = GearPair(GearPairDesign.from_config({"spiral_angle_deg": spiral}))
    mesh = segment_mesh(pair, member, 2e-3, teeth=7)
    volume = tetrahedra_volume(mesh.nodes, mesh.tetrahedra)
    whole = quadrature_mass_properties(pair, member).volume
    assert volume == pytest.approx(7 / pair.design.teeth[member - 1] * whole, rel=0.02)


def test_flank_curvature_along_the_contact_line_is_the_generating_curve(pair):
    # both flanks contain the contact line, which lies in the plane of action
    # with the flanks' normals: its normal curvature is the curve's, sin(beta_p)/R
    from lsbg.gear.flank import member_polar_angle

    d = pair.design
    rho = d.mean_cone_distance
    plane = pair.planes["drive"]
    h = 1e-6
    for member in (1, 2):
        def surface(r, t):
            return pair.flank(member, "drive", r, member_polar_angle(pair, member, r, t))
        slope = (plane.curve.polar_angle(rho * (1 + h)) - plane.curve.polar_angle(rho * (1 - h))) \
            / (2 * h * rho)
        xp, np_ = surface(rho * (1 + h), slope * rho * h)
        xm, nm = surface(rho * (1 - h), -slope * rho * h)
        line, turn = (xp - xm), (np_ - nm)
        kappa = abs(turn @ line) / (line @ line)
        assert kappa == pytest.approx(math.sin(d.plane_spiral_angle) / rho, rel=1e-5)


def test_pinion_profile_curvature_matches_its_virtual_gear(pair):
    # at the mean point the pinion's normal section is the involute of its
    # virtual (Tredgold, normal-section) spur gear: rho = r_v sin(alpha_n)
    d = pair.design
    kappa = normal_curvature_across(pair, 1, d.mean_cone_distance, 0.0)[0]
    r_v = d.mean_pitch_radius(1) / math.cos(d.pitch_angle(1)) / math.cos(d.spiral_angle) ** 2
    assert kappa == pytest.approx(1 / (r_v * math.sin(d.normal_pressure_angle)), rel=0.02)


def test_compliance_is_positive_and_mostly_local(compliance):
    for name in ("pinion", "gear"):
        c = compliance[f"compliance_{name}"].values
        f, p = c.shape[1:3]
        own = c[1].reshape(f * p, f * p)
        assert np.all(np.diag(own) > 0)
        # a tooth moves most under its own load; the neighbours far less
        centre = (f // 2, p // 2)
        assert abs(c[0][centre + centre]) < 0.2 * c[1][centre + centre]
        assert abs(c[2][centre + centre]) < 0.2 * c[1][centre + centre]


def test_uniform_bed_as_compliance_reproduces_the_line_model(contact):
    # a diagonal compliance 1/(k_l l) without Hertz is the line model's bed of
    # springs: the complementarity solve must find the kernel's mismatch
    for phase in (0.0, 0.13, 0.5, 0.77):
        pinion = phase * contact.pitch / contact.e1
        points = contact_points(contact, contact.orientation * pinion * contact.e1)
        diagonal = np.diag(1.0 / (contact.params.line_stiffness * points.length))
        loads, eps = solve_contact(diagonal, points, TORQUE, contact.e2, lambda f: 0.0 * f)
        gear = contact.static_gear_angle(TORQUE, pinion)
        assert eps == pytest.approx(pinion * contact.e1 - gear * contact.e2, rel=1e-9)


@pytest.fixture(scope="module")
def problem(pair, compliance, contact):
    """The contact problem at 0.3 base pitches: FE compliance, its points, matrix and the
    flanks' relative curvature and thicknesses there."""
    fe = FECompliance(compliance, pair, contact.orientation,
                      contact.arrays[2][0, :contact.params.slices, 0])
    points = contact_points(contact, 0.3 * contact.pitch)
    weights = fe.weights(points)
    return (fe, points, fe.matrix(points, weights), *fe.point_values(points, weights))


def test_contact_problem_is_complementary_and_balanced(problem, contact):
    fe, points, matrix, curvature, h1, h2 = problem

    def local(forces):
        return local_approach(forces / points.length, curvature, h1, h2, fe.young, fe.poisson)

    loads, eps = solve_contact(matrix, points, TORQUE, contact.e2, local)
    gap = matrix @ loads + local(loads) - (points.lever * eps - points.separation)
    scale = np.abs(points.lever * eps).max()
    assert np.all(loads >= 0)
    assert np.all(gap >= -1e-9 * scale)
    assert np.all(np.abs(loads * gap) <= 1e-9 * scale * loads.max())
    assert contact.e2 * np.sum(points.lever * loads) == pytest.approx(TORQUE, rel=1e-9)
    assert np.count_nonzero(loads) > points.lever.size // 2


def test_hertz_lines_are_the_local_approach_with_its_derivative():
    rng = np.random.default_rng(1)
    n = 40
    length = rng.uniform(1e-6, 2e-3, n)  # slivers of bands too
    curvature, h1, h2 = rng.uniform(50, 5000, n), rng.uniform(1e-3, 4e-3, n), \
        rng.uniform(1e-3, 4e-3, n)
    forces = rng.uniform(1.0, 4000.0, n)
    lines = HertzLines(length, curvature, h1, h2, 2.06e11, 0.3)
    expected = local_approach(forces / length, curvature, h1, h2, 2.06e11, 0.3)
    assert np.allclose(lines.approach(forces), expected, rtol=1e-13, atol=0)
    h = 1e-6
    numeric = (lines.approach(forces * (1 + h)) - lines.approach(forces * (1 - h))) / (2 * h * forces)
    assert np.allclose(lines.tangent(forces), numeric, rtol=1e-6)
    assert lines.approach(np.zeros(n)).max() == 0 and np.all(np.isinf(lines.tangent(np.zeros(n))))


def test_local_approach_keeps_growing_past_the_formulas_range():
    # b ~ h at q ~ 1e9 N/m: the formula turns down there; a band cut to a
    # sliver reaches such q, and a falling approach made it a rigid post
    q = np.logspace(4, 12, 400)
    approach = local_approach(q, 1000.0, 2e-3, 2e-3, 2.06e11, 0.3)
    assert np.all(np.diff(approach) > 0)
    # a whole band's loads (b << h) keep Weber and Banaschek's formula
    from lsbg.tooth.reference import (line_contact_approach, line_contact_half_width,
                                      reduced_modulus)
    ordinary = q < 1e7
    b = line_contact_half_width(q[ordinary], 1e-3, reduced_modulus(2.06e11, 0.3, 2.06e11, 0.3))
    formula = 2 * line_contact_approach(q[ordinary], 2.06e11, 0.3, b, 2e-3)
    assert np.allclose(approach[ordinary], formula, rtol=1e-14, atol=0)


def test_newton_finds_the_secant_fixed_point_from_any_start(problem, contact):
    fe, points, matrix, curvature, h1, h2 = problem
    lines = HertzLines(points.length, curvature, h1, h2, fe.young, fe.poisson)
    secant = solve_contact(matrix, points, TORQUE, contact.e2, lines.approach)
    newton = solve_contact(matrix, points, TORQUE, contact.e2, lines.approach, lines.tangent)
    warm = solve_contact(matrix, points, 1.01 * TORQUE, contact.e2, lines.approach,
                         lines.tangent, start=newton[0])
    cold = solve_contact(matrix, points, 1.01 * TORQUE, contact.e2, lines.approach,
                         lines.tangent)
    assert newton[1] == pytest.approx(secant[1], rel=1e-9)
    assert np.allclose(newton[0], secant[0], rtol=0, atol=1e-7 * secant[0].max())
    assert warm[1] == pytest.approx(cold[1], rel=1e-12)


def test_basic_rack_undercuts_below_seventeen_teeth():
    # ISO 53 profile A: h = 1.25 m, rho = 0.38 m; no undercut from
    # z = 2 (h - rho (1 - sin 20 deg)) / sin^2 20 deg = 17.1 teeth up
    alpha = math.radians(20)
    roll = [undercut_roll(z / 2, alpha, 1.25, 0.38, z)[0] for z in (10, 14, 16, 18, 30)]
    assert roll[0] > roll[1] > roll[2] > 0
    assert roll[3] == roll[4] == 0
    # a sharp rack of depth 1 m undercuts z = 10 up to about half a module above T1
    assert undercut_roll(5.0, alpha, 1.0, 0.0, 10)[0] == pytest.approx(0.50, abs=0.01)


def test_field_ends_where_the_pinions_generated_flank_starts(pair, contact):
    # the gear's tip overshoots the 9-tooth pinion's base cone (lsbg's undercut):
    # the generated pinion's involute starts inside lsbg's field, the gear's
    # tip still bounds the other side
    d = pair.design
    rho = contact.arrays[2][0, :contact.params.slices, 0]
    lo, hi = active_field(pair, 0.25 * d.mean_module * math.cos(d.spiral_angle), rho)
    psi_lo, psi_hi = pair.planes["drive"].field[:2]
    assert pair.undercut["drive"]["pinion"] > 0
    assert np.all(lo == psi_lo)
    assert np.all((psi_hi - hi > math.radians(0.3)) & (psi_hi - hi < math.radians(0.8)))
    for turn in np.linspace(0, contact.pitch, 7):
        points = contact_points(contact, turn, (lo, hi))
        assert np.all(points.psi <= hi[points.band] + 1e-12)


def test_fe_mesh_stiffness_lies_in_the_iso_band(contact, compliance):
    out = fe_loaded_tca(contact, compliance, TORQUE, phases=16)
    per_width = out.attrs["mesh_stiffness_per_face_width_N_per_mm_um"]
    # ISO 10300 / 6336 steel gears: roughly 12-25 N/(mm um)
    assert 12 <= per_width <= 25
    # the tooth's compliance adds to the uniform bed's transmission error
    assert out.attrs["transmission_error_mean_urad"] > 0
    assert np.all(out["root_stress_pinion"].values > 0)


def test_points_know_where_their_band_reaches_the_field_end(contact):
    """A band cut by the field's end is an edge point (its line ends on a tip), on
    the side it is cut; inside the field no band is."""
    psi_lo, psi_hi = contact.pair.planes["drive"].field[:2]
    for turn in np.linspace(0, contact.pitch, 9):
        points = contact_points(contact, turn)
        assert set(np.unique(points.edge)) <= {-1, 0, 1}
        low, high = points.edge == -1, points.edge == 1
        np.testing.assert_allclose(points.psi_from[low], psi_lo, atol=1e-15)
        np.testing.assert_allclose(points.psi_to[high], psi_hi, atol=1e-15)
        inside = points.edge == 0
        assert np.all((points.psi_from[inside] > psi_lo) & (points.psi_to[inside] < psi_hi))


def test_tip_relief_takes_the_load_off_the_profile_ends(pair, compliance):
    """Without relief the bands at the ends of the active profile carry load (an edge
    load, named as such); a tip relief of both members larger than the pairs'
    deflection at its rated torque leaves them unloaded, and the largest pressure
    falls."""
    from lsbg.tca.modification import FlankModification
    from lsbg.tca.separation import separation_field

    crowned = FlankModification(25e-6, 5e-6)
    relieved = FlankModification(25e-6, 5e-6, pinion_tip_relief=40e-6, gear_tip_relief=40e-6)
    out = {}
    for name, modification in (("crowned", crowned), ("relieved", relieved)):
        contact = MeshContact(pair, ContactParameters(model="line"),
                              separation=separation_field(pair, modification))
        out[name] = fe_loaded_tca(contact, compliance, RATED, phases=16)
    edge = out["crowned"]
    assert edge.attrs["max_edge_load_share"] > 0.02
    assert edge.attrs["max_edge_line_load_N_mm"] > 100
    assert edge.attrs["tip_relief"] == "none"
    # off the edges the pressure is Hertz's between flanks, never above the largest
    assert np.all(edge["max_flank_pressure"].values <= edge["max_contact_pressure"].values)
    free = out["relieved"]
    assert free.attrs["max_edge_load_share"] == 0.0
    assert free.attrs["tip_relief"] == "pinion's tip, gear's tip"
    assert free.attrs["max_contact_pressure_MPa"] < edge.attrs["max_contact_pressure_MPa"]
    # the relieved flank is still in equilibrium: the same torque on fewer points
    assert free.attrs["max_relief_start_line_load_N_mm"] > 0


def test_nodal_cholesky_solves_a_block_system():
    # a 3-D grid's stiffness-like matrix with three DOFs per node, some clamped
    import scipy.sparse as sp
    from scipy.sparse.linalg import spsolve

    from lsbg.tooth.cholesky import NodalCholesky

    rng = np.random.default_rng(3)
    line = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(7, 7))
    eye = sp.identity(7)
    grid = (sp.kron(sp.kron(line, eye), eye) + sp.kron(sp.kron(eye, line), eye)
            + sp.kron(sp.kron(eye, eye), line))
    coupling = sp.csr_matrix(rng.uniform(-0.3, 0.3, (3, 3)))
    block = sp.identity(3) + coupling @ coupling.T
    matrix = (sp.kron(grid, block) + 0.01 * sp.identity(3 * 343)).tocsr()
    free = np.arange(3 * 10, 3 * 343)
    factor = NodalCholesky(matrix, free, np.arange(3 * 343)[free] // 3)
    rhs = rng.standard_normal((free.size, 4))
    expected = spsolve(matrix[free][:, free].tocsc(), rhs)
    assert np.allclose(factor.solve(rhs), expected, rtol=1e-10, atol=1e-12 * np.abs(expected).max())
    assert np.allclose(factor.solve(rhs[:, 0]), expected[:, 0], rtol=1e-10,
                       atol=1e-12 * np.abs(expected).max())


def test_resource_estimate_matches_the_mesh_and_grows_with_it(pair, compliance):
    from lsbg.tooth.resources import fe_resource_estimate

    coarse = fe_resource_estimate(pair, FEMeshSettings(tooth_size=0.52, body_size=10.0))
    for name in ("pinion", "gear"):
        assert getattr(coarse, f"dofs_{name}") == pytest.approx(
            compliance.attrs[f"fe_dofs_{name}"], rel=0.15)
    fine = fe_resource_estimate(pair, FEMeshSettings(tooth_size=0.3))
    assert fine.dofs > 2 * coarse.dofs and fine.seconds > 2 * coarse.seconds
    assert 2 * coarse.memory < fine.memory < 1e10


@pytest.mark.parametrize("kwargs, key", [
    ({"young_modulus": -1.0}, "young_modulus"),
    ({"poisson_ratio": 0.5}, "poisson_ratio"),
])
def test_material_out_of_range_is_named(kwargs, key):
    with pytest.raises(ValueError, match=key):
        ToothMaterial(**kwargs)


@pytest.mark.parametrize("kwargs, key", [
    ({"tooth_size": 3.0}, "tooth_size"),
    ({"tooth_size": 0.6}, "tooth_size = 0.6"),   # fewer than three elements across the tooth
    ({"face_points": 2}, "face_points"),
])
def test_mesh_settings_out_of_range_are_named(kwargs, key):
    with pytest.raises(ValueError, match=key):
        FEMeshSettings(**kwargs)


def test_compliance_of_another_design_is_refused(compliance):
    other = GearPair(GearPairDesign(trace="circular"))
    with pytest.raises(ValueError, match="design trace"):
        fe_loaded_tca(MeshContact(other, ContactParameters(model="line")), compliance, TORQUE,
                      phases=8)


def test_root_stresses_are_those_of_every_fillet_point(problem):
    """The fillet points left out cannot hold a position's largest tension: the root
    stresses are those of all points' tensors to the last bit, with loads from the
    grid's own weights, extrapolated ones (< 0) and an unloaded tooth pair."""
    from lsbg.tooth.elasticity import largest_principal

    fe, points = problem[:2]
    weights = fe.weights(points)
    rng = np.random.default_rng(3)
    loads = rng.uniform(0.0, 2e3, (5, points.rho.size))
    loads[2] = 0.0  # a pair in mesh without load
    on_grid = loads @ weights
    on_grid[3] += rng.uniform(-200.0, 0.0, on_grid.shape[1])  # extrapolated weights
    on_grid[4] = -on_grid[4]  # every fillet in compression: no tension
    position = np.array([0, 0, 1, 2, 3])
    root = fe.root_stresses([(position, on_grid)], 4)
    for name in ("pinion", "gear"):
        stress = np.moveaxis(fe.stress[name] @ on_grid.T, -1, 0)
        expected = np.zeros(4)
        np.maximum.at(expected, position, largest_principal(stress).max(axis=1))
        assert root[name].tobytes() == expected.tobytes()
        assert root[name][0] > 0 and root[name][1] == 0.0  # position 1 unloaded



def test_root_stresses_are_the_same_from_the_file(problem, compliance, pair, contact, tmp_path):
    """An FE compliance computed in this process (its fillet stress a strided view) and
    the same read back from its file (what a study's jobs read) give the same root
    stresses to the last bit: the products do not depend on the arrays' layout."""
    import xarray as xr

    from lsbg.files import write_dataset

    fe, points = problem[:2]
    write_dataset(compliance, tmp_path / "compliance.nc")
    read = FECompliance(xr.load_dataset(tmp_path / "compliance.nc"), pair, contact.orientation,
                        contact.arrays[2][0, :contact.params.slices, 0])
    on_grid = np.random.default_rng(4).uniform(0.0, 2e3, (3, points.rho.size)) \
        @ fe.weights(points)
    position = np.array([0, 1, 1])
    here, there = fe.root_stresses([(position, on_grid)], 2), read.root_stresses(
        [(position, on_grid)], 2)
    for name in ("pinion", "gear"):
        assert here[name].tobytes() == there[name].tobytes()

def test_separations_shared_by_a_positions_calls_change_no_point(pair):
    """The line model's points read the field's separations where a line and its
    bands' cone distances are the same: every array as from a call of its own."""
    from lsbg.tca.modification import FlankModification
    from lsbg.tca.separation import separation_field

    crowned = MeshContact(pair, ContactParameters(model="line"),
                          separation=separation_field(pair, FlankModification(25e-6, 5e-6)))
    band_rho = crowned.arrays[2][0, :crowned.params.slices, 0]
    field = active_field(pair, 0.25 * pair.design.mean_module
                         * math.cos(pair.design.spiral_angle), band_rho)
    turn = 0.3 * crowned.pitch
    known = {}
    shared = (contact_points(crowned, turn, field, known), contact_points(crowned, turn,
                                                                          separations=known))
    own = contact_points(crowned, turn, field), contact_points(crowned, turn)
    assert len(known) > 0
    for a, b in zip(shared, own):
        for name, value in vars(b).items():
            assert np.asarray(getattr(a, name)).tobytes() == np.asarray(value).tobytes(), name
