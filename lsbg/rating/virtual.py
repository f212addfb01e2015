"""The virtual cylindrical gears of ISO 10300-1:2023, Annex A (method B1).

ISO 10300 rates a bevel gear pair through a pair of cylindrical gears that
mesh like it at the mean point of the face width: in the transverse section,
reference diameters d_v = d_m / cos(delta), the mean spiral angle as helix
angle; in the normal section (for the tooth form), z_vn = z_v / (cos^2
beta_vb cos beta_v). Only the geometry at the mean point enters, so the
rating cannot tell a logarithmic from a circular tooth trace of the same
mean spiral angle: that is what the rest of lsbg is for.

Scope: bevel gears without hypoid offset (a = 0, so alpha_lim = 0 and the
effective pressure angle is the normal one); the drive flank. The contact
line positions of Table A.2 (for Z_LS) are those of face contact ratios
eps_vbeta >= 1 (the branch that ISO/TR 10300-30:2024's spiral bevel sample
uses); below it (spiral angles under about 28 deg for the paper's pair) the
same positions are an approximation, flagged by
:attr:`VirtualCylindricalGears.line_positions_exact`.

SI units inside (m, rad); the standard's own are mm and degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from lsbg.gear.depth import mean_depth

__all__ = ["BevelRatingGeometry", "VirtualCylindricalGears", "rating_geometry",
           "virtual_cylindrical_gears", "contact_line_length"]


@dataclass(frozen=True)
class BevelRatingGeometry:
    """A bevel gear pair as ISO 10300 describes it (ISO 23509 symbols).

    Parameters
    ----------
    teeth : tuple of int
        z1, z2 [-].
    mean_pitch_diameter : tuple of float
        d_m1, d_m2 [m].
    pitch_angle : tuple of float
        delta_1, delta_2 [rad].
    mean_normal_module : float
        m_mn [m].
    mean_spiral_angle : float
        beta_m (both members, no offset) [rad].
    normal_pressure_angle : float
        alpha_n of the drive flank; also the effective pressure angle
        alpha_e (no offset) [rad].
    mean_addendum, mean_dedendum : tuple of float
        h_am1, h_am2 and h_fm1, h_fm2 [m].
    profile_shift : float
        x_hm1 (x_hm2 = -x_hm1) [-].
    thickness_modification : tuple of float
        x_sm1, x_sm2 [-].
    face_width : float
        b [m].
    effective_face_width : float
        b_eff, the face width the contact pattern covers [m].
    tool_edge_radius : tuple of float
        rho_a01, rho_a02 [m].
    crown_dedendum_factor : float
        k_hfp = h_fm / m_mn + x_hm, the basic crown gear's dedendum factor:
        the tool's addendum is k_hfp m_mn [-].
    mean_cone_distance, outer_cone_distance : float
        R_m, R_e [m].
    lengthwise_curvature_radius : float
        r_c0, the tooth trace's radius of curvature at the mean point (the
        cutter radius of a face-milled gear) [m].
    """

    teeth: tuple
    mean_pitch_diameter: tuple
    pitch_angle: tuple
    mean_normal_module: float
    mean_spiral_angle: float
    normal_pressure_angle: float
    mean_addendum: tuple
    mean_dedendum: tuple
    profile_shift: float
    thickness_modification: tuple
    face_width: float
    effective_face_width: float
    tool_edge_radius: tuple
    crown_dedendum_factor: float
    mean_cone_distance: float
    outer_cone_distance: float
    lengthwise_curvature_radius: float


def rating_geometry(design, tool_edge_radius=0.25, effective_face_width=0.85):
    """The ISO 10300 description of one of lsbg's designs.

    The addenda and dedenda are the mean point's (ISO 10300 reads them there),
    whatever the depth's taper (:func:`lsbg.gear.depth.mean_depth`); the design's profile shift x_hm1 moves depth between the members'
    addenda and dedenda (the basic crown gear's dedendum factor is
    h_fm1 / m_mn + x_hm1) and, with the thickness modification x_smn1,
    their thicknesses; the backlash is split between the two tooth
    thicknesses (each thinner by j/2 in the transverse section). The tooth trace's curvature at the
    mean point: the cutter radius for both SBGs (ISO 10300's r_c0, the paper's arc
    and ISO 23509's face-milled trace alike); for the
    logarithmic spiral, whose tangent keeps the angle beta_p to the ray in
    the plane of action, R_m / sin(beta_m) on the pitch cone (Eq. 12-13 of
    the paper give the curve).

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    tool_edge_radius : float
        rho_a0 / m_mn, both members (the FE segment's root fillet) [-].
    effective_face_width : float
        b_eff / b [-].

    Returns
    -------
    BevelRatingGeometry
    """
    d = design
    m_mn = d.mean_module * math.cos(d.spiral_angle)
    # the mean point's depths, under every depth taper (lsbg.gear.depth)
    h_am = tuple(mean_depth(d, i, "addendum") for i in (1, 2))
    h_fm = tuple(mean_depth(d, i, "dedendum") for i in (1, 2))
    # s_mn = m_mn (pi/2 + 2 (x_hm tan(alpha_n) + x_sm)): each tooth thinner by j/2
    # (transverse), the pinion's thicker by x_smn1 and the gear's thinner
    x_sm = -d.backlash * math.cos(d.spiral_angle) / (4 * m_mn)
    x_s = (x_sm + d.thickness_modification, x_sm - d.thickness_modification)
    if d.trace != "logarithmic":
        curvature = d.cutter_radius
    else:
        curvature = d.mean_cone_distance / math.sin(d.spiral_angle)
    return BevelRatingGeometry(
        teeth=d.teeth,
        mean_pitch_diameter=tuple(2 * d.mean_pitch_radius(i) for i in (1, 2)),
        pitch_angle=tuple(d.pitch_angle(i) for i in (1, 2)),
        mean_normal_module=m_mn, mean_spiral_angle=d.spiral_angle,
        normal_pressure_angle=d.normal_pressure_angle,
        mean_addendum=h_am, mean_dedendum=h_fm, profile_shift=float(d.profile_shift),
        thickness_modification=x_s, face_width=d.face_width,
        effective_face_width=effective_face_width * d.face_width,
        tool_edge_radius=(tool_edge_radius * m_mn,) * 2,
        crown_dedendum_factor=h_fm[0] / m_mn + d.profile_shift,
        mean_cone_distance=d.mean_cone_distance,
        outer_cone_distance=d.outer_cone_distance, lengthwise_curvature_radius=curvature)


@dataclass(frozen=True)
class VirtualCylindricalGears:
    """The virtual cylindrical gear pair (ISO 10300-1:2023, A.2 and A.3).

    Lengths [m], angles [rad]; pairs are (pinion, gear).

    Attributes
    ----------
    reference_diameter, tip_diameter, base_diameter : tuple of float
        d_v, d_va, d_vb in the transverse section.
    teeth : tuple of float
        z_v.
    ratio : float
        u_v = z_v2 / z_v1.
    helix_angle, base_helix_angle, transverse_pressure_angle : float
        beta_v, beta_vb, alpha_vet.
    transverse_base_pitch, path_of_contact : float
        p_vet, g_valpha.
    transverse_contact_ratio, face_contact_ratio, contact_ratio : float
        eps_valpha, eps_vbeta (over b_eff), eps_vgamma = eps_valpha + eps_vbeta.
    face_width, effective_face_width : float
        b_v, b_v,eff.
    max_line_distance : float
        f_max: the largest distance of a contact line from the middle one.
    line_positions : tuple of float
        f_t, f_m, f_r: distances of the tip, middle and root contact lines
        from the middle of the zone of action (Table A.2).
    line_positions_exact : bool
        False where eps_vbeta < 1: Table A.2's branch for eps_vbeta >= 1
        applied outside it.
    middle_line_length : float
        l_bm.
    normal_curvature_radius, relative_curvature_radius, contact_line_inclination : float
        rho_t, rho_rel = rho_t cos^2 beta_B, beta_B.
    normal_teeth, normal_reference_diameter, normal_tip_diameter, normal_base_diameter : tuple
        z_vn, d_vn, d_van, d_vbn in the normal section.
    """

    reference_diameter: tuple
    tip_diameter: tuple
    base_diameter: tuple
    teeth: tuple
    ratio: float
    helix_angle: float
    base_helix_angle: float
    transverse_pressure_angle: float
    transverse_base_pitch: float
    path_of_contact: float
    transverse_contact_ratio: float
    face_contact_ratio: float
    contact_ratio: float
    face_width: float
    effective_face_width: float
    max_line_distance: float
    line_positions: tuple
    line_positions_exact: bool
    middle_line_length: float
    normal_curvature_radius: float
    relative_curvature_radius: float
    contact_line_inclination: float
    normal_teeth: tuple
    normal_reference_diameter: tuple
    normal_tip_diameter: tuple
    normal_base_diameter: tuple

    def as_dict(self):
        """Every quantity, pairs split into ``_pinion`` / ``_gear`` keys (SI)."""
        out = {}
        for field in fields(self):
            value = getattr(self, field.name)
            if isinstance(value, tuple) and len(value) == 2:
                out[f"{field.name}_pinion"], out[f"{field.name}_gear"] = value
            elif isinstance(value, tuple):
                for name, v in zip(("tip", "middle", "root"), value):
                    out[f"{field.name}_{name}"] = v
            else:
                out[field.name] = value
        return out


def contact_line_length(f, base_helix_angle, path_of_contact, effective_face_width,
                        face_width, max_line_distance):
    """Length of the contact line at distance f from the middle of the zone of action.

    ISO 10300-1:2023, A.2.7 (no offset): the line inclined at beta_vb across
    the zone of action, g_valpha long, is l_b0 = g_valpha / sin(beta_vb);
    the ends of the contact pattern shorten it by the factor 1 - C_lb, C_lb =
    sqrt((f / f_max)^2 + k^2 (1 - (f / f_max)^2)), k = 1 - sqrt(b_eff / b).

    Parameters
    ----------
    f : float
        Distance from the middle line [m].
    base_helix_angle : float
        beta_vb [rad], > 0 (spiral bevel gears).
    path_of_contact, effective_face_width, face_width, max_line_distance : float
        g_valpha, b_v,eff, b_v, f_max [m].

    Returns
    -------
    float
        l_b [m].
    """
    full = path_of_contact / math.sin(base_helix_angle)
    ratio = (f / max_line_distance) ** 2 if max_line_distance > 0 else 0.0
    k = 1.0 - math.sqrt(effective_face_width / face_width)
    return full * (1.0 - math.sqrt(ratio + k * k * (1.0 - ratio)))


def virtual_cylindrical_gears(geometry):
    """The virtual cylindrical gears of a pair (method B1, no hypoid offset).

    Parameters
    ----------
    geometry : BevelRatingGeometry

    Returns
    -------
    VirtualCylindricalGears

    Raises
    ------
    ValueError
        If eps_valpha >= 2 (outside ISO 10300-2/-3's scope) or the spiral
        angle is 0 (straight or Zerol bevel gears).
    """
    g = geometry
    beta = g.mean_spiral_angle
    alpha_n = g.normal_pressure_angle
    if not beta > 0:
        raise ValueError(f"mean spiral angle {math.degrees(beta):.4g} deg: this rating covers "
                         f"spiral bevel gears (beta_m > 0)")
    d_v = tuple(d / math.cos(delta) for d, delta in zip(g.mean_pitch_diameter, g.pitch_angle))
    z_v = tuple(z / math.cos(delta) for z, delta in zip(g.teeth, g.pitch_angle))
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    beta_b = math.asin(math.sin(beta) * math.cos(alpha_n))
    d_va = tuple(d + 2 * h for d, h in zip(d_v, g.mean_addendum))
    d_vb = tuple(d * math.cos(alpha_t) for d in d_v)
    p_et = math.pi * g.mean_normal_module * math.cos(alpha_t) / math.cos(beta)
    path = 0.5 * sum(math.sqrt(da * da - db * db) - d * math.sin(alpha_t)
                     for d, da, db in zip(d_v, d_va, d_vb))
    eps_a = path / p_et
    b_eff = g.effective_face_width
    eps_b = b_eff * math.sin(beta) / (math.pi * g.mean_normal_module)
    if eps_a >= 2:
        raise ValueError(f"transverse contact ratio of the virtual gears {eps_a:.3f} >= 2: "
                         f"outside ISO 10300-2/-3's scope")
    f_max = max(0.5 * (path + s * b_eff * math.tan(beta_b)) * math.cos(beta_b) for s in (1, -1))
    # Table A.2, eps_vbeta >= 1: the tip and root lines one normal base pitch
    # from the middle one (the neighbouring pairs' lines); applied below it too
    positions = (p_et * math.cos(beta_b), 0.0, -p_et * math.cos(beta_b))
    l_bm = contact_line_length(0.0, beta_b, path, b_eff, g.face_width, f_max)
    # relative curvature in the normal section at the mean point (A.39, no offset)
    r_m = g.mean_cone_distance
    inverse = math.cos(beta) ** 2 / math.sin(alpha_n) * sum(
        1 / (r_m * math.tan(delta)) for delta in g.pitch_angle)
    rho_t = 1 / inverse
    beta_contact = math.atan(math.tan(beta) * math.sin(alpha_n))
    z_vn = tuple(z / (math.cos(beta_b) ** 2 * math.cos(beta)) for z in z_v)
    d_vn = tuple(z * g.mean_normal_module for z in z_vn)
    return VirtualCylindricalGears(
        reference_diameter=d_v, tip_diameter=d_va, base_diameter=d_vb, teeth=z_v,
        ratio=z_v[1] / z_v[0], helix_angle=beta, base_helix_angle=beta_b,
        transverse_pressure_angle=alpha_t, transverse_base_pitch=p_et, path_of_contact=path,
        transverse_contact_ratio=eps_a, face_contact_ratio=eps_b, contact_ratio=eps_a + eps_b,
        face_width=g.face_width, effective_face_width=b_eff, max_line_distance=f_max,
        line_positions=positions, line_positions_exact=eps_b >= 1, middle_line_length=l_bm, normal_curvature_radius=rho_t,
        relative_curvature_radius=rho_t * math.cos(beta_contact) ** 2,
        contact_line_inclination=beta_contact, normal_teeth=z_vn, normal_reference_diameter=d_vn,
        normal_tip_diameter=tuple(d + 2 * h for d, h in zip(d_vn, g.mean_addendum)),
        normal_base_diameter=tuple(d * math.cos(alpha_n) for d in d_vn))
