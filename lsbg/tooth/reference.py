"""Closed-form reference values for the finite-element tooth compliance.

SI units inside (m, N, Pa, rad); stiffness per unit face width in N/m per m
(N/m²; 1 N/(mm·µm) = 1e9 N/m²). Three independent references:

* **ISO 6336-1:2019 method B** (§9.3): the single stiffness of a steel pair
  ``c' = C_M C_R C_B cos β / q'`` with ::

      q' = 0.04723 + 0.15551/zn1 + 0.25791/zn2 - 0.00635 x1 - 0.11654 x1/zn1
           - 0.00193 x2 - 0.24188 x2/zn2 + 0.00529 x1² + 0.00182 x2²  [mm·µm/N]
      C_B = [1 + 0.5 (1.2 - h_fP/m_n)] [1 - 0.02 (20° - α_n)],  C_M = 0.8,

  and the mesh stiffness c_γα = c' (0.75 ε_α + 0.25). Checked against worked
  example 1 of ISO/TR 6336-30:2017 (Annex A: c'_th = 17.85584, c' = 12.37047
  N/(mm·µm)); the standard's own text and equation numbers were not at hand.

* **Potential-energy (PE) method** for one spur involute tooth (Yang & Lin
  1987; Tian 2004; Chaari et al. 2009): a Timoshenko cantilever from the root
  circle to the load point, loaded along the line of action at the load angle
  α1 between the force and the normal to the tooth centre line (u along the
  centre line, h the half thickness, A = 2 h L, I = 2/3 h³ L)::

      1/k_b = ∫ [cos α1 (u_L - u) - h_L sin α1]² / (E I) du
      1/k_s = ∫ 1.2 cos² α1 / (G A) du,    1/k_a = ∫ sin² α1 / (E A) du

  The involute part starts at the base circle (the root circle if higher);
  below the base circle the tooth is Tian's straight part of constant half
  thickness h_b = r_b sin θ_b down to the root circle (the fillet is not in
  the beam). The gear body adds Sainsot, Velex & Duverger (2004)::

      1/k_f = cos² α1/(E L) [L* (u_f/S_f)² + M* (u_f/S_f) + P* (1 + Q* tan² α1)]
      X*(h_f, θ_f) = A/θ_f² + B h_f² + C h_f/θ_f + D/θ_f + E h_f + F

  with h_f = r_f/r_int, S_f = 2 r_f θ_f, u_f from the root circle to where the
  line of action crosses the centre line, and θ_f from the generating rack
  of tip radius ρ_fP: θ_f = [π/2 + 2 (h_fP - ρ_fP) tan α/m + 2 ρ_fP/(m cos α)]/z.
  The coefficient table is taken as three public implementations reproduce
  it alike (ROSS ``GearElementTVMS`` among them); the paper was not at hand.
  The Hertz term is Yang & Sun's constant 1/k_h = 4 (1 - ν²)/(π E L). Plane
  strain (wide face) uses E/(1 - ν²) in bending, compression and, by this
  module's choice (the sources do not say), Sainsot's term; shear uses
  G = E/(2 (1 + ν)) in both states.

* **Hertz line contact** (Johnson 1985, §4.2): b = sqrt(4 q R/(π E*)),
  p0 = sqrt(q E*/(π R)) = 2 q/(π b), 1/E* = Σ (1 - ν_i²)/E_i, and the approach
  of the surface to a point at depth d >> b on one body's axis (plane strain)
  ``δ = q (1 - ν²)/(π E) [2 ln(2 d/b) - ν/(1 - ν)]``. Its equation number was
  not confirmed; it was re-derived here as the d >> b limit of the integrated
  strain of the axis stresses σ_z = -p0 b/sqrt(b² + z²), σ_x = -p0 [(b² + 2 z²)
  /(b sqrt(b² + z²)) - 2 z/b] (Johnson §4.2, after McEwen), error O((b/d)²).

References
----------
.. [1] ISO 6336-1:2019, Calculation of load capacity of spur and helical
   gears - Part 1, §9.3; ISO/TR 6336-30:2017, example 1, Annex A.
.. [2] D. C. H. Yang, J. Y. Lin, Hertzian damping, tooth friction and bending
   elasticity in gear impact dynamics, J. Mech. Transm. Autom. Des. 109(2),
   189-196, 1987.
.. [3] X. Tian, Dynamic simulation for system response of gearbox including
   localized gear faults, MSc thesis, University of Alberta, 2004.
.. [4] F. Chaari, T. Fakhfakh, M. Haddar, Analytical modelling of spur gear
   tooth crack and influence on gearmesh stiffness, Eur. J. Mech. A/Solids
   28(3), 461-468, 2009.
.. [5] P. Sainsot, P. Velex, O. Duverger, Contribution of gear body to tooth
   deflections - a new bidimensional analytical formula, J. Mech. Des.
   126(4), 748-752, 2004.
.. [6] D. C. H. Yang, Z. S. Sun, A rotary model for spur gear dynamics,
   J. Mech. Transm. Autom. Des. 107(4), 529-535, 1985.
.. [7] K. L. Johnson, Contact Mechanics, Cambridge University Press, 1985, §4.2.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["iso6336_single_pair_stiffness", "iso6336_mesh_stiffness", "potential_energy_compliance",
           "spur_single_pair_stiffness", "reduced_modulus", "line_contact_half_width",
           "line_contact_peak_pressure", "line_contact_approach"]

#: ISO 6336-1 method B coefficients of q' [mm·µm/N], in the order of the module docstring.
_ISO_Q = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
#: 1 N/(mm·µm) in N/m² (1 mm·µm = 1e-9 m²).
_ISO_UNIT = 1e9
#: Sainsot et al. (2004), coefficient table: rows L*, M*, P*, Q*; columns A, B, C, D, E, F.
_SAINSOT = np.array([
    [-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045],
    [60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086],
    [-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236],
    [-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904],
])
#: Timoshenko shear coefficient of a rectangular section, as in [2]-[4].
_SHEAR_FACTOR = 1.2
# Gauss-Legendre nodes for the PE integrals over the pressure angle, where the
# integrands are smooth (h > 0 in the tooth): ~1e-12 relative against quad.
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(64)


def _positive(name, value, allow_inf=False):
    value = np.asarray(value, dtype=float)
    # NaN fails "> 0" already; the ndarray methods keep this cheap in hot loops
    if not ((value > 0).all() and (allow_inf or np.isfinite(value).all())):
        raise ValueError(f"{name} must be > 0, got {value}")
    return value


def _poisson(value, name="poisson_ratio"):
    value = np.asarray(value, dtype=float)
    if not ((value > 0) & (value < 0.5)).all():
        raise ValueError(f"{name} must lie in (0, 0.5), got {value}")
    return value


def _scalar(array):
    return array[()] if isinstance(array, np.ndarray) and array.ndim == 0 else array


def _inv(angle):   # involute function [rad]
    return np.tan(angle) - angle


# ISO 6336-1:2019 method B

def iso6336_single_pair_stiffness(virtual_teeth_1, virtual_teeth_2, profile_shift_1=0.0,
                                  profile_shift_2=0.0, normal_pressure_angle=math.radians(20),
                                  dedendum_factor=1.25, helix_angle=0.0, rim_factor=1.0,
                                  theory_factor=0.8):
    """Single stiffness c' of a tooth pair, ISO 6336-1:2019 method B (§9.3).

    ``c' = C_M C_R C_B cos β / q'``, with q' and C_B as in the module docstring.

    Parameters
    ----------
    virtual_teeth_1, virtual_teeth_2 : array_like
        Virtual numbers of teeth zn1, zn2 of pinion and wheel (for bevel
        gears those of the virtual cylindrical gears), > 0; ``numpy.inf`` for
        a rack, and ISO's zn2 = inf for an internal gear [-].
    profile_shift_1, profile_shift_2 : array_like, default 0
        Profile shift coefficients x1, x2 [-].
    normal_pressure_angle : array_like, default radians(20)
        Normal pressure angle α_n of the basic rack [rad].
    dedendum_factor : array_like, default 1.25
        Dedendum of the basic rack over the module, h_fP/m_n [-].
    helix_angle : array_like, default 0
        Reference helix angle β [rad].
    rim_factor : array_like, default 1.0
        Gear blank factor C_R, 1 for solid gears [-].
    theory_factor : array_like, default 0.8
        Correction factor C_M between theory and measurement [-].

    Returns
    -------
    numpy.ndarray or numpy.float64
        c' per unit face width [N/m²] (over 1e9: N/(mm·µm)). ISO's reduction
        below 100 N/mm of line load is left out.
    """
    zn1 = _positive("virtual_teeth_1", virtual_teeth_1, allow_inf=True)
    zn2 = _positive("virtual_teeth_2", virtual_teeth_2, allow_inf=True)
    x1 = np.asarray(profile_shift_1, dtype=float)
    x2 = np.asarray(profile_shift_2, dtype=float)
    terms = (1, 1 / zn1, 1 / zn2, x1, x1 / zn1, x2, x2 / zn2, x1**2, x2**2)
    q = sum(c * t for c, t in zip(_ISO_Q, terms))
    # C_B takes α_n in degrees.
    basic_rack = (1.0 + 0.5 * (1.2 - np.asarray(dedendum_factor, dtype=float))) \
        * (1.0 - 0.02 * (20.0 - np.degrees(normal_pressure_angle)))
    c_prime = theory_factor * rim_factor * basic_rack * np.cos(helix_angle) / q
    return _scalar(np.asarray(c_prime * _ISO_UNIT))


def iso6336_mesh_stiffness(c_prime, transverse_contact_ratio):
    """Mean mesh stiffness c_γα = c' (0.75 ε_α + 0.25), ISO 6336-1:2019 §9.3.

    Parameters
    ----------
    c_prime : array_like
        Single stiffness c' per unit face width, > 0 [N/m²].
    transverse_contact_ratio : array_like
        Transverse contact ratio ε_α, >= 1 [-].

    Returns
    -------
    numpy.ndarray or numpy.float64
        c_γα per unit face width [N/m²].
    """
    c_prime = _positive("c_prime", c_prime)
    eps = np.asarray(transverse_contact_ratio, dtype=float)
    if np.any(~(eps >= 1.0)):
        raise ValueError(f"transverse_contact_ratio must be >= 1, got {eps}")
    return _scalar(c_prime * (0.75 * eps + 0.25))


# Potential-energy method (one spur tooth)

def potential_energy_compliance(teeth, module, load_radius, face_width, young_modulus,
                                poisson_ratio, pressure_angle=math.radians(20),
                                addendum_factor=1.0, dedendum_factor=1.25, plane="strain",
                                bore_radius=None, root_fillet_factor=0.38):
    """Compliances of one spur involute tooth along the line of action, PE method.

    Parameters
    ----------
    teeth : int
        Number of teeth z, > 0 [-].
    module : float
        Module m, > 0 [m].
    load_radius : array_like
        Radius of the loaded point of the involute, in [max(r_b, r_f), r_a] [m].
    face_width : float
        Face width L, > 0 [m].
    young_modulus : float
        Young's modulus E, > 0 [Pa].
    poisson_ratio : float
        Poisson's ratio ν in (0, 0.5) [-].
    pressure_angle : float, default radians(20)
        Pressure angle α of the standard (unshifted) basic rack [rad].
    addendum_factor, dedendum_factor : float, default 1.0, 1.25
        Addendum and dedendum over the module [-].
    plane : {"strain", "stress"}, default "strain"
        Plane strain (wide face, E/(1 - ν²)) or plane stress (E) [-].
    bore_radius : float, optional
        Inner radius r_int of the gear body for Sainsot's h_f; default r_f/2 [m].
    root_fillet_factor : float, default 0.38
        Tip radius of the generating rack over the module, ρ_fP/m, for θ_f [-].

    Returns
    -------
    dict of numpy.ndarray or numpy.float64
        ``"bending"``, ``"shear"``, ``"axial"``, ``"fillet_foundation"``,
        ``"hertz"`` (a pair's constant) and ``"total"`` (the first four: the
        tooth body) [m/N]; times the face width, per unit face width [m²/N].

    Raises
    ------
    ValueError
        Naming the parameter: non-positive sizes, E <= 0, ν outside (0, 0.5),
        a load radius off the involute, an unknown plane, a bore off (0, r_f).
    """
    teeth = float(_positive("teeth", teeth))
    module = float(_positive("module", module))
    width = float(_positive("face_width", face_width))
    modulus = float(_positive("young_modulus", young_modulus))
    nu = float(_poisson(poisson_ratio))
    _positive("addendum_factor", addendum_factor)
    _positive("dedendum_factor", dedendum_factor)
    if not 0 < pressure_angle < math.pi / 2:
        raise ValueError(f"pressure_angle must lie in (0, pi/2) rad, got {pressure_angle}")
    if plane not in ("strain", "stress"):
        raise ValueError(f"plane must be 'strain' or 'stress', got {plane!r}")
    pitch = module * teeth / 2
    base = pitch * math.cos(pressure_angle)
    tip, root = pitch + addendum_factor * module, pitch - dedendum_factor * module
    if root <= 0:
        raise ValueError(f"dedendum_factor {dedendum_factor} leaves no root circle")
    # Half angle of the tooth on the base circle (thickness π m/2 on the pitch circle).
    theta_b = math.pi / (2 * teeth) + float(_inv(pressure_angle))
    if theta_b <= _inv(math.acos(base / tip)):
        raise ValueError(f"addendum_factor {addendum_factor} makes a pointed tooth")
    bore = 0.5 * root if bore_radius is None else float(bore_radius)
    if not 0 < bore < root:
        raise ValueError(f"bore_radius must lie in (0, root radius {root}) m, got {bore_radius}")
    rho = float(root_fillet_factor)
    # Half width of the generating rack's tip flat over m; < 0: beyond a full round.
    flat = math.pi / 4 - (dedendum_factor - rho) * math.tan(pressure_angle) \
        - rho / math.cos(pressure_angle)
    if rho < 0 or flat < 0:
        raise ValueError(f"root_fillet_factor must lie in [0, full round], "
                         f"got {root_fillet_factor}")
    radius = np.asarray(load_radius, dtype=float)
    lowest = max(base, root)
    if np.any(~((radius >= lowest * (1 - 1e-12)) & (radius <= tip * (1 + 1e-12)))):
        raise ValueError(f"load_radius must lie on the involute, in [{lowest}, {tip}] m, "
                         f"got {radius}")
    e_beam = modulus / (1 - nu**2) if plane == "strain" else modulus
    shear_modulus = modulus / (2 * (1 + nu))

    alpha_load = np.arccos(np.clip(base / radius, -1.0, 1.0))
    psi_load = theta_b - _inv(alpha_load)   # polar angle from the centre line
    u_load, h_load = radius * np.cos(psi_load), radius * np.sin(psi_load)
    # The line of action touches the base circle at polar angle θ_b - tan α,
    # so the load angle is α1 = tan α - θ_b (> 0: the tooth is compressed).
    load_angle = np.tan(alpha_load) - theta_b
    cos1, sin1 = np.cos(load_angle), np.sin(load_angle)

    # Involute part over the pressure angle α (Gauss-Legendre).
    alpha_start = math.acos(base / root) if root > base else 0.0
    half = (alpha_load - alpha_start)[..., None] / 2
    alpha = alpha_start + half * (1 + _NODES)
    r, psi = base / np.cos(alpha), theta_b - _inv(alpha)
    u, h = r * np.cos(psi), r * np.sin(psi)
    # du/dα = d(r cos ψ)/dα with dr/dα = r tan α, dψ/dα = -tan² α.
    weights = _WEIGHTS * half * r * np.tan(alpha) * (np.cos(psi) + np.sin(psi) * np.tan(alpha))
    moment = cos1[..., None] * (u_load[..., None] - u) - (sin1 * h_load)[..., None]
    bending = np.sum(weights * moment**2 / (e_beam * 2 / 3 * h**3 * width), axis=-1)
    length_over_area = np.sum(weights / (2 * h * width), axis=-1)
    if root < base:
        # Tian's straight part of half thickness h_b from the root to the base
        # circle; the moment is linear in u there, so ∫ m² du = Δ(m³)/(3 cos α1).
        h_b = base * math.sin(theta_b)
        u_b, u_f = base * math.cos(theta_b), math.sqrt(root**2 - h_b**2)
        m_b, m_f = (cos1 * (u_load - end) - sin1 * h_load for end in (u_b, u_f))
        bending = bending + (m_f**3 - m_b**3) / (3 * cos1 * e_beam * 2 / 3 * h_b**3 * width)
        length_over_area = length_over_area + (u_b - u_f) / (2 * h_b * width)
    shear = _SHEAR_FACTOR * cos1**2 / shear_modulus * length_over_area
    axial = sin1**2 / e_beam * length_over_area

    # Sainsot et al.: θ_f from the generating rack's tip flat (see module docstring).
    theta_f, h_f = (math.pi - 2 * flat) / teeth, root / bore
    stars = _SAINSOT @ np.array([1 / theta_f**2, h_f**2, h_f / theta_f, 1 / theta_f, h_f, 1.0])
    # u_f / S_f: the line of action crosses the centre line at u_L - h_L tan α1.
    ratio = (u_load - h_load * np.tan(load_angle) - root) / (2 * root * theta_f)
    foundation = cos1**2 / (e_beam * width) * (
        stars[0] * ratio**2 + stars[1] * ratio + stars[2] * (1 + stars[3] * np.tan(load_angle)**2))

    out = {"bending": bending, "shear": shear, "axial": axial, "fillet_foundation": foundation,
           "hertz": np.full_like(bending, 4 * (1 - nu**2) / (math.pi * modulus * width)),
           "total": bending + shear + axial + foundation}
    return {key: _scalar(np.asarray(value)) for key, value in out.items()}


def spur_single_pair_stiffness(teeth_1, teeth_2, module, load_radius_1, face_width,
                               young_modulus, poisson_ratio, pressure_angle=math.radians(20),
                               plane="strain", bore_radius_1=None, bore_radius_2=None, **tooth):
    """Stiffness of one spur tooth pair along the line of action, PE method + Hertz.

    ``1/k = 1/k_h + Σ_i (1/k_b + 1/k_s + 1/k_a + 1/k_f)_i`` at the standard
    centre distance m (z1 + z2)/2, which sets the wheel's load radius.

    Parameters
    ----------
    teeth_1, teeth_2 : int
        Numbers of teeth of pinion and wheel, > 0 [-].
    module : float
        Module m [m].
    load_radius_1 : array_like
        Radius of the contact point on the pinion's involute [m].
    face_width, young_modulus, poisson_ratio, pressure_angle, plane
        As in :func:`potential_energy_compliance`, both gears alike [m, Pa, -, rad, -].
    bore_radius_1, bore_radius_2 : float, optional
        Body inner radii of pinion and wheel [m].
    **tooth
        ``addendum_factor``, ``dedendum_factor``, ``root_fillet_factor`` [-].

    Returns
    -------
    numpy.ndarray or numpy.float64
        Pair stiffness for the face width L [N/m] (over L: per unit width [N/m²]).
    """
    z1, z2 = float(_positive("teeth_1", teeth_1)), float(_positive("teeth_2", teeth_2))
    _positive("module", module)
    r1 = np.asarray(load_radius_1, dtype=float)
    # Distance from the wheel's tangency point T2 along the line of action.
    s2 = module * (z1 + z2) / 2 * math.sin(pressure_angle) \
        - np.sqrt(np.clip(r1**2 - (module * z1 / 2 * math.cos(pressure_angle))**2, 0, None))
    r2 = np.hypot(module * z2 / 2 * math.cos(pressure_angle), s2)
    common = dict(face_width=face_width, young_modulus=young_modulus,
                  poisson_ratio=poisson_ratio, pressure_angle=pressure_angle, plane=plane)
    try:
        if np.any(s2 < 0):
            raise ValueError("load_radius beyond the line of action")
        pinion = potential_energy_compliance(z1, module, r1, bore_radius=bore_radius_1,
                                             **common, **tooth)
        wheel = potential_energy_compliance(z2, module, r2, bore_radius=bore_radius_2,
                                            **common, **tooth)
    except ValueError as error:
        if not str(error).startswith("load_radius"):
            raise
        # Name the caller's parameter: the wheel's radius follows from it.
        raise ValueError(f"load_radius_1 {r1} m puts the contact off an involute "
                         f"(wheel at {r2} m): {error}") from None
    return _scalar(np.asarray(1 / (pinion["hertz"] + pinion["total"] + wheel["total"])))


# Hertz line contact (Johnson 1985, §4.2)

def reduced_modulus(young_modulus_1, poisson_ratio_1, young_modulus_2, poisson_ratio_2):
    """Contact modulus E*: 1/E* = (1 - ν1²)/E1 + (1 - ν2²)/E2.

    Parameters
    ----------
    young_modulus_1, young_modulus_2 : array_like
        Young's moduli, > 0 [Pa].
    poisson_ratio_1, poisson_ratio_2 : array_like
        Poisson's ratios in (0, 0.5) [-].

    Returns
    -------
    numpy.ndarray or numpy.float64
        E* [Pa].
    """
    e1 = _positive("young_modulus_1", young_modulus_1)
    e2 = _positive("young_modulus_2", young_modulus_2)
    nu1 = _poisson(poisson_ratio_1, "poisson_ratio_1")
    nu2 = _poisson(poisson_ratio_2, "poisson_ratio_2")
    return _scalar(1.0 / ((1 - nu1**2) / e1 + (1 - nu2**2) / e2))


def _hertz_inputs(load_per_length, reduced_radius, reduced_modulus):
    return (_positive("load_per_length", load_per_length),
            _positive("reduced_radius", reduced_radius),
            _positive("reduced_modulus", reduced_modulus))


def line_contact_half_width(load_per_length, reduced_radius, reduced_modulus):
    """Half width of a Hertz line contact, b = sqrt(4 q R/(π E*)).

    Parameters
    ----------
    load_per_length : array_like
        Normal load per unit length q, > 0 [N/m].
    reduced_radius : array_like
        R with 1/R = 1/R1 + 1/R2, > 0 [m].
    reduced_modulus : array_like
        Contact modulus E*, > 0 [Pa].

    Returns
    -------
    numpy.ndarray or numpy.float64
        b [m].
    """
    q, radius, e_star = _hertz_inputs(load_per_length, reduced_radius, reduced_modulus)
    return _scalar(np.sqrt(4 * q * radius / (np.pi * e_star)))


def line_contact_peak_pressure(load_per_length, reduced_radius, reduced_modulus):
    """Peak pressure of a Hertz line contact, p0 = sqrt(q E*/(π R)) = 2 q/(π b).

    Parameters
    ----------
    load_per_length, reduced_radius, reduced_modulus : array_like
        q > 0 [N/m], R > 0 [m] and E* > 0 [Pa], as in
        :func:`line_contact_half_width`.

    Returns
    -------
    numpy.ndarray or numpy.float64
        p0 [Pa].
    """
    q, radius, e_star = _hertz_inputs(load_per_length, reduced_radius, reduced_modulus)
    return _scalar(np.sqrt(q * e_star / (np.pi * radius)))


def line_contact_approach(load_per_length, young_modulus, poisson_ratio, half_width, depth):
    """Approach of one body's surface to a point at depth d on its axis (plane strain).

    ``δ = q (1 - ν²)/(π E) [2 ln(2 d/b) - ν/(1 - ν)]``; the two bodies'
    approaches add. Valid for d >> b (error O((b/d)²)).

    Parameters
    ----------
    load_per_length : array_like
        Normal load per unit length q, > 0 [N/m].
    young_modulus : array_like
        Young's modulus E of the body, > 0 [Pa].
    poisson_ratio : array_like
        Poisson's ratio ν of the body in (0, 0.5) [-].
    half_width : array_like
        Contact half width b, > 0 [m].
    depth : array_like
        Depth d of the reference point below the contact centre, > 0 [m].

    Returns
    -------
    numpy.ndarray or numpy.float64
        δ [m], positive for a compression.
    """
    q = _positive("load_per_length", load_per_length)
    e = _positive("young_modulus", young_modulus)
    nu = _poisson(poisson_ratio)
    b = _positive("half_width", half_width)
    d = _positive("depth", depth)
    return _scalar(q * (1 - nu**2) / (np.pi * e) * (2 * np.log(2 * d / b) - nu / (1 - nu)))
