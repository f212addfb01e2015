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
  model's linearised contact at the static load.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

__all__ = ["conjugacy_errors", "contact_resonance", "loaded_tca_checks", "check_crowning",
           "contact_state_checks", "design_point_checks", "CHECK_VARIABLES",
           "CONJUGACY_VARIABLES", "TCA_POSITIONS", "LTCA_PHASES", "RESONANCE_POSITIONS"]

#: Positions of each surface TCA of :func:`contact_state_checks` over a mesh cycle [-].
TCA_POSITIONS = 100
#: Mesh positions of each loaded TCA of :func:`loaded_tca_checks` [-].
LTCA_PHASES = 64
#: Pinion angles over one pitch at which :func:`contact_resonance` linearises [-].
RESONANCE_POSITIONS = 12
#: The crowning checked where the loaded TCA ran on conjugate flanks [m]
#: (lengthwise, profile: the practice default of the ``flank_modification`` section).
DEFAULT_CROWNING = (25e-6, 5e-6)

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
        ISO 6336-1's c_gamma = 20 N/(mm·µm) [N/(mm·µm)].
    """
    from lsbg.contact import MeshContact, calibrated_line_stiffness
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
            "k_l_for_c_gamma_20_N_per_mm_um": calibrated_line_stiffness(pair) / 1e9}


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
        [mm] (the displacement that moves both types' patterns most).
    """
    from lsbg.contact import ContactParameters, MeshContact
    from lsbg.tca.analysis import tooth_contact_analysis
    from lsbg.tca.loaded import loaded_tca
    from lsbg.tca.misalignment import Misalignment
    from lsbg.tca.separation import separation_field

    design = pair.design
    conjugate = tooth_contact_analysis(pair, positions=positions)
    backlash = design.backlash / design.mean_pitch_radius(2) * 1e6
    crowned = tooth_contact_analysis(pair, modification, positions=positions)
    line = loaded_tca(MeshContact(pair, ContactParameters(model="line"),
                                  separation=separation_field(pair, modification)),
                      0.0, phases=positions)
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
    }


def design_point_checks(geometry_dir, mesh, run, history=""):
    """Every check of a design point as one dataset (``lsbg checks``).

    Parameters
    ----------
    geometry_dir : str or os.PathLike
        The design point's geometry directory (``lsbg geometry``).
    mesh : xarray.Dataset
        Its loaded TCA (``lsbg ltca``): the line model's parameters, the load
        and the crowning of :func:`loaded_tca_checks` and
        :func:`contact_state_checks` (:func:`check_crowning`).
    run : xarray.Dataset
        Its point-model run: the contact law and load of
        :func:`contact_resonance`.
    history : str
        The command that computes it (the ``history`` attribute).

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
    from lsbg.contact import ContactParameters
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.directory import read_design

    design = read_design(geometry_dir)
    load = float(mesh.attrs["load_torque_N_m"])
    params = ContactParameters.from_dict(mesh.attrs, prefix="contact_")
    crowning = check_crowning(mesh.attrs)
    answers = {**loaded_tca_checks(GearPair(design), params, load),
               **contact_state_checks(GearPair(design), crowning),
               **contact_resonance(geometry_dir, run)}
    conjugacy = conjugacy_errors(read_design(geometry_dir))
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
        "tca_positions": TCA_POSITIONS,
        "ltca_phases": LTCA_PHASES,
        "resonance_positions": RESONANCE_POSITIONS,
        "resonance_run_engine": str(run.attrs.get("solver_engine", "")),
        **{f"design_{k}": v for k, v in design.to_config().items()},
    }
    return xr.Dataset(variables, coords=coords, attrs=attrs)
