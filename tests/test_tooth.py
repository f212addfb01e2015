"""The tooth stage: FE segment, compliance, local contact and the LTCA on them."""

import math

import numpy as np
import pytest

from lsbg.contact import ContactParameters, MeshContact
from lsbg.design import GearPairDesign
from lsbg.geometry import GearPair
from lsbg.tooth.compliance import FEMeshSettings, ToothMaterial, tooth_compliance
from lsbg.tooth.local import local_approach, normal_curvature_across
from lsbg.tooth.ltca import FECompliance, contact_points, fe_loaded_tca, solve_contact

TORQUE = 1964.99  # the paper's gear torque [N m]


@pytest.fixture(scope="module")
def pair():
    return GearPair(GearPairDesign())


@pytest.fixture(scope="module")
def compliance(pair):
    # coarse (one mean normal module per element on the teeth) to keep the suite fast
    return tooth_compliance(pair, settings=FEMeshSettings(tooth_size=1.0))


@pytest.fixture(scope="module")
def contact(pair):
    return MeshContact(pair, ContactParameters(model="line"))


def tetrahedra_volume(nodes, tets):
    a, b, c, d = (nodes[:, t] for t in tets)
    return np.abs(np.einsum("ij,ij->j", b - a, np.cross(c - a, d - a, axis=0))).sum() / 6


def test_segment_holds_three_teeth_of_the_blank(pair):
    from lsbg.mass import quadrature_mass_properties
    from lsbg.tooth.segment import segment_mesh

    mesh = segment_mesh(pair, 1, 2e-3)
    volume = tetrahedra_volume(mesh.nodes, mesh.tetrahedra)
    whole = quadrature_mass_properties(pair, 1).volume
    # three of nine teeth and their rim; the root fillets add a little material
    assert volume == pytest.approx(3 / 9 * whole, rel=0.02)
    assert mesh.clamped.size > 50


def test_flank_curvature_along_the_contact_line_is_the_generating_curve(pair):
    # both flanks contain the contact line, which lies in the plane of action
    # with the flanks' normals: its normal curvature is the curve's, sin(beta_p)/R
    from lsbg.tooth.compliance import member_polar_angle

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


def test_contact_problem_is_complementary_and_balanced(pair, compliance, contact):
    fe = FECompliance(compliance, pair, contact.orientation,
                      contact.arrays[2][0, :contact.params.slices, 0])
    points = contact_points(contact, 0.3 * contact.pitch)
    weights = fe.weights(points)
    matrix = fe.matrix(points, weights)
    curvature, h1, h2 = fe.point_values(points, weights)

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


def test_fe_mesh_stiffness_lies_in_the_iso_band(contact, compliance):
    out = fe_loaded_tca(contact, compliance, TORQUE, phases=16)
    per_width = out.attrs["mesh_stiffness_per_face_width_N_per_mm_um"]
    # ISO 10300 / 6336 steel gears: roughly 12-25 N/(mm um)
    assert 12 <= per_width <= 25
    # the tooth's compliance adds to the uniform bed's transmission error
    assert out.attrs["transmission_error_mean_urad"] > 0
    assert np.all(out["root_stress_pinion"].values > 0)


@pytest.mark.parametrize("kwargs, key", [
    ({"young_modulus": -1.0}, "young_modulus"),
    ({"poisson_ratio": 0.5}, "poisson_ratio"),
])
def test_material_out_of_range_is_named(kwargs, key):
    with pytest.raises(ValueError, match=key):
        ToothMaterial(**kwargs)


@pytest.mark.parametrize("kwargs, key", [
    ({"tooth_size": 3.0}, "tooth_size"),
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
