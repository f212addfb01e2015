"""Closed-form references for the tooth compliance: ISO 6336-1 method B, the
potential-energy method with Sainsot's gear body, Hertz line contact."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from lsbg.tooth import reference as ref

STEEL = dict(young_modulus=206e9, poisson_ratio=0.3)
TOOTH = dict(teeth=40, module=4e-3, face_width=25e-3, **STEEL)   # pitch radius 80 mm
ALPHA = math.radians(20)
N_PER_MM_UM = 1e9   # 1 N/(mm µm) in N/m²


def inv(angle):
    return math.tan(angle) - angle


def load_angle(teeth, radius, module=4e-3):
    """α1 = tan α_r - θ_b, θ_b = π/(2z) + inv α (Tian 2004): the line of action
    touches the base circle at polar angle -α1 from the tooth centre line."""
    base = module * teeth / 2 * math.cos(ALPHA)
    return math.tan(math.acos(base / radius)) - (math.pi / (2 * teeth) + inv(ALPHA)), base


# ---------------------------------------------------------------------------
# ISO 6336-1:2019 method B
# ---------------------------------------------------------------------------

def test_iso_rack_limit_is_the_constant_term():
    # zn1 = zn2 = inf, x = 0: q' = 0.04723 mm µm/N, c'_th = 21.17298;
    # C_B = 1 + 0.5 (1.2 - 1.25) = 0.975, c' = 0.8 * 0.975 / 0.04723 = 16.51493 N/(mm µm).
    c = ref.iso6336_single_pair_stiffness(np.inf, np.inf)
    assert c == pytest.approx(16.51493 * N_PER_MM_UM, rel=1e-6)
    theoretical = ref.iso6336_single_pair_stiffness(np.inf, np.inf, dedendum_factor=1.2,
                                                    theory_factor=1.0)
    assert theoretical == pytest.approx(21.17298 * N_PER_MM_UM, rel=1e-6)


def test_iso_equal_gears_of_40_teeth():
    # q' = 0.04723 + (0.15551 + 0.25791)/40 = 0.0575655, c' = 0.78/q' = 13.54978 N/(mm µm).
    assert ref.iso6336_single_pair_stiffness(40, 40) == pytest.approx(13.54978e9, rel=1e-6)


def test_iso_profile_shift_and_pressure_angle_terms():
    # x1 = 0.5, zn = inf: q' = 0.04723 - 0.00635*0.5 + 0.00529*0.25 = 0.0453775,
    # c' = 0.78/q' = 17.18914 N/(mm µm).
    c = ref.iso6336_single_pair_stiffness(np.inf, np.inf, profile_shift_1=0.5)
    assert c == pytest.approx(17.18914e9, rel=1e-6)
    # x2 = 0.3, zn1 = 30, zn2 = 60: q' = 0.04723 + 0.15551/30 + 0.25791/60 - 0.00193*0.3
    # - 0.24188*0.3/60 + 0.00182*0.09 = 0.05508757; C_M = C_B = 1 with h_fP/m = 1.2.
    c = ref.iso6336_single_pair_stiffness(30, 60, profile_shift_2=0.3, dedendum_factor=1.2,
                                          theory_factor=1.0)
    assert c == pytest.approx(1e9 / 0.05508757, rel=1e-6)
    # α_n = 25 deg: C_B = 0.975 * (1 - 0.02 * (20 - 25)) = 1.0725.
    ratio = (ref.iso6336_single_pair_stiffness(40, 40, normal_pressure_angle=math.radians(25))
             / ref.iso6336_single_pair_stiffness(40, 40, normal_pressure_angle=ALPHA))
    assert ratio == pytest.approx(1.1, rel=1e-12)


def test_iso_tr_6336_30_example_1():
    # ISO/TR 6336-30:2017, example 1 (single helical, m_n = 8 mm, z = 17/103,
    # x1 = 0.145, β = 15.8 deg, basic rack h_fP = 1.4 m_n), Annex A:
    # zn = 18.905/114.543, c'_th = 17.85584, c' = 12.37047 N/(mm µm).
    # zn = z/(cos² β_b cos β) with sin β_b = sin β cos α_n (ISO 6336-1).
    beta = math.radians(15.8)
    zn = np.array([17, 103]) / ((1 - (math.sin(beta) * math.cos(ALPHA))**2) * math.cos(beta))
    assert zn == pytest.approx([18.905, 114.543], rel=1e-5)
    c_th = ref.iso6336_single_pair_stiffness(zn[0], zn[1], 0.145, 0.0, dedendum_factor=1.2,
                                             theory_factor=1.0)
    assert c_th == pytest.approx(17.85584e9, rel=2e-6)
    c = ref.iso6336_single_pair_stiffness(zn[0], zn[1], 0.145, 0.0, dedendum_factor=1.4,
                                          helix_angle=beta)
    assert c == pytest.approx(12.37047e9, rel=2e-6)


def test_iso_mesh_stiffness():
    # c_γα = c' (0.75 ε_α + 0.25): ε_α = 1.6 gives 1.45 c'.
    assert ref.iso6336_mesh_stiffness(13e9, 1.6) == pytest.approx(1.45 * 13e9, rel=1e-12)
    np.testing.assert_allclose(ref.iso6336_mesh_stiffness(10e9, [1.0, 2.0]), [10e9, 17.5e9])


# ---------------------------------------------------------------------------
# Potential-energy method
# ---------------------------------------------------------------------------

def test_involute_part_matches_tians_integrals():
    # With the root circle on the base circle (h_f* = z (1 - cos α)/2) the tooth is
    # the involute alone, and Tian's (2004) closed integrands over the tangency
    # angle a from -α1 to α2 = θ_b apply (plane stress, rectangular section):
    #   1/k_b = ∫ 3 {1 + cos α1 [(α2 - a) sin a - cos a]}² (α2 - a) cos a
    #             / (2 E L [sin a + (α2 - a) cos a]³)
    #   1/k_s = ∫ 1.2 (1 + ν) (α2 - a) cos a cos² α1 / (E L [sin a + (α2 - a) cos a])
    #   1/k_a = ∫ (α2 - a) cos a sin² α1 / (2 E L [sin a + (α2 - a) cos a])
    z, e, nu, width = 40, 206e9, 0.3, 25e-3
    a2 = math.pi / (2 * z) + inv(ALPHA)
    for radius in (76e-3, 80e-3, 83.9e-3):
        a1, _ = load_angle(z, radius)
        got = ref.potential_energy_compliance(z, 4e-3, radius, width, e, nu, plane="stress",
                                              dedendum_factor=z * (1 - math.cos(ALPHA)) / 2)

        def thick(a):
            return math.sin(a) + (a2 - a) * math.cos(a)

        kb = quad(lambda a: 3 * (1 + math.cos(a1) * ((a2 - a) * math.sin(a) - math.cos(a)))**2
                  * (a2 - a) * math.cos(a) / (2 * e * width * thick(a)**3), -a1, a2,
                  epsabs=0, epsrel=1e-13)[0]
        ks = quad(lambda a: 1.2 * (1 + nu) * (a2 - a) * math.cos(a) * math.cos(a1)**2
                  / (e * width * thick(a)), -a1, a2, epsabs=0, epsrel=1e-13)[0]
        ka = quad(lambda a: (a2 - a) * math.cos(a) * math.sin(a1)**2
                  / (2 * e * width * thick(a)), -a1, a2, epsabs=0, epsrel=1e-13)[0]
        assert got["bending"] == pytest.approx(kb, rel=1e-10)
        assert got["shear"] == pytest.approx(ks, rel=1e-10)
        assert got["axial"] == pytest.approx(ka, rel=1e-10)


def test_straight_part_below_the_base_circle():
    # z = 40, h_f* = 1.25: root 75 mm < base 75.175 mm. Tian's straight part has half
    # thickness h_b = r_b sin θ_b from u_f = sqrt(r_f² - h_b²) to u_b = r_b cos θ_b,
    # and the moment there is r_b - u cos α1 (cos α1 u_L - sin α1 h_L = r_b on the
    # involute), so in plane strain (E' = E/(1 - ν²)):
    #   Δ(1/k_b) = [(r_b - c u_f)³ - (r_b - c u_b)³] / (3 c E' 2/3 h_b³ L),  c = cos α1
    #   Δ(1/k_s) = 1.2 c² (u_b - u_f)/(G 2 h_b L),  Δ(1/k_a) = sin² α1 (u_b - u_f)/(E' 2 h_b L)
    z, radius, width = 40, 80e-3, 25e-3
    a1, base = load_angle(z, radius)
    theta_b = math.pi / (2 * z) + inv(ALPHA)
    h_b, u_b = base * math.sin(theta_b), base * math.cos(theta_b)
    u_f = math.sqrt(75e-3**2 - h_b**2)
    e1, g = 206e9 / 0.91, 206e9 / 2.6
    c, s = math.cos(a1), math.sin(a1)
    full = ref.potential_energy_compliance(load_radius=radius, **TOOTH)
    involute = ref.potential_energy_compliance(load_radius=radius, **TOOTH,
                                               dedendum_factor=z * (1 - math.cos(ALPHA)) / 2)
    bending = ((base - c * u_f)**3 - (base - c * u_b)**3) / (3 * c * e1 * 2 / 3 * h_b**3 * width)
    assert full["bending"] - involute["bending"] == pytest.approx(bending, rel=1e-9)
    assert full["shear"] - involute["shear"] == pytest.approx(
        1.2 * c**2 * (u_b - u_f) / (g * 2 * h_b * width), rel=1e-9)
    assert full["axial"] - involute["axial"] == pytest.approx(
        s**2 * (u_b - u_f) / (e1 * 2 * h_b * width), rel=1e-9)


def test_fillet_foundation_is_sainsots_formula():
    # Pitch point of z = 40, m = 4 mm: θ_f = (π/2 + 2 (1.25 - 0.38) tan 20° + 2 * 0.38/cos 20°)/40
    # = 0.0753220 rad, h_f = 75/37.5 = 2 (default bore), S_f = 2 r_f θ_f; the line of action
    # crosses the centre line at r_b/cos α1, so u_f = r_b/cos α1 - r_f. The coefficient
    # table of Sainsot et al. (2004) as public implementations (ROSS GearElementTVMS and
    # others) reproduce it (rows L*, M*, P*, Q*; columns A..F).
    table = [[-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045],
             [60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086],
             [-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236],
             [-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904]]
    theta, h = 0.0753220, 2.0
    lstar, mstar, pstar, qstar = (a / theta**2 + b * h**2 + c * h / theta + d / theta + e * h + f
                                  for a, b, c, d, e, f in table)
    assert (lstar, mstar, pstar, qstar) == pytest.approx((6.8981, 1.0984, 2.8626, 0.5145), abs=1e-4)
    a1, base = load_angle(40, 80e-3)
    ratio = (base / math.cos(a1) - 75e-3) / (2 * 75e-3 * theta)
    expected = math.cos(a1)**2 / (206e9 / 0.91 * 25e-3) * (
        lstar * ratio**2 + mstar * ratio + pstar * (1 + qstar * math.tan(a1)**2))
    got = ref.potential_energy_compliance(load_radius=80e-3, **TOOTH)["fillet_foundation"]
    assert got == pytest.approx(expected, rel=1e-5)


def test_pe_invariants():
    radii = np.linspace(75.2e-3, 84e-3, 9)
    base = ref.potential_energy_compliance(load_radius=radii, **TOOTH)
    # Each component grows as the load moves to the tip except the axial one
    # (sin² α1 falls to 0 where α1 changes sign, near the base circle).
    for key in ("bending", "fillet_foundation", "total"):
        assert np.all(np.diff(base[key]) > 0), key
    # 2D elasticity: the compliance of a similar tooth does not depend on its size.
    scaled = ref.potential_energy_compliance(**{**TOOTH, "module": 8e-3}, load_radius=2 * radii)
    stiff = ref.potential_energy_compliance(**{**TOOTH, "young_modulus": 412e9}, load_radius=radii)
    wide = ref.potential_energy_compliance(**{**TOOTH, "face_width": 50e-3}, load_radius=radii)
    stress = ref.potential_energy_compliance(load_radius=radii, plane="stress", **TOOTH)
    for key in base:
        np.testing.assert_allclose(scaled[key], base[key], rtol=1e-12)
        np.testing.assert_allclose(stiff[key], base[key] / 2, rtol=1e-12)
        np.testing.assert_allclose(wide[key], base[key] / 2, rtol=1e-12)
    # Plane strain stiffens by 1/(1 - ν²) all but shear (G) and Hertz (its own 1 - ν²).
    for key, factor in (("bending", 0.91), ("axial", 0.91), ("fillet_foundation", 0.91),
                        ("shear", 1.0), ("hertz", 1.0)):
        np.testing.assert_allclose(base[key] / stress[key], factor, rtol=1e-12)
    np.testing.assert_allclose(base["total"], base["bending"] + base["shear"] + base["axial"]
                               + base["fillet_foundation"], rtol=1e-14)
    # Yang & Sun (1985): 1/k_h = 4 (1 - ν²)/(π E L) = 2.2498e-10 m/N.
    np.testing.assert_allclose(base["hertz"], 4 * 0.91 / (math.pi * 206e9 * 25e-3), rtol=1e-14)


def test_pair_stiffness_is_near_iso_and_symmetric():
    # At the pitch point of equal gears both teeth carry the same load radius, so
    # 1/k = 1/k_h + 2 (tooth body); the PE pair lies within 25 % of ISO's c'_th.
    k = ref.spur_single_pair_stiffness(40, 40, 4e-3, 80e-3, 25e-3, **STEEL)
    tooth = ref.potential_energy_compliance(load_radius=80e-3, **TOOTH)
    assert 1 / k == pytest.approx(tooth["hertz"] + 2 * tooth["total"], rel=1e-12)
    c_th = ref.iso6336_single_pair_stiffness(40, 40, dedendum_factor=1.2, theory_factor=1.0)
    assert 0.75 < k / 25e-3 / c_th < 1.25


@pytest.mark.parametrize("kwargs, match", [
    (dict(teeth=0), "teeth"), (dict(teeth=-12), "teeth"),
    (dict(young_modulus=0.0), "young_modulus"),
    (dict(poisson_ratio=0.5), "poisson_ratio"), (dict(poisson_ratio=0.0), "poisson_ratio"),
    (dict(load_radius=75.0e-3), "load_radius"), (dict(load_radius=84.1e-3), "load_radius"),
    (dict(plane="solid"), "plane"), (dict(bore_radius=80e-3), "bore_radius"),
    (dict(face_width=-1.0), "face_width"), (dict(module=0.0), "module"),
    (dict(root_fillet_factor=0.5), "root_fillet_factor"), (dict(dedendum_factor=21), "dedendum"),
    (dict(addendum_factor=3.0, load_radius=80e-3), "addendum_factor"),
])
def test_pe_refuses_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        ref.potential_energy_compliance(**{**TOOTH, "load_radius": 80e-3, **kwargs})


def test_iso_and_pair_refuse_bad_input():
    with pytest.raises(ValueError, match="virtual_teeth_1"):
        ref.iso6336_single_pair_stiffness(0, 40)
    with pytest.raises(ValueError, match="virtual_teeth_2"):
        ref.iso6336_single_pair_stiffness(40, -3)
    with pytest.raises(ValueError, match="transverse_contact_ratio"):
        ref.iso6336_mesh_stiffness(13e9, 0.9)
    for radius in (75.2e-3, 90e-3):   # wheel's contact beyond its tip; beyond the pinion's
        with pytest.raises(ValueError, match="load_radius_1"):
            ref.spur_single_pair_stiffness(40, 40, 4e-3, radius, 25e-3, **STEEL)
    with pytest.raises(ValueError, match="teeth_2"):
        ref.spur_single_pair_stiffness(40, 0, 4e-3, 80e-3, 25e-3, **STEEL)


# ---------------------------------------------------------------------------
# Hertz line contact
# ---------------------------------------------------------------------------

def test_line_contact_example():
    # Steel on steel, R1 = R2 = 20 mm (R = 10 mm), q = 100 N/mm:
    # E* = 206e9/(2 * 0.91) = 113.1868 GPa, b = sqrt(4 * 1e5 * 0.01/(π * 113.1868e9))
    # = 0.106061 mm, p0 = sqrt(1e5 * 113.1868e9/(π * 0.01)) = 600.237 MPa = 2 q/(π b).
    e_star = ref.reduced_modulus(206e9, 0.3, 206e9, 0.3)
    assert e_star == pytest.approx(113.1868e9, rel=1e-6)
    b = ref.line_contact_half_width(1e5, 0.01, e_star)
    p0 = ref.line_contact_peak_pressure(1e5, 0.01, e_star)
    assert b == pytest.approx(0.106061e-3, rel=1e-5)
    assert p0 == pytest.approx(600.237e6, rel=1e-6)
    # The elliptic pressure carries the load.
    load = quad(lambda x: p0 * math.sqrt(1 - (x / b)**2), -b, b, epsabs=0, epsrel=1e-12)[0]
    assert load == pytest.approx(1e5, rel=1e-9)


def test_line_contact_approach():
    # q = 1e5 N/m, E = 206 GPa, ν = 0.3, b = 0.1 mm, d = 10 mm:
    # δ = 1e5 * 0.91/(π * 206e9) * (2 ln 200 - 0.3/0.7) = 1.429758e-6 m.
    q, e, nu, b = 1e5, 206e9, 0.3, 1e-4
    assert ref.line_contact_approach(q, e, nu, b, 1e-2) == pytest.approx(1.429758e-6, rel=1e-6)
    # Doubling the depth adds 2 q (1 - ν²) ln 2/(π E).
    deeper = ref.line_contact_approach(q, e, nu, b, [1e-2, 2e-2])
    assert np.diff(deeper)[0] == pytest.approx(2 * q * 0.91 * math.log(2) / (math.pi * e),
                                               rel=1e-12)


def test_line_contact_approach_is_the_strain_of_the_axis_stresses():
    # Plane-strain ε_z = [(1 - ν²) σ_z - ν (1 + ν) σ_x]/E integrated from the surface to
    # depth d on the axis, with Johnson's (§4.2, McEwen) σ_z = -p0 b/sqrt(b² + z²) and
    # σ_x = -p0 [(b² + 2 z²)/(b sqrt(b² + z²)) - 2 z/b], p0 = 2 q/(π b); the closed form
    # is its d >> b limit.
    q, e, nu, b = 1e5, 206e9, 0.3, 1e-4
    p0 = 2 * q / (math.pi * b)

    def strain(z):
        root = math.sqrt(b**2 + z**2)
        sz = -p0 * b / root
        sx = -p0 * ((b**2 + 2 * z**2) / (b * root) - 2 * z / b)
        return ((1 - nu**2) * sz - nu * (1 + nu) * sx) / e

    for depth in (200 * b, 1000 * b):
        exact = -quad(strain, 0, depth, epsabs=0, epsrel=1e-12, limit=200)[0]
        assert ref.line_contact_approach(q, e, nu, b, depth) == pytest.approx(exact, rel=2e-5)


@pytest.mark.parametrize("args, match", [
    ((0.0, 206e9, 0.3, 1e-4, 1e-2), "load_per_length"),
    ((1e5, -1.0, 0.3, 1e-4, 1e-2), "young_modulus"),
    ((1e5, 206e9, 0.6, 1e-4, 1e-2), "poisson_ratio"),
    ((1e5, 206e9, 0.3, 0.0, 1e-2), "half_width"),
    ((1e5, 206e9, 0.3, 1e-4, 0.0), "depth"),
])
def test_line_contact_refuses_bad_input(args, match):
    with pytest.raises(ValueError, match=match):
        ref.line_contact_approach(*args)


def test_hertz_helpers_refuse_bad_input():
    with pytest.raises(ValueError, match="poisson_ratio_2"):
        ref.reduced_modulus(206e9, 0.3, 206e9, 0.5)
    with pytest.raises(ValueError, match="young_modulus_1"):
        ref.reduced_modulus(0.0, 0.3, 206e9, 0.3)
    with pytest.raises(ValueError, match="reduced_radius"):
        ref.line_contact_half_width(1e5, -0.01, 1e11)
    with pytest.raises(ValueError, match="reduced_modulus"):
        ref.line_contact_peak_pressure(1e5, 0.01, 0.0)
