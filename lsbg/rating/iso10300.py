"""Contact and root stress of a bevel gear pair by ISO 10300:2023, method B1.

sigma_H = sqrt(F_n / (l_bm rho_rel)) Z_M-B Z_LS Z_E sqrt(K_A K_v K_Hbeta K_Halpha)
against sigma_HP = sigma_Hlim Z_NT Z_X Z_L Z_v Z_R Z_W Z_K Z_Hyp (ISO 10300-2);
sigma_F = F_vmt / (b_v m_mn) Y_Fa Y_Sa Y_eps Y_BS Y_LS K_A K_v K_Fbeta K_Falpha
against sigma_FP = sigma_Flim Y_ST Y_NT Y_delta,relT Y_R,relT Y_X (ISO 10300-3).
The safety factors S_H = sigma_HP / sigma_H and S_F = sigma_FP / sigma_F;
the rated torques are those at which they reach 1 (with the load factors
held at the rated load's values: none of the chosen methods depends on the
load). The permissible stresses are the endurance values (Z_NT = Y_NT = 1:
long life); :mod:`lsbg.rating.life` turns stress ratios into life ratios.

The factors that the standard leaves to the user are stated in
:class:`RatingConditions`; :func:`rate` records each factor's value.

SI units inside (N, m, Pa, rad, s).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

from lsbg.rating import factors as f
from lsbg.rating.virtual import virtual_cylindrical_gears

__all__ = ["RatingMaterial", "RatingConditions", "BevelRating", "rate"]

#: Bevel gear factor for the permissible contact stress, Z_K (ISO 10300-2:2023).
BEVEL_GEAR_FACTOR = 1.2
#: Stress correction factor of the standard test gear, Y_ST (ISO 10300-3).
TEST_GEAR_STRESS_CORRECTION = 2.0


@dataclass(frozen=True)
class RatingMaterial:
    """Case-hardened steel of both members (ISO 6336-5 quality MQ by default).

    Parameters
    ----------
    young_modulus : float
        E [Pa].
    poisson_ratio : float
        nu [-].
    contact_endurance : float
        sigma_Hlim [Pa]: ISO 6336-5 gives 1300-1650 MPa for case-carburized
        steel (MQ 1500).
    bending_endurance : float
        sigma_Flim [Pa]: 310-525 MPa (MQ 500; sigma_FE = 2 sigma_Flim).
    """

    young_modulus: float = 206e9
    poisson_ratio: float = 0.3
    contact_endurance: float = 1500e6
    bending_endurance: float = 500e6

    def __post_init__(self):
        checks = (("young_modulus", self.young_modulus, 150e9, 250e9, "Pa"),
                  ("poisson_ratio", self.poisson_ratio, 0.25, 0.35, ""),
                  ("contact_endurance", self.contact_endurance, 1300e6, 1650e6, "Pa"),
                  ("bending_endurance", self.bending_endurance, 310e6, 525e6, "Pa"))
        for name, value, low, high, unit in checks:
            if not (math.isfinite(value) and low <= value <= high):
                raise ValueError(f"{name} = {value!r}: outside case-hardened steel's range "
                                 f"{low:g}-{high:g} {unit} (ISO 6336-5)".rstrip())


@dataclass(frozen=True)
class RatingConditions:
    """The factors and service conditions ISO 10300 leaves to the user.

    Parameters
    ----------
    application_factor : float
        K_A [-], 1 for a uniform driver and load (ISO 10300-1, Annex B:
        1-2.25).
    dynamic_factor : float
        K_v [-], >= 1: lsbg's own dynamic factor by default (the study's
        largest tangential force over its static value).
    mounting : {"both_straddle", "one_cantilever", "both_cantilever"}
    contact_pattern : {"full_load", "light_test_load", "estimated"}
        How the contact pattern was verified (K_Hbeta-be, Table 4).
    accuracy_grade : int
        ISO 17485 grade B, 2-11: K_Halpha = K_Falpha by method C.
    transverse_load_factor : float, optional
        K_Halpha = K_Falpha given (e.g. from method B), 1-2; None: method C.
    profile_crowning : {"low", "high"}
        e_LS of Z_LS.
    oil_viscosity : float
        nu_40 [m^2/s].
    flank_roughness, root_roughness : float
        Rz [m].
    effective_face_width : float
        b_eff / b [-].
    """

    application_factor: float = 1.0
    dynamic_factor: float = 1.0
    mounting: str = "one_cantilever"
    contact_pattern: str = "light_test_load"
    accuracy_grade: int = 6
    transverse_load_factor: float | None = None
    profile_crowning: str = "low"
    oil_viscosity: float = 150e-6
    flank_roughness: float = 8e-6
    root_roughness: float = 16e-6
    effective_face_width: float = 0.85

    def __post_init__(self):
        ranges = (("application_factor", self.application_factor, 1.0, 2.25),
                  ("dynamic_factor", self.dynamic_factor, 1.0, 3.0),
                  ("accuracy_grade", self.accuracy_grade, 2, 11),
                  ("oil_viscosity", self.oil_viscosity, 10e-6, 2000e-6),
                  ("flank_roughness", self.flank_roughness, 0.5e-6, 40e-6),
                  ("root_roughness", self.root_roughness, 1e-6, 40e-6),
                  ("effective_face_width", self.effective_face_width, 0.5, 1.0))
        if self.transverse_load_factor is not None:
            ranges += (("transverse_load_factor", self.transverse_load_factor, 1.0, 2.0),)
        for name, value, low, high in ranges:
            if isinstance(value, bool) or not (math.isfinite(value) and low <= value <= high):
                raise ValueError(f"{name} = {value!r}: outside ISO 10300's range {low:g}-{high:g}")
        for name, value, allowed in (("mounting", self.mounting, f.MOUNTING_FACTORS["full_load"]),
                                     ("contact_pattern", self.contact_pattern, f.MOUNTING_FACTORS),
                                     ("profile_crowning", self.profile_crowning, ("low", "high"))):
            if value not in allowed:
                raise ValueError(f"{name} = {value!r}: one of {sorted(allowed)}")
        if int(self.accuracy_grade) != self.accuracy_grade:
            raise ValueError(f"accuracy_grade = {self.accuracy_grade!r}: an integer 2-11")


@dataclass(frozen=True)
class BevelRating:
    """Stresses, permissible stresses and safety factors of both members.

    Stresses [Pa], torques [N m]; pairs are (pinion, gear).

    Attributes
    ----------
    pinion_torque : float
        T_1 rated.
    contact_stress : float
        sigma_H (the same on both flanks in contact).
    permissible_contact_stress, contact_safety : tuple
        sigma_HP, S_H.
    root_stress, permissible_root_stress, bending_safety : tuple
        sigma_F, sigma_FP, S_F.
    nominal_contact_stress : float
        sigma_H0, before the load factors.
    rated_pinion_torque_contact, rated_pinion_torque_bending : float
        T_1 at which the smaller S_H, S_F is 1.
    factors : dict
        Every factor and intermediate value by its ISO symbol (SI).
    """

    pinion_torque: float
    contact_stress: float
    nominal_contact_stress: float
    permissible_contact_stress: tuple
    contact_safety: tuple
    root_stress: tuple
    permissible_root_stress: tuple
    bending_safety: tuple
    rated_pinion_torque_contact: float
    rated_pinion_torque_bending: float
    factors: dict = field(default_factory=dict)


def rate(geometry, pinion_torque, pinion_speed, material=None, conditions=None):
    """ISO 10300 method B1 rating of a bevel gear pair (no hypoid offset, drive flank).

    Parameters
    ----------
    geometry : lsbg.rating.virtual.BevelRatingGeometry
    pinion_torque : float
        T_1 [N m], > 0.
    pinion_speed : float
        n_1 [rad/s], > 0 (Z_v).
    material : RatingMaterial, optional
    conditions : RatingConditions, optional

    Returns
    -------
    BevelRating
    """
    material = RatingMaterial() if material is None else material
    conditions = RatingConditions() if conditions is None else conditions
    if not (pinion_torque > 0 and pinion_speed > 0):
        raise ValueError(f"pinion torque {pinion_torque!r} N m and speed {pinion_speed!r} rad/s "
                         f"must be positive")
    g, c = geometry, conditions
    v = virtual_cylindrical_gears(g)
    d_m1 = g.mean_pitch_diameter[0]
    force = 2 * pinion_torque / d_m1  # F_mt1 = F_vmt (no offset)
    normal = force / (math.cos(g.normal_pressure_angle) * math.cos(g.mean_spiral_angle))
    speed = pinion_speed * d_m1 / 2
    k_hbeta, k_fbeta, k_f0 = f.face_load_factors(g, c.mounting, c.contact_pattern)
    k_alpha = (f.transverse_load_factor(c.accuracy_grade, v.contact_ratio)
               if c.transverse_load_factor is None else c.transverse_load_factor)
    load = c.application_factor * c.dynamic_factor
    z_mb, z_ls = f.mid_zone_factor(v), f.load_sharing_factor(v, c.profile_crowning)
    z_e = f.elasticity_factor(material.young_modulus, material.poisson_ratio)
    z_l, z_v, z_r = f.lubricant_film_factors(material.contact_endurance, c.oil_viscosity, speed,
                                             c.flank_roughness, v.relative_curvature_radius)
    sigma_h0 = math.sqrt(normal / (v.middle_line_length * v.relative_curvature_radius)) \
        * z_mb * z_ls * z_e
    sigma_h = sigma_h0 * math.sqrt(load * k_hbeta * k_alpha)
    # Z_NT = Z_X = Z_W = Z_Hyp = 1: long life, case-hardened, equal hardness, no offset
    sigma_hp = material.contact_endurance * z_l * z_v * z_r * BEVEL_GEAR_FACTOR
    y_eps, y_bs = f.contact_ratio_factor(v), f.bevel_spiral_angle_factor(g, v)
    y_ls = z_ls ** 2
    y_r, y_x = f.surface_condition_factor(c.root_roughness), f.size_factor(g.mean_normal_module)
    forms = [f.tooth_form(g, v, member) for member in (1, 2)]
    nominal = force / (v.face_width * g.mean_normal_module)
    sigma_f0 = tuple(nominal * t.form_factor * t.stress_correction * y_eps * y_bs * y_ls
                     for t in forms)
    sigma_f = tuple(s * load * k_fbeta * k_alpha for s in sigma_f0)
    y_delta = tuple(f.notch_sensitivity_factor(t.notch_parameter) for t in forms)
    sigma_fp = tuple(material.bending_endurance * TEST_GEAR_STRESS_CORRECTION * y * y_r * y_x
                     for y in y_delta)
    s_h = (sigma_hp / sigma_h,) * 2
    s_f = tuple(p / s for p, s in zip(sigma_fp, sigma_f))
    values = {
        "F_mt1": force, "F_n": normal, "v_mt": speed, "K_A": c.application_factor,
        "K_v": c.dynamic_factor, "K_Hbeta": k_hbeta, "K_Fbeta": k_fbeta, "K_F0": k_f0,
        "K_Halpha": k_alpha, "K_Falpha": k_alpha, "Z_M-B": z_mb, "Z_LS": z_ls, "Z_E": z_e,
        "Z_L": z_l, "Z_v": z_v, "Z_R": z_r, "Z_K": BEVEL_GEAR_FACTOR, "Z_NT": 1.0,
        "Y_eps": y_eps, "Y_BS": y_bs, "Y_LS": y_ls, "Y_R,relT": y_r, "Y_X": y_x,
        "Y_ST": TEST_GEAR_STRESS_CORRECTION, "Y_NT": 1.0,
        "sigma_F0_pinion": sigma_f0[0], "sigma_F0_gear": sigma_f0[1],
    }
    for name, form, y in zip(("pinion", "gear"), forms, y_delta):
        values.update({f"{key}_{name}": value for key, value in asdict(form).items()})
        values[f"Y_delta,relT_{name}"] = y
    values.update({k: float(x) for k, x in v.as_dict().items()})
    return BevelRating(
        pinion_torque=pinion_torque, contact_stress=sigma_h, nominal_contact_stress=sigma_h0,
        permissible_contact_stress=(sigma_hp, sigma_hp), contact_safety=s_h,
        root_stress=sigma_f, permissible_root_stress=sigma_fp, bending_safety=s_f,
        # sigma_H grows as sqrt(T), sigma_F as T, with load-independent factors
        rated_pinion_torque_contact=pinion_torque * min(s_h) ** 2,
        rated_pinion_torque_bending=pinion_torque * min(s_f), factors=values)
