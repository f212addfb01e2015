"""The influence factors of ISO 10300:2023 (parts 1-3, method B1), one function each.

Each function takes the virtual cylindrical gears
(:func:`lsbg.rating.virtual.virtual_cylindrical_gears`) or plain numbers
and returns the factor; the formula's clause is in its docstring. The
standard works in mm, N, MPa, m/s and um; its empirical formulas are
evaluated in those units here, behind SI arguments.

Sources: ISO 10300-1:2023 (load factors), ISO 10300-2:2023 (contact),
ISO 10300-3:2023 (root), checked against the worked spiral bevel example of
ISO/TR 10300-30:2024, Annex A (tests/rating/test_iso10300.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["MOUNTING_FACTORS", "mid_zone_factor", "load_sharing_factor", "elasticity_factor",
           "lubricant_film_factors", "face_load_factors", "transverse_load_factor",
           "ToothForm", "tooth_form", "contact_ratio_factor", "bevel_spiral_angle_factor",
           "surface_condition_factor", "notch_sensitivity_factor", "size_factor"]

#: K_Hbeta-be, ISO 10300-1:2023 Table 4: (how the contact pattern was
#: verified) x (mounting: both members straddle mounted, one cantilever, both).
MOUNTING_FACTORS = {
    "full_load": {"both_straddle": 1.00, "one_cantilever": 1.00, "both_cantilever": 1.00},
    "light_test_load": {"both_straddle": 1.05, "one_cantilever": 1.10, "both_cantilever": 1.25},
    "estimated": {"both_straddle": 1.20, "one_cantilever": 1.32, "both_cantilever": 1.50},
}

#: Slip-layer thickness rho' of case-hardened steel for Y_delta,relT [mm]
#: (ISO 10300-3:2023, Table 4).
_SLIP_LAYER_CASE_HARDENED_MM = 0.0030


def mid_zone_factor(virtual):
    """Z_M-B: contact stress at the determinant point of the mid-zone (ISO 10300-2, 6.4.1).

    Parameters
    ----------
    virtual : lsbg.rating.virtual.VirtualCylindricalGears

    Returns
    -------
    float
        [-].
    """
    eps_a, eps_b = virtual.transverse_contact_ratio, virtual.face_contact_ratio
    if eps_b <= 0:
        f1, f2 = 2.0, 2.0 * (eps_a - 1.0)
    elif eps_b < 1:
        f1 = 2.0 + (eps_a - 2.0) * eps_b
        f2 = 2.0 * eps_a - 2.0 + (2.0 - eps_a) * eps_b
    else:
        f1 = f2 = eps_a
    terms = [math.sqrt(math.sqrt((da / db) ** 2 - 1.0) - f * math.pi / z)
             for da, db, f, z in zip(virtual.tip_diameter, virtual.base_diameter, (f1, f2),
                                     virtual.teeth)]
    return math.tan(virtual.transverse_pressure_angle) / (terms[0] * terms[1])


def load_sharing_factor(virtual, profile_crowning="low"):
    """Z_LS: the middle contact line's share of the load (ISO 10300-2, 6.4.2).

    The peak load on each of the tip, middle and root contact lines falls
    parabolically with its distance f from the middle of the zone of action,
    p* = 1 - |f / f_max|^e_LS (e_LS = 3 for low, 1.5 for high profile
    crowning); each line carries an elliptical load of area A* = pi/4 p* l_b;
    Z_LS = sqrt(A*_m / (A*_t + A*_m + A*_r)).

    Parameters
    ----------
    virtual : lsbg.rating.virtual.VirtualCylindricalGears
    profile_crowning : {"low", "high"}

    Returns
    -------
    float
        [-].
    """
    from lsbg.rating.virtual import contact_line_length

    exponent = {"low": 3.0, "high": 1.5}[profile_crowning]
    f_max = virtual.max_line_distance
    areas = []
    for f in virtual.line_positions:
        length = contact_line_length(f, virtual.base_helix_angle, virtual.path_of_contact,
                                     virtual.effective_face_width, virtual.face_width, f_max)
        areas.append(math.pi / 4 * (1.0 - abs(f / f_max) ** exponent) * length)
    return math.sqrt(areas[1] / sum(areas))


def elasticity_factor(young_modulus, poisson_ratio):
    """Z_E = sqrt(1 / (pi 2 (1 - nu^2) / E)), both members of one steel [sqrt(Pa)].

    Parameters
    ----------
    young_modulus, poisson_ratio : float
        E [Pa] and nu [-] of the steel.
    """
    return math.sqrt(young_modulus / (2 * math.pi * (1 - poisson_ratio ** 2)))


def lubricant_film_factors(contact_endurance, viscosity_40, speed, flank_roughness,
                           relative_curvature_radius):
    """Z_L, Z_v, Z_R (ISO 10300-2, 8.2.3; the same as ISO 6336-2's).

    Parameters
    ----------
    contact_endurance : float
        sigma_Hlim [Pa]; the constants use it within 850-1200 MPa.
    viscosity_40 : float
        Kinematic viscosity of the oil at 40 degC [m^2/s].
    speed : float
        Tangential speed at the mean point, v_mt [m/s].
    flank_roughness : float
        Mean peak-to-valley roughness Rz of both flanks [m].
    relative_curvature_radius : float
        rho_rel [m].

    Returns
    -------
    tuple of float
        (Z_L, Z_v, Z_R) [-].
    """
    limit = min(max(contact_endurance / 1e6, 850.0), 1200.0)
    c_zl = 0.08 * (limit - 850.0) / 350.0 + 0.83
    z_l = c_zl + 4.0 * (1.0 - c_zl) / (1.2 + 134.0 / (viscosity_40 * 1e6)) ** 2
    c_zv = c_zl + 0.02
    z_v = c_zv + 2.0 * (1.0 - c_zv) / math.sqrt(0.8 + 32.0 / speed)
    rz10 = flank_roughness * 1e6 * (10.0 / (relative_curvature_radius * 1e3)) ** (1 / 3)
    c_zr = 0.12 + (1000.0 - limit) / 5000.0
    return z_l, z_v, (3.0 / rz10) ** c_zr


def face_load_factors(geometry, mounting="one_cantilever", contact_pattern="light_test_load"):
    """K_Hbeta, K_Fbeta and the lengthwise curvature factor K_F0 (ISO 10300-1, clause 8).

    K_Hbeta = 1.5 K_Hbeta-be (the pattern covers most of the face width);
    K_Fbeta = K_Hbeta / K_F0, K_F0 = 0.211 (r_c0 / R_m)^q + 0.789 within
    1 ... 1.15, q = 0.279 / lg(sin beta_m): a tooth trace curved more
    tightly than the cone distance bends its root less.

    Parameters
    ----------
    geometry : lsbg.rating.virtual.BevelRatingGeometry
    mounting : {"both_straddle", "one_cantilever", "both_cantilever"}
    contact_pattern : {"full_load", "light_test_load", "estimated"}
        How the contact pattern was verified.

    Returns
    -------
    tuple of float
        (K_Hbeta, K_Fbeta, K_F0) [-].
    """
    k_hbeta = 1.5 * MOUNTING_FACTORS[contact_pattern][mounting]
    q = 0.279 / math.log10(math.sin(geometry.mean_spiral_angle))
    ratio = geometry.lengthwise_curvature_radius / geometry.mean_cone_distance
    k_f0 = min(max(0.211 * ratio ** q + 0.789, 1.0), 1.15)
    return k_hbeta, k_hbeta / k_f0, k_f0


def transverse_load_factor(accuracy_grade, contact_ratio):
    """K_Halpha = K_Falpha of spiral bevel gears by method C (ISO 10300-1, Table 5).

    Parameters
    ----------
    accuracy_grade : int
        ISO 17485 accuracy grade B, 2-11 [-].
    contact_ratio : float
        eps_vgamma [-].
    """
    if accuracy_grade <= 6:
        return 1.0
    return {7: 1.1, 8: 1.2, 9: 1.4}.get(int(accuracy_grade), max(contact_ratio, 1.4))


@dataclass(frozen=True)
class ToothForm:
    """The root's geometry of the 30-degree tangent method (ISO 10300-3, 6.4.1.2).

    Lengths [m], angles [rad].

    Attributes
    ----------
    form_factor, stress_correction : float
        Y_Fa, Y_Sa [-].
    root_thickness, fillet_radius, bending_arm : float
        s_Fn, rho_F, h_Fa.
    notch_parameter : float
        q_s = s_Fn / (2 rho_F) [-].
    fillet_angle, load_angle : float
        theta (the 30-degree tangent's parameter), alpha_Fan.
    """

    form_factor: float
    stress_correction: float
    root_thickness: float
    fillet_radius: float
    bending_arm: float
    notch_parameter: float
    fillet_angle: float
    load_angle: float


def _involute(angle):
    return math.tan(angle) - angle


def tooth_form(geometry, virtual, member):
    """Y_Fa and Y_Sa of a generated tooth, load at the tip of the virtual normal-section gear.

    ISO 10300-3:2023, 6.4.1.2 and 6.4.2 (as ISO 6336-3's method B): the
    tangent at 30 degrees to the tooth's centre line touches the fillet that
    the tool's edge radius rho_a0 generates; theta solves
    theta = 2 G / z_vn tan(theta) - H by fixed-point iteration from pi/6.

    Parameters
    ----------
    geometry : lsbg.rating.virtual.BevelRatingGeometry
    virtual : lsbg.rating.virtual.VirtualCylindricalGears
    member : {1, 2}

    Returns
    -------
    ToothForm
    """
    i = member - 1
    m = geometry.mean_normal_module
    alpha = geometry.normal_pressure_angle
    shift = geometry.profile_shift if member == 1 else -geometry.profile_shift
    thickness = geometry.thickness_modification[i]
    rho_a0 = geometry.tool_edge_radius[i]
    h_a0 = geometry.crown_dedendum_factor * m
    z_vn = virtual.normal_teeth[i]
    e = (math.pi / 4 - thickness) * m - h_a0 * math.tan(alpha) \
        - rho_a0 * (1 - math.sin(alpha)) / math.cos(alpha)
    g = rho_a0 / m - h_a0 / m + shift
    h = 2 / z_vn * (math.pi / 2 - e / m) - math.pi / 3
    theta = math.pi / 6
    for _ in range(200):
        new = 2 * g / z_vn * math.tan(theta) - h
        if abs(new - theta) <= 1e-10:
            theta = new
            break
        theta = new
    else:
        raise RuntimeError(f"the 30-degree tangent's fillet angle did not settle (member {member})")
    s_fn = m * z_vn * math.sin(math.pi / 3 - theta) \
        + math.sqrt(3) * m * (g / math.cos(theta) - rho_a0 / m)
    rho_f = rho_a0 + 2 * g * g * m / (math.cos(theta) * (z_vn * math.cos(theta) ** 2 - 2 * g))
    d_van, d_vbn = virtual.normal_tip_diameter[i], virtual.normal_base_diameter[i]
    alpha_an = math.acos(d_vbn / d_van)
    gamma_a = (math.pi / 2 + 2 * (shift * math.tan(alpha) + thickness)) / z_vn \
        + _involute(alpha) - _involute(alpha_an)
    alpha_fan = alpha_an - gamma_a
    h_fa = m / 2 * ((math.cos(gamma_a) - math.sin(gamma_a) * math.tan(alpha_fan)) * d_van / m
                    - z_vn * math.cos(math.pi / 3 - theta) - g / math.cos(theta) + rho_a0 / m)
    y_fa = 6 * (h_fa / m) * math.cos(alpha_fan) / ((s_fn / m) ** 2 * math.cos(alpha))
    arm = s_fn / h_fa
    q_s = s_fn / (2 * rho_f)
    y_sa = (1.2 + 0.13 * arm) * q_s ** (1 / (1.21 + 2.3 / arm))
    return ToothForm(y_fa, y_sa, s_fn, rho_f, h_fa, q_s, theta, alpha_fan)


def contact_ratio_factor(virtual):
    """Y_eps (ISO 10300-3, 6.4.3): 0.25 + 0.75 / eps_valpha falling linearly to 0.625 at
    eps_vbeta = 1 [-]."""
    eps_a, eps_b = virtual.transverse_contact_ratio, virtual.face_contact_ratio
    spur = 0.25 + 0.75 / eps_a
    if eps_b >= 1:
        return 0.625
    return spur - max(eps_b, 0.0) * (spur - 0.625)


def bevel_spiral_angle_factor(geometry, virtual):
    """Y_BS (ISO 10300-3, 6.4.4): the root stress of an oblique contact line on a
    tooth of finite length, from the developed tooth length b_a = b_v / cos beta_v,
    the part l_bb of it the middle contact line covers and the ratio of b_a to the
    mean whole depth [-]."""
    b_a = virtual.face_width / math.cos(virtual.helix_angle)
    l_bb = virtual.middle_line_length * math.cos(virtual.base_helix_angle) \
        / math.cos(virtual.helix_angle)
    # x = 2 b_a / (h_m1 + h_m2), each member's whole depth h_m = h_am + h_fm
    x = 2 * b_a / (sum(geometry.mean_addendum) + sum(geometry.mean_dedendum))
    a = -0.0182 * x * x + 0.4736 * x - 0.32
    b = -0.0032 * x * x + 0.0526 * x + 0.712
    c = -0.0050 * x * x + 0.0850 * x + 0.54
    return a / c * (l_bb / b_a - 1.05 * b) ** 2 + 1.0


def surface_condition_factor(root_roughness):
    """Y_R,relT of case-hardened steel, 1 um <= Rz <= 40 um (ISO 10300-3, 6.5.1) [-].

    Parameters
    ----------
    root_roughness : float
        Rz of the root fillet [m].
    """
    return 1.674 - 0.529 * (root_roughness * 1e6 + 1.0) ** 0.1


def notch_sensitivity_factor(notch_parameter):
    """Y_delta,relT of case-hardened steel (ISO 10300-3, 6.5.2.2) [-].

    Parameters
    ----------
    notch_parameter : float
        q_s [-].
    """
    chi = 0.2 * (1.0 + 2.0 * notch_parameter)
    rho = _SLIP_LAYER_CASE_HARDENED_MM
    return (1.0 + math.sqrt(rho * chi)) / (1.0 + math.sqrt(rho * 1.2))


def size_factor(normal_module):
    """Y_X of case-hardened steel, 1.05 - 0.01 m_mn[mm] within 0.8 ... 1 [-].

    Parameters
    ----------
    normal_module : float
        m_mn [m].
    """
    return min(max(1.05 - 0.01 * normal_module * 1e3, 0.8), 1.0)
