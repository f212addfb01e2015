"""What the reports check at a design point, computed once: ``lsbg checks``.

The verification report checks that nobody tuned what must hold by
construction, and the paper report explains its point model's fluctuations by
the contact resonance. Both were computed inside the notebooks; here they are
computed by one command per design point and written to one dataset
(:func:`design_point_checks`), which the reports only read
(:mod:`lsbg.tables.verification`):

* :func:`conjugacy_errors`: the distance of both members' flanks from the
  contact lines in the plane of action (exact line contact, DESIGN.md §2);
* :func:`loaded_tca_checks`: the line model's loaded TCA without load, at
  twice the load and with two and four times the slices, and the line
  stiffness that gives ISO 6336-1's c_gamma;
* :func:`contact_state_checks`: the surface TCA on the conjugate and the
  crowned pair, the line model on the separation field, a displaced pair;
* :func:`contact_resonance`: the gear's torsional frequency on the point
  model's linearised contact at the static load;
* what the checks' bounds (:func:`lsbg.tables.verification.verification_checks`)
  need from a stage: :func:`stiffness_bounds`, :func:`linearity_bound`,
  :func:`peak_to_peak_resolution`, the coarse-grid and half-crowning TCAs.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

__all__ = ["conjugacy_errors", "contact_resonance", "loaded_tca_checks", "check_crowning",
           "contact_state_checks", "design_point_checks", "stiffness_bounds",
           "linearity_bound", "peak_to_peak_resolution", "point_check_rows",
           "CHECK_VARIABLES", "CONJUGACY_VARIABLES", "TCA_POSITIONS", "LTCA_PHASES",
           "RESONANCE_POSITIONS", "EPS", "ROUNDINGS"]

#: Positions of each surface TCA of :func:`contact_state_checks` over a mesh cycle [-].
TCA_POSITIONS = 100
#: Mesh positions of each loaded TCA of :func:`loaded_tca_checks` [-].
LTCA_PHASES = 64
#: Pinion angles over one pitch at which :func:`contact_resonance` linearises [-].
RESONANCE_POSITIONS = 12
#: The crowning checked where the loaded TCA ran on conjugate flanks [m]
#: (lengthwise, profile: the practice default of the ``flank_modification`` section).
DEFAULT_CROWNING = (25e-6, 5e-6)

#: float64's epsilon; a generous count of the roundings a computed point, normal or
#: angle carries (two rotations of three-term sums, a unit vector, an angle) [-].
EPS, ROUNDINGS = float(np.finfo(float).eps), 16
#: lsbg.contact.statics.static_mismatch stops at a bracket of ATOL + RTOL |eps| [rad, -].
STATIC_ATOL, STATIC_RTOL = 1e-18, 1e-14
#: lsbg.tca.loaded.loaded_tca's torque difference over +-STIFFNESS_STEP max|TE| [-].
STIFFNESS_STEP = 1e-6

#: Scalars of :func:`design_point_checks`: name -> (the key of the check functions'
#: answers, units, long name).
CHECK_VARIABLES = {
    "unloaded_te_max": ("unloaded_te_max_rad", "rad",
                        "largest transmission error without load, from the flank surfaces"),
    "linearity_error": ("linearity_error", "1",
                        "largest deviation of TE(2T)/TE(T) from 2 (line model, loaded TCA)"),
    "te_pp_slices_x2_change": ("te_pp_slices_x2_change_percent", "percent",
                               "change of the loaded TE peak to peak with twice the slices"),
    "te_pp_slices_x4_change": ("te_pp_slices_x4_change_percent", "percent",
                               "change of the loaded TE peak to peak with four times the slices"),
    "calibrated_line_stiffness": ("k_l_for_c_gamma_20_N_per_mm_um", "N/(mm um)",
                                  "line stiffness that gives c_gamma = 20 N/(mm um)"),
    "conjugate_te_pp": ("conjugate_te_pp_rad", "rad",
                        "conjugate, aligned pair: unloaded TE peak to peak (surfaces)"),
    "backlash_error": ("backlash_error", "1",
                       "conjugate pair: least backlash over the design's j_t/r_m2, minus 1"),
    "crowned_te_pp": ("crowned_te_pp_urad", "urad",
                      "crowned pair: unloaded TE peak to peak (surfaces)"),
    "designed_te_pp": ("designed_te_pp_urad", "urad",
                       "crowned pair: unloaded TE peak to peak of the closed-form parabola"),
    "line_model_te_difference": ("line_model_te_difference", "1",
                                 "line model on the separation field over the surface TCA, "
                                 "unloaded TE peak to peak, minus 1"),
    "pattern_shift_plus": ("pattern_shift_plus_mm", "mm",
                           "bearing pattern's movement towards the heel, offset E = +0.1 mm"),
    "pattern_shift_minus": ("pattern_shift_minus_mm", "mm",
                            "bearing pattern's movement towards the heel, offset E = -0.1 mm"),
    "resonance_frequency": ("frequency_hz", "Hz",
                            "gear's torsional resonance on the point model's linearised "
                            "contact at the static load, mean over a pinion pitch"),
    "resonance_frequency_min": ("frequency_min_hz", "Hz", "the same, least over a pinion pitch"),
    "resonance_frequency_max": ("frequency_max_hz", "Hz", "the same, largest over a pinion pitch"),
    "resonance_stiffness": ("stiffness_N_m_per_rad", "N m/rad",
                            "point model's linearised mesh stiffness at the static load, mean"),
    "linearity_bound": ("linearity_bound", "1", "bound of the linearity error"),
    "stiffness_slice_bias": ("stiffness_slice_bias", "1", "slices' exact stiffness bias"),
    "stiffness_sampling_bound": ("stiffness_sampling_bound", "1", "stiffness bound of the phases"),
    "stiffness_roundoff_bound": ("stiffness_roundoff_bound", "1", "stiffness round-off bound"),
    "conjugate_te_coarse_max": ("conjugate_te_coarse_max_rad", "rad",
                                "conjugate pair: largest TE, grid of every other point"),
    "backlash_coarse_error": ("backlash_coarse_error", "1",
                              "conjugate pair: least backlash, that grid, over j_t/r_m2, - 1"),
    "crowned_half_te_pp": ("crowned_half_te_pp_urad", "urad", "half the crowning: TE peak to peak"),
    "crowned_te_sampling": ("crowned_te_sampling_urad", "urad", "crowned TE sampling bound"),
    "line_model_te_sampling": ("line_model_te_sampling_urad", "urad", "line model TE sampling"),
    "line_model_slicing": ("line_model_slicing_urad", "urad", "line model slicing bound, as TE"),
}

#: Variables of :func:`design_point_checks` over the conjugacy check's mesh positions:
#: name -> (column of :func:`conjugacy_errors`, units, long name).
CONJUGACY_VARIABLES = {
    "conjugacy_pinion_distance": ("pinion_distance_m", "m",
                                  "largest distance of the pinion's flank from the contact line"),
    "conjugacy_gear_distance": ("gear_distance_m", "m",
                                "largest distance of the gear's flank from the contact line"),
    "conjugacy_normal_mismatch": ("normal_mismatch", "1",
                                  "largest |n1 + n2| of the flank normals on the contact line"),
}


def conjugacy_errors(design, side="drive", phases=25, n=17) -> pd.DataFrame:
    """Distance between the pinion and gear flanks on the contact lines.

    At each mesh position (turn Ψ of the generating curve) both members are
    turned so that tooth 0's contact line lies at Ψ; the flank points of both
    members at the contact-line points (same cone distance and polar angle)
    must coincide with the line and their normals must be opposite: exact
    line contact (DESIGN.md §2).

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    side : {'drive', 'coast'}
    phases : int, default 25
        Mesh positions across the field of contact (and a little beyond) [-].
    n : int, default 17
        Points per contact line; the end points (possibly on the base cone,
        where the polar angle is a singular parameter) are left out [-].

    Returns
    -------
    pandas.DataFrame
        Per mesh position with a contact line: ``phase_deg``,
        ``pinion_distance_m`` and ``gear_distance_m`` (largest distance of a
        member's flank point from the contact line point) [m] and
        ``normal_mismatch`` (largest |n1 + n2|) [-].
    """
    from lsbg.gear.geometry import GearPair
    from lsbg.gear.vectors import rotate

    pair = GearPair(design)
    lo, hi = pair.planes[side].field[:2]
    rows = []
    for phase in np.linspace(lo - 0.3, hi + 0.3, phases):
        rho, points, _ = pair.contact_line(side, phase, n=n)
        if rho.size < 3:
            continue
        rho, points = rho[1:-1], points[1:-1]
        flanks = []
        for member in (1, 2):
            u = pair.rotation_axis[member]
            rotation = (phase / pair.axis_normal_component(member, side)
                        - pair.flank_offset[(member, side)])
            polar = np.arccos(points @ pair.axis[member] / np.linalg.norm(points, axis=1))
            body, normals = pair.flank(member, side, rho, polar)
            flanks.append((rotate(body, u, rotation), rotate(normals, u, rotation)))
        (p1, n1), (p2, n2) = flanks
        rows.append({"phase_deg": math.degrees(phase),
                     "pinion_distance_m": float(np.max(np.linalg.norm(p1 - points, axis=1))),
                     "gear_distance_m": float(np.max(np.linalg.norm(p2 - points, axis=1))),
                     "normal_mismatch": float(np.max(np.linalg.norm(n1 + n2, axis=1)))})
    return pd.DataFrame(rows, columns=["phase_deg", "pinion_distance_m", "gear_distance_m",
                                       "normal_mismatch"])


def contact_resonance(geometry_dir, run=None, positions=RESONANCE_POSITIONS) -> dict:
    """Torsional resonance of the gear on the linearised contact at the static load.

    The pinion follows its prescribed motion, so the gear (inertia J2) rests
    on the mesh spring k = −dT/dφ2 of the IMPACT law at the deflection that
    carries the load: f = √(k/J2) / 2π. The stiffness varies with the mesh
    position (the number of tooth pairs and their lines change), so it is
    evaluated at ``positions`` pinion angles over one pinion pitch.

    Parameters
    ----------
    geometry_dir : str or os.PathLike
        Geometry directory of the design point.
    run : xarray.Dataset, optional
        Run dataset whose contact parameters and load torque to use (the
        paper's otherwise).
    positions : int, default 12
        Mesh positions over one pinion pitch [-].

    Returns
    -------
    dict
        ``frequency_hz`` (mean), ``frequency_min_hz``, ``frequency_max_hz``
        [Hz] and ``stiffness_N_m_per_rad`` (mean) [N m/rad].
    """
    from lsbg.contact import ContactParameters
    from lsbg.dynamics import SimulationSettings, load_model

    params = ContactParameters.from_dict({} if run is None else run.attrs, prefix="contact_")
    model = load_model(geometry_dir, params)
    load = (float(run.attrs["solver_load_torque_N_m"])
            if run is not None and "solver_load_torque_N_m" in run.attrs
            else SimulationSettings().load_torque)
    z1 = model.pair.design.pinion_teeth
    stiffness = []
    for phi1 in np.linspace(0.0, 2 * math.pi / z1, positions, endpoint=False):
        phi2 = model.contact.static_gear_angle(load, pinion_angle=phi1)
        h = 1e-7
        plus = model.contact.forces(phi1, phi2 + h).gear_torque
        minus = model.contact.forces(phi1, phi2 - h).gear_torque
        stiffness.append(abs(plus - minus) / (2 * h))
    stiffness = np.asarray(stiffness)
    freq = np.sqrt(stiffness / model.gear_inertia) / (2 * math.pi)
    return {"frequency_hz": float(freq.mean()), "frequency_min_hz": float(freq.min()),
            "frequency_max_hz": float(freq.max()),
            "stiffness_N_m_per_rad": float(stiffness.mean())}


def peak_to_peak_resolution(values, cusps=False):
    """How far the peak to peak of one evenly sampled period can be off [unit of ``values``]:
    the true maximum lies within a step of the sampled one, above it by at most half the
    larger neighbouring step where the curve is concave there (convex at the minimum), by
    at most that step with ``cusps`` (two convex arcs meeting: a crowned pair's changeover,
    slope < step / (h (1 - h)) for a step h in periods)."""
    v = np.asarray(values, dtype=float)
    steps = np.abs(np.diff(np.r_[v[-1], v, v[0]]))  # steps[i]: into sample i, [i+1]: out
    return float(sum(max(steps[i], steps[i + 1]) for i in (np.argmax(v), np.argmin(v)))
                 / (1 if cusps else 2))


def linearity_bound(single, e2, terms):
    """Bound of |TE(2T)/TE(T) - 2| of the line model's loaded TCA on conjugate flanks [-]:
    the static solve stops within STATIC_ATOL + STATIC_RTOL |eps|, a torque sums ``terms``
    products, TE = phi1 z1/z2 - phi2 cancels angles of size A (four roundings), so each TE
    is off by a relative rho, their ratio by 2 (rho(T) + rho(2T)) <= 4 rho(T). ``single``:
    the loaded TCA at T (:func:`lsbg.tca.loaded.loaded_tca`); ``e2`` = sin(delta_b2) [-]."""
    te = np.abs(single.transmission_error.values) * 1e-6
    kinematic = np.radians(single.pinion_angle.values) * single.attrs["design_pinion_teeth"] \
        / single.attrs["design_gear_teeth"]
    scale = max(np.abs(kinematic).max(), np.abs(kinematic - te).max())
    return float(4 * (STATIC_RTOL + (terms + 1) * EPS
                      + (STATIC_ATOL / e2 + 4 * EPS * scale) / te.min()))


def stiffness_bounds(contact, mesh):
    """How far a loaded TCA's mean mesh stiffness can be off its closed form [-].

    The closed form counts each band at its centre's lever L while in the
    field; a band the field's edge cuts acts at its inside part's middle,
    L + t dL with t = (1 - f)/2 at the fraction f inside, which adds
    K dL^2 dpsi / (24 L^2 Psi_p) over entry and exit (K its stiffness, dpsi
    its turn across the edge): the slices' exact **bias** (slices^-3). The
    mean of N phases, a periodic rectangle rule, is off by at most h^2 V /
    (12 Psi_p), h = Psi_p / N, V the total variation of the stiffness's slope
    (its jumps where bands start or end crossing an edge, net of the
    neighbour's, and its turns with the lever), or by the bands' steps / N
    (Koksma) for a band crossing at once. A sample, the torque's central
    difference over +-STIFFNESS_STEP max|TE|, carries the mismatch's
    roundings (4 EPS at the angles' scale) and the torque sum's.

    ``contact`` is the loaded TCA's line model (lsbg.contact.MeshContact: its
    band table), ``mesh`` the loaded TCA (``lsbg ltca``); returns
    ``stiffness_slice_bias`` (signed), ``stiffness_sampling_bound`` and
    ``stiffness_roundoff_bound``, relative to the closed form [-].
    """
    from lsbg.contact import kernels as k
    from lsbg.contact.mesh import MAX_PAIRS

    sides, band = contact.arrays[1], contact.arrays[2][0]
    lever, d_lever = band[:, k.B_LEVER], band[:, k.B_D_LEVER]
    a, b = band[:, k.B_THETA_IN], band[:, k.B_THETA_OUT]
    full = (contact.params.line_stiffness * contact.e2**2 * lever**2 * band[:, k.B_LENGTH]
            / contact.base_radius**2)   # each band's K [N/m]
    pitch, mean = contact.pitch, contact.mean_mesh_stiffness()
    bias = float(np.sum(full * (d_lever / lever)**2 * np.abs(b - a)) / (24 * pitch))
    psi_lo, psi_hi = sides[0, k.S_PSI_LO], sides[0, k.S_PSI_HI]
    sigma = np.sign(b - a) * d_lever / (2 * lever)   # lever / L = 1 + sigma (1 - f), entry
    jumps, turns = {}, 0.0
    for K, w, s, lo, hi in zip(full, np.abs(b - a), sigma, np.minimum(a, b), np.maximum(a, b)):
        if w <= 0.0:
            turns = math.inf
            break
        # slope jumps: entry f 0 -> 1 across psi_lo, exit 1 -> 0 across psi_hi (sigma -> -sigma)
        for x, jump in ((psi_lo - hi, (1 + s)**2), (psi_lo - lo, -(1 - 2 * s)),
                        (psi_hi - hi, -(1 + 2 * s)), (psi_hi - lo, (1 - s)**2)):
            jumps[x] = jumps.get(x, 0.0) + K * jump / w
        turns += K / w * (abs(4 * s + s * s) + abs(s * s - 4 * s))
    phases = int(mesh.attrs["phases"])
    peano = (pitch / phases)**2 * (sum(map(abs, jumps.values())) + turns) / (12 * pitch)
    koksma = 2 * float(np.sum(full * (1 + np.abs(sigma))**2)) / phases
    te = np.abs(mesh.transmission_error.values) * 1e-6
    pinion = np.abs(np.radians(mesh.pinion_angle.values))
    gear = pinion * contact.e1 / contact.e2 + te
    step = STIFFNESS_STEP * te.max() if te.max() > 0 else 1e-9
    scale = max(pinion.max() * contact.e1, gear.max() * contact.e2, pitch)
    roundoff = ((4 * EPS * scale + EPS * gear.max() * contact.e2) / (step * contact.e2)
                + contact.params.slices * MAX_PAIRS * EPS * te.max() / step)
    return {"stiffness_slice_bias": bias / mean,
            "stiffness_sampling_bound": min(peano, koksma) / mean,
            "stiffness_roundoff_bound": float(roundoff)}


def loaded_tca_checks(pair, params, load, phases=LTCA_PHASES) -> dict:
    """What the line model's loaded TCA must satisfy on a design, checked.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    params : lsbg.contact.ContactParameters
        The line model's parameters (those of the design point's loaded TCA).
    load : float
        The load on the gear [N m].
    phases : int
        Mesh positions of each loaded TCA [-].

    Returns
    -------
    dict
        ``unloaded_te_max_rad``: the largest unloaded transmission error from
        the flank surfaces (classical TCA) at five pinion angles over a pitch
        [rad]; ``linearity_error``: the largest deviation of TE(2T)/TE(T)
        from 2 [-]; ``te_pp_slices_x2_change_percent`` and
        ``te_pp_slices_x4_change_percent``: the change of the peak-to-peak TE
        with two and four times the slices [%];
        ``k_l_for_c_gamma_20_N_per_mm_um``: the line stiffness that gives
        ISO 6336-1's c_gamma = 20 N/(mm·µm) [N/(mm·µm)]; ``linearity_bound``
        [-] (:func:`linearity_bound`).
    """
    from lsbg.contact import MeshContact, calibrated_line_stiffness
    from lsbg.contact.mesh import MAX_PAIRS
    from lsbg.tca.loaded import loaded_tca, unloaded_transmission_error

    design = pair.design
    unloaded = unloaded_transmission_error(
        pair, np.linspace(0.0, 2 * math.pi / design.pinion_teeth, 5))
    double = loaded_tca(MeshContact(pair, params), 2 * load, phases=phases)
    single = loaded_tca(MeshContact(pair, params), load, phases=phases)
    linear = float(np.max(np.abs(double.transmission_error / single.transmission_error - 2)))
    pp = {n: loaded_tca(MeshContact(pair, params.replace(slices=n)), load, phases=phases)
          .attrs["transmission_error_peak_to_peak_urad"]
          for n in (2 * params.slices, 4 * params.slices)}
    pp[params.slices] = single.attrs["transmission_error_peak_to_peak_urad"]
    return {"unloaded_te_max_rad": float(np.max(np.abs(unloaded))),
            "linearity_error": linear,
            "te_pp_slices_x2_change_percent": 100 * (pp[2 * params.slices] / pp[params.slices] - 1),
            "te_pp_slices_x4_change_percent": 100 * (pp[4 * params.slices] / pp[params.slices] - 1),
            "k_l_for_c_gamma_20_N_per_mm_um": calibrated_line_stiffness(pair) / 1e9,
            "linearity_bound": linearity_bound(single, math.sin(design.base_cone_angle(2)),
                                               params.slices * MAX_PAIRS)}


def check_crowning(attrs):
    """The crowning the contact-state checks run on: a loaded TCA's, or the practice default.

    Parameters
    ----------
    attrs : dict
        The attributes of the design point's loaded TCA (``lsbg ltca``), its
        ``flank_modification_*_um``.

    Returns
    -------
    lsbg.tca.modification.FlankModification
        Its lengthwise and profile crowning; :data:`DEFAULT_CROWNING` where it
        has neither or one of them is zero (the checks need both).
    """
    from lsbg.tca.modification import FlankModification

    lengthwise = float(attrs.get("flank_modification_lengthwise_crowning_um", 25.0) or 25.0)
    profile = float(attrs.get("flank_modification_profile_crowning_um", 5.0) or 5.0)
    crowning = FlankModification(lengthwise * 1e-6, profile * 1e-6)
    if crowning.lengthwise_crowning == 0 or crowning.profile_crowning == 0:
        crowning = FlankModification(*DEFAULT_CROWNING)
    return crowning


def contact_state_checks(pair, modification, positions=TCA_POSITIONS) -> dict:
    """What the contact-state analysis must satisfy on a design, checked.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification : lsbg.tca.modification.FlankModification
        The crowning to check (with lengthwise and profile crowning).
    positions : int
        Positions of each TCA over a mesh cycle [-].

    Returns
    -------
    dict
        ``conjugate_te_pp_rad``: the conjugate, aligned pair's unloaded TE
        peak to peak from the surfaces [rad]; ``backlash_error``: its least
        backlash against the design's j_t / r_m2, relative [-];
        ``crowned_te_pp_urad`` and ``designed_te_pp_urad``: the crowned
        pair's TE peak to peak from the surfaces and from the closed form
        [µrad]; ``line_model_te_difference``: the line model's unloaded TE on
        the separation field against the surface TCA's, relative [-];
        ``pattern_shift_plus_mm``, ``pattern_shift_minus_mm``: the pattern
        centre's movement towards the heel for an offset E = +0.1 and -0.1 mm
        [mm] (the displacement that moves both types' patterns most); for their
        bounds (:func:`point_check_rows`), the ``*_coarse_*`` on the grid of every
        other point and the ``crowned_half_*``, ``*_sampling_*`` and ``*_slicing_*``
        of :data:`CHECK_VARIABLES`.
    """
    from lsbg.contact import ContactParameters, MeshContact
    from lsbg.tca.analysis import FACE_POINTS, PROFILE_POINTS, tooth_contact_analysis
    from lsbg.tca.loaded import loaded_tca
    from lsbg.tca.misalignment import Misalignment
    from lsbg.tca.modification import FlankModification
    from lsbg.tca.separation import separation_field

    design = pair.design
    conjugate = tooth_contact_analysis(pair, positions=positions)
    coarse = tooth_contact_analysis(pair, positions=positions,
                                    grid=((FACE_POINTS + 1) // 2, (PROFILE_POINTS + 1) // 2))
    backlash = design.backlash / design.mean_pitch_radius(2) * 1e6
    crowned = tooth_contact_analysis(pair, modification, positions=positions)
    half = tooth_contact_analysis(pair, FlankModification(
        modification.lengthwise_crowning / 2, modification.profile_crowning / 2,
        modification.bias / 2), positions=positions)
    line_params = ContactParameters(model="line")
    line = loaded_tca(MeshContact(pair, line_params,
                                  separation=separation_field(pair, modification)),
                      0.0, phases=positions)
    # the slices' centres miss at most (C_L + C_P k^2 + |bias| k) / slices^2 of the least
    # separation along v = a + k u; as TE over the lever (designed_transmission_error's k)
    plane, rm = pair.planes["drive"], design.mean_cone_distance
    beta = abs(float(plane.curve.ray_angle(rm)))
    k = math.tan(beta) * design.face_width / (rm * (plane.field[1] - plane.field[0]))
    curvature = (modification.lengthwise_crowning + modification.profile_crowning * k * k
                 + abs(modification.bias) * k) / (rm * math.cos(beta) * math.sin(
                     design.base_cone_angle(2)))
    centre = crowned.attrs["pattern_centre_cone_distance_mm"]
    shifted = {sign: tooth_contact_analysis(pair, modification,
                                            Misalignment(offset=sign * 1e-4),
                                            positions=positions)
               for sign in (1, -1)}
    surface_pp = crowned.attrs["transmission_error_peak_to_peak_urad"]
    return {
        "conjugate_te_pp_rad": conjugate.attrs["transmission_error_peak_to_peak_urad"] * 1e-6,
        "backlash_error": conjugate.attrs["backlash_min_urad"] / backlash - 1,
        "crowned_te_pp_urad": surface_pp,
        "designed_te_pp_urad": crowned.attrs["designed_transmission_error_peak_to_peak_urad"],
        "line_model_te_difference":
            line.attrs["transmission_error_peak_to_peak_urad"] / surface_pp - 1,
        "pattern_shift_plus_mm": shifted[1].attrs["pattern_centre_cone_distance_mm"] - centre,
        "pattern_shift_minus_mm": shifted[-1].attrs["pattern_centre_cone_distance_mm"] - centre,
        "conjugate_te_coarse_max_rad": float(np.abs(coarse.transmission_error).max()) * 1e-6,
        "backlash_coarse_error": coarse.attrs["backlash_min_urad"] / backlash - 1,
        "crowned_half_te_pp_urad": half.attrs["transmission_error_peak_to_peak_urad"],
        "crowned_te_sampling_urad": peak_to_peak_resolution(crowned.transmission_error, True),
        "line_model_te_sampling_urad": peak_to_peak_resolution(line.transmission_error, True),
        "line_model_slicing_urad": curvature / line_params.slices**2 * 1e6,
    }


def design_point_checks(geometry_dir, mesh, run, history="", design=None,
                        phases=LTCA_PHASES, positions=TCA_POSITIONS):
    """Every check of a design point as one dataset (``lsbg checks``).

    Parameters
    ----------
    geometry_dir, mesh, run
        The design point's geometry directory (``lsbg geometry``), its loaded
        TCA (``lsbg ltca``: the line model, load and crowning checked,
        :func:`check_crowning`) and point-model run (:func:`contact_resonance`).
    history : str
        The command that computes it (the ``history`` attribute).
    design : lsbg.gear.design.GearPairDesign, optional
        The design itself, without a directory or run (no resonance: NaN).
    phases, positions : int
        Mesh positions of each loaded TCA and of each surface TCA [-].

    Returns
    -------
    xarray.Dataset
        The scalars of :data:`CHECK_VARIABLES`, the conjugacy errors of
        :data:`CONJUGACY_VARIABLES` over the mesh positions (coordinate
        ``phase`` [degree]), CF-1.11 attributes, the design (``design_*``),
        the loaded TCA's load and slices and the crowning checked.
    """
    import xarray as xr

    import lsbg
    from lsbg.contact import ContactParameters, MeshContact
    from lsbg.gear.geometry import GearPair

    from lsbg.solid.directory import read_design

    if design is None:
        design, resonance = read_design(geometry_dir), contact_resonance(geometry_dir, run)
    else:
        resonance = dict.fromkeys(("frequency_hz", "frequency_min_hz", "frequency_max_hz",
                                   "stiffness_N_m_per_rad"), math.nan)
    load = float(mesh.attrs["load_torque_N_m"])
    params = ContactParameters.from_dict(mesh.attrs, prefix="contact_")
    crowning = check_crowning(mesh.attrs)
    answers = {**loaded_tca_checks(GearPair(design), params, load, phases),
               **contact_state_checks(GearPair(design), crowning, positions),
               **resonance,
               **stiffness_bounds(MeshContact(GearPair(design), params), mesh)}
    conjugacy = conjugacy_errors(design)
    variables = {name: ((), float(answers[key]), {"units": units, "long_name": text})
                 for name, (key, units, text) in CHECK_VARIABLES.items()}
    variables.update({name: ("phase", conjugacy[column].to_numpy(float),
                             {"units": units, "long_name": text})
                      for name, (column, units, text) in CONJUGACY_VARIABLES.items()})
    coords = {"phase": ("phase", conjugacy["phase_deg"].to_numpy(float),
                        {"units": "degree", "long_name": "turn of the generating curve in "
                                                      "the plane of action (drive side)"})}
    attrs = {
        "Conventions": "CF-1.11",
        "title": f"Verification checks of a {design.trace} spiral bevel gear pair",
        "source": f"lsbg {lsbg.__version__} (lsbg.experiments.point_checks)",
        "history": history,
        "lsbg_version": lsbg.__version__,
        "load_torque_N_m": load,
        "contact_slices": int(params.slices),
        "lengthwise_crowning_um": crowning.lengthwise_crowning * 1e6,
        "profile_crowning_um": crowning.profile_crowning * 1e6,
        "tca_positions": int(positions),
        "ltca_phases": int(phases),
        "mesh_phases": int(mesh.attrs["phases"]),
        "resonance_positions": RESONANCE_POSITIONS,
        "resonance_run_engine": "" if run is None else str(run.attrs.get("solver_engine", "")),
        **{f"design_{k}": v for k, v in design.to_config().items()},
    }
    return xr.Dataset(variables, coords=coords, attrs=attrs)


def point_check_rows(add, checks, meshes, records, eps, number):
    """The loaded TCA's and the contact state's checks, each with its bound and reason:
    ``add(key, check, values, bounds, unit, reason, ...)`` makes a row of
    :func:`lsbg.tables.verification.verification_checks` from a value and a bound per
    design point; ``checks``, ``meshes``: ``{gear type: dataset}`` of
    :func:`design_point_checks` and ``lsbg ltca``; ``records``: their design records,
    in that order; ``eps`` = ROUNDINGS EPS [-]; ``number`` formats a number."""
    from lsbg.tca.analysis import FACE_POINTS, PROFILE_POINTS, RASTER_SHAPE

    ds, mesh = list(checks.values()), [meshes[label] for label in checks]
    v = {n: np.array([float(d[n]) for d in ds]) for n in ds[0].data_vars if ds[0][n].ndim == 0}
    a = {n: np.array([m.attrs[n] for m in mesh]) for n in (
        "mean_mesh_stiffness_closed_form_N_per_um", "mesh_stiffness_mean_N_per_um",
        "mesh_stiffness_per_face_width_N_per_mm_um", "contact_line_stiffness_N_per_m2",
        "transmission_error_peak_to_peak_urad", "phases")}
    add("unloaded_te", "no transmission error without load (flank surfaces)",
        np.abs(v["unloaded_te_max"]), eps * math.pi, " rad",
        "round-off of two azimuths (each at most π) and their differences: 16 ε π")
    closed = a["mean_mesh_stiffness_closed_form_N_per_um"]
    bound = (np.abs(v["stiffness_slice_bias"]) + v["stiffness_sampling_bound"]
             + v["stiffness_roundoff_bound"])
    add("stiffness", "mean mesh stiffness equals its closed form (relative difference)",
        np.abs(a["mesh_stiffness_mean_N_per_um"] / closed - 1), bound, "", "the slices' exact "
        "bias (a band cut by the field's edge acts at its inside part's middle) + the mean of "
        f"{'/'.join(map(str, sorted(set(a['phases']))))} phases (rectangle rule, h² V/(12 Ψ_p)) + "
        "round-off")
    c_gamma, width = a["mesh_stiffness_per_face_width_N_per_mm_um"], np.array(
        [d.attrs["design_face_width_mm"] for d in ds])
    iso = 20e-9 * a["contact_line_stiffness_N_per_m2"] / v["calibrated_line_stiffness"]
    bound = np.abs(closed / width / iso - 1) + bound   # + the slices' midpoint rule
    i = int(np.argmax(np.abs(c_gamma / iso - 1) / bound))
    add("c_gamma", "mean mesh stiffness per face width cγ is ISO 6336-1's 20 N/(mm·µm) at the "
        "line stiffness used", np.abs(c_gamma / iso - 1), bound, "", "20 k_l/k_l(20), ± the "
        "slices' midpoint rule of ∫ρ² cos β_p dρ (from the closed form) and the mean's bound",
        result=f"{number(c_gamma.min(), 3)}–{number(c_gamma.max(), 3)} N/(mm·µm)",
        bound_text=f"{number(iso[i], 4)} ± {number(iso[i] * bound[i])} N/(mm·µm)")
    add("linearity", "loaded TCA linear in load (|TE(2T)/TE(T) − 2|)", v["linearity_error"],
        v["linearity_bound"], "", "4 × the TE's error: the static solve's 10⁻¹⁴, the torque's "
        "sum, φ1 z1/z2 − φ2's round-off (4 ε max|φ2| / min TE)")
    add("slices", "peak-to-peak TE converged in the slices (change with twice as many)",
        np.abs(v["te_pp_slices_x2_change"]), [100 * peak_to_peak_resolution(
            m.transmission_error) for m in mesh] / a["transmission_error_peak_to_peak_urad"],
        " %", "the loaded TCA's peak-to-peak resolution at its phases (half the larger TE "
        "step beside each extreme)")
    grid = f"the grid of every other point ({(FACE_POINTS + 1) // 2} × " \
        f"{(PROFILE_POINTS + 1) // 2})"
    add("conjugate_te", "contact state: conjugate, aligned pair without transmission error "
        "(surface TCA)", v["conjugate_te_pp"], v["conjugate_te_coarse_max"] + eps * math.pi,
        " rad", f"the largest TE on {grid}, which the fine grid holds, so its first contact "
        "is nearer the true one; + 16 ε π")
    play = np.array([x["backlash_mm"] * 2 / x["mean_pitch_diameter_gear_mm"] for x in records])
    add("backlash", "contact state: backlash from the coast flanks equals the design's "
        "(relative)", np.abs(v["backlash_error"]), v["backlash_coarse_error"]
        + eps * math.pi / play, "", f"the least backlash on {grid}, relative; + 16 ε π")
    designed = v["designed_te_pp"]
    error = v["crowned_te_pp"] / designed - 1
    first = 2 * np.abs(error - (2 * v["crowned_half_te_pp"] / designed - 1))
    add("crowned", "crowned pair's transmission error against its closed-form parabola",
        100 * np.abs(error), 100 * (first + v["crowned_te_sampling"] / designed), " %",
        "the flanks touch off the conjugate lines the closed form takes, first order in the "
        "ease-off: 2|e(C) − e(C/2)|; + the changeover's cusp at "
        f"{ds[0].attrs['tca_positions']} positions (the larger TE step beside each extreme)")
    add("line_model", "line model on the separation field against the surface TCA, unloaded",
        100 * np.abs(v["line_model_te_difference"]), 100 * (first + (
            v["line_model_slicing"] + v["crowned_te_sampling"] + v["line_model_te_sampling"])
            / designed), " %", "the same first-order term (the slices see the separation on "
        "the conjugate lines), + what slices miss, (C_L + C_P k²)/slices², + both samplings")
    plus, minus = v["pattern_shift_plus"], v["pattern_shift_minus"]
    cell, least = width / RASTER_SHAPE[0], np.minimum(np.abs(plus), np.abs(minus))
    add("pattern", "an offset E of ±0.1 mm moves the bearing pattern either way", -least, -cell,
        " mm", f"each move more than a cell of the pattern's raster (b/{RASTER_SHAPE[0]}: its "
        "centroid's resolution), the two of opposite sign",
        result="; ".join(f"{label}: {p:+.3g} / {m:+.3g} mm"
                         for label, p, m in zip(checks, plus, minus)),
        bound_text=f"> {number(cell.max())} mm each way",
        ok=bool((np.sign(plus) == -np.sign(minus)).all() and (least > cell).all()))
