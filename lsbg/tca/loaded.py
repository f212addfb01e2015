"""Quasi-static loaded tooth contact analysis (LTCA) of the line model.

The first look a gear engineer takes at a mesh: at each of N positions over
one mesh cycle (one base pitch of the contact lines), turn the pinion and find
the gear rotation at which the line contact carries the load at rest
(:meth:`lsbg.contact.MeshContact.static_gear_angle`). From the equilibria:

* the loaded static **transmission error**, TE = phi1 z1/z2 - phi2 (gear
  behind its kinematic position), its peak-to-peak value and mesh harmonics;
* the **mesh stiffness** along the line of action at the mean point,
  k = -dT2/dphi2 / r_b2^2 (the virtual cylindrical gear of ISO 10300), and
  per unit face width (c_γ of ISO 6336-1);
* the **contact length**, the **load of each tooth pair** (load sharing) and
  the **contact pattern**: load per unit length over the flank, face width x
  profile.

Unloaded, conjugate flanks have no transmission error. :func:`unloaded_transmission_error`
checks that on the flank *surfaces* themselves (the classical unloaded TCA),
independently of the plane-of-action kernel the loaded analysis uses.

Inside, everything is SI; the dataset speaks the paper's units (µrad, N/µm,
mm, N/mm) with ``units`` attributes (CF-1.11).
"""

from __future__ import annotations

import datetime
import math

import numpy as np

import lsbg
from lsbg.contact import ContactParameters, MeshContact
from lsbg.contact import kernels
from lsbg.files import short_labels
from lsbg.gear.flank import active_polar_range, mesh_phase_pinion_angle

#: Default number of mesh phases over one base pitch.
PHASES = 256
#: Profile points of the contact pattern.
PROFILE_POINTS = 61
#: Mesh harmonics of the transmission error reported.
HARMONICS = 3


def harmonic_amplitudes(values, count=HARMONICS):
    """Amplitudes of the first harmonics of one period sampled evenly.

    Parameters
    ----------
    values : array_like
        One period, N even samples (the endpoint excluded) [any unit].
    count : int
        Number of harmonics [-].

    Returns
    -------
    numpy.ndarray
        Amplitude of harmonics 1..count, 2 |X_h| / N [unit of ``values``].
    """
    values = np.asarray(values, dtype=float)
    spectrum = np.fft.rfft(values - values.mean())
    return 2.0 * np.abs(spectrum[1:count + 1]) / values.size


def transmission_error_summary(transmission_error, mesh_stiffness, face_width):
    """Summary figures of a loaded TCA's transmission error and mesh stiffness.

    Parameters
    ----------
    transmission_error : numpy.ndarray
        One mesh cycle, evenly sampled [rad].
    mesh_stiffness : numpy.ndarray
        Mesh stiffness at the same positions [N/m].
    face_width : float
        [m].

    Returns
    -------
    dict
        Dataset attributes: TE peak to peak, mean and harmonics [urad]; mean
        mesh stiffness [N/um], per unit face width [N/(mm um)], its peak to
        peak [N/um] and variation [%].
    """
    te, stiffness = np.asarray(transmission_error), np.asarray(mesh_stiffness)
    harmonics = harmonic_amplitudes(te * 1e6)
    mean_stiffness = float(stiffness.mean())
    return {
        "transmission_error_peak_to_peak_urad": float(np.ptp(te) * 1e6),
        "transmission_error_mean_urad": float(te.mean() * 1e6),
        **{f"transmission_error_harmonic_{h + 1}_urad": float(a) for h, a in enumerate(harmonics)},
        "mesh_stiffness_mean_N_per_um": mean_stiffness * 1e-6,
        "mesh_stiffness_per_face_width_N_per_mm_um": mean_stiffness / face_width * 1e-9,
        "mesh_stiffness_peak_to_peak_N_per_um": float(np.ptp(stiffness) * 1e-6),
        "mesh_stiffness_variation_percent": float(100 * np.ptp(stiffness) / mean_stiffness),
    }


def loaded_tca(contact: MeshContact, load_torque, phases=PHASES, profile_points=PROFILE_POINTS):
    """Loaded tooth contact analysis over one mesh cycle.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        A line-model contact (damping plays no part at rest).
    load_torque : float
        Torque on the gear [N m], >= 0. At 0 the analysis is the unloaded
        TCA of the model: the flanks just touch, the transmission error is
        zero for conjugate flanks, and the mesh stiffness is the slope at
        first touch.
    phases : int
        Mesh positions over one base pitch [-] (at least 8).
    profile_points : int
        Points of the contact pattern across the field of contact [-].

    Returns
    -------
    xarray.Dataset
        Variables on ``mesh_phase`` (fraction of a base pitch):
        ``transmission_error`` [urad], ``mesh_stiffness`` [N/um],
        ``contact_length`` [mm], ``pinion_angle`` [deg]; ``pair_load``
        (mesh_phase, tooth_pair) [N]; ``tooth_pair_load`` (passage) [N], the
        load of one tooth pair on its way through the field; and
        ``contact_pattern`` (cone_distance, profile_angle) [N/mm]. Attributes
        hold the summary figures (peak-to-peak TE, its harmonics, mean mesh
        stiffness and per unit face width, its variation) and the design.

    Raises
    ------
    ValueError
        For a point-model contact, a negative load or fewer than 8 phases.
    """
    import xarray as xr

    if contact.params.model != "line":
        raise ValueError(f"contact model = {contact.params.model!r}: the loaded TCA is "
                         f"defined for the line model")
    if not (math.isfinite(load_torque) and load_torque >= 0):
        raise ValueError(f"load_torque = {load_torque!r}: must be a number >= 0 [N m]")
    if isinstance(phases, bool) or int(phases) != phases or phases < 8:
        raise ValueError(f"phases = {phases!r}: must be a whole number >= 8")
    pair, design = contact.pair, contact.pair.design
    z1, z2 = design.teeth
    fraction = np.arange(int(phases)) / int(phases)
    pinion = mesh_phase_pinion_angle(pair, fraction)
    gear = np.array([contact.static_gear_angle(load_torque, p) for p in pinion])
    te = pinion * z1 / z2 - gear
    # Mesh stiffness: the torque's slope at the equilibrium, a central
    # difference a millionth of the elastic approach wide; unloaded, one-sided
    # into the flanks (backing off they separate and carry nothing).
    if load_torque > 0.0:
        h = 1e-6 * np.abs(te).max()
        slope = np.array([(contact.forces(p, g - h).gear_torque
                           - contact.forces(p, g + h).gear_torque) / (2 * h)
                          for p, g in zip(pinion, gear)])
    else:
        h = 1e-9
        slope = np.array([(contact.forces(p, g - h).gear_torque - contact.forces(p, g).gear_torque)
                          / h for p, g in zip(pinion, gear)])
    stiffness = slope / contact.base_radius**2
    # Tooth pairs and slices at each equilibrium (drive side only: the load
    # keeps the coast flanks apart).
    sides = contact.arrays[1]
    first, last = sides[0, kernels.S_FIRST], sides[0, kernels.S_LAST]
    lines = int(math.floor((last - first) / contact.pitch)) + 2
    pair_load = np.zeros((phases, lines))
    length = np.zeros(phases)
    samples = [[] for _ in range(contact.params.slices)]  # per band: (psi, load)
    passage, passage_load = [], []
    _, table = sides, contact.arrays[2]
    theta = np.arctan2(table[0, :, kernels.B_SIN], table[0, :, kernels.B_COS])
    for i, (p, g) in enumerate(zip(pinion, gear)):
        pairs, loads = contact.pair_contacts(p, g, slice_loads=True)
        for pc, row in zip(pairs, loads):
            if pc.side != "drive":
                continue
            position = (pc.phase - first) / contact.pitch
            slot = int(math.floor(position))
            pair_load[i, slot] = pc.normal_force
            length[i] += pc.contact_length
            passage.append(position)
            passage_load.append(pc.normal_force)
            for j in range(row.size):
                samples[j].append((pc.phase + theta[j], row[j]))
    psi_lo, psi_hi = sides[0, kernels.S_PSI_LO], sides[0, kernels.S_PSI_HI]
    profile = np.linspace(psi_lo, psi_hi, int(profile_points))
    pattern = np.zeros((contact.params.slices, profile.size))
    for j, points in enumerate(samples):
        points = np.array(sorted(points))
        if points.size:
            pattern[j] = np.interp(profile, points[:, 0], points[:, 1], left=0.0, right=0.0)
    order = np.argsort(passage)
    passage = np.asarray(passage)[order]
    passage_load = np.asarray(passage_load)[order]
    rho = table[0, :, kernels.B_RHO]

    extent = loaded_pattern_extent(pattern, rho, table[0, :, kernels.B_D_RHO], profile)
    attrs = {
        "Conventions": "CF-1.11",
        "title": f"Loaded tooth contact analysis of a {design.trace} spiral bevel gear pair "
                 f"({z1}:{z2}, spiral angle {math.degrees(design.spiral_angle):g} deg)",
        "source": f"lsbg {lsbg.__version__} (lsbg.tca.loaded.loaded_tca), line contact model",
        "history": f"{datetime.datetime.now(datetime.timezone.utc).isoformat(timespec='seconds')} "
                   f"lsbg.tca.loaded.loaded_tca",
        "lsbg_version": lsbg.__version__,
        "load_torque_N_m": float(load_torque),
        "phases": int(phases),
        **transmission_error_summary(te, stiffness, design.face_width),
        **extent,
        **(contact.separation.attrs if contact.separation is not None else {}),
        "mean_mesh_stiffness_closed_form_N_per_um": contact.mean_mesh_stiffness() * 1e-6,
        "base_radius_gear_mm": contact.base_radius * 1e3,
        "mesh_frequency_per_pinion_rev": z1,
        **{f"contact_{k}": v for k, v in contact.params.to_dict().items()},
        **{f"design_{k}": v for k, v in design.to_config().items()},
    }
    ratio = pair.contact_ratio()
    attrs.update(design_contact_ratio=ratio["total"], design_contact_ratio_profile=ratio["profile"],
                 design_contact_ratio_face=ratio["face"])
    return short_labels(xr.Dataset(
        {
            "transmission_error": ("mesh_phase", te * 1e6, {
                "units": "urad", "long_name": "loaded static transmission error, gear rotation "
                                              "behind its kinematic position phi1 z1/z2 - phi2"}),
            "mesh_stiffness": ("mesh_phase", stiffness * 1e-6, {
                "units": "N/um", "long_name": "mesh stiffness along the line of action at the "
                                              "mean point, -dT2/dphi2 / r_b2^2"}),
            "contact_length": ("mesh_phase", length * 1e3, {
                "units": "mm", "long_name": "length of the contact lines inside the field"}),
            "pinion_angle": ("mesh_phase", np.degrees(pinion), {
                "units": "degree", "long_name": "pinion rotation"}),
            "pair_load": (("mesh_phase", "tooth_pair"), pair_load, {
                "units": "N", "long_name": "normal load of each tooth pair whose line meets "
                                           "the field (0: none)"}),
            "tooth_pair_load": ("passage", passage_load, {
                "units": "N", "long_name": "normal load of one tooth pair on its way through "
                                           "the field of contact"}),
            "contact_pattern": (("cone_distance", "profile_angle"), pattern * 1e-3, {
                "units": "N/mm", "long_name": "load per unit length of contact line over the "
                                              "flank (contact pattern)"}),
        },
        coords={
            "mesh_phase": ("mesh_phase", fraction, {
                "units": "1", "long_name": "mesh phase, fraction of a base pitch from the "
                                           "drive flanks of tooth 0 touching at the mean point"}),
            "tooth_pair": ("tooth_pair", np.arange(lines), {
                "long_name": "tooth pair, counted from the first line that can meet the field"}),
            "passage": ("passage", passage, {
                "units": "1", "long_name": "position of a tooth pair's contact line on its way "
                                           "through the field, in base pitches"}),
            "cone_distance": ("cone_distance", rho * 1e3, {
                "units": "mm", "long_name": "distance from the apex (slice centre)"}),
            "profile_angle": ("profile_angle", np.degrees(profile), {
                "units": "degree", "long_name": "polar angle in the plane of action from the "
                                                "pitch line (position along the path of contact)"}),
        },
        attrs={k: (float(v) if isinstance(v, (np.floating, np.integer)) else v)
               for k, v in attrs.items()},
    ))


def loaded_pattern_extent(pattern, cone_distance, band_width, profile_angle):
    """Extent of the loaded contact pattern and the share of load at its edges.

    Parameters
    ----------
    pattern : numpy.ndarray, shape (bands, profile)
        Load per unit length over the flank [N/m].
    cone_distance, band_width : numpy.ndarray, shape (bands,)
        Band centres and widths [m].
    profile_angle : numpy.ndarray, shape (profile,)
        Polar angles in the plane of action across the field [rad].

    Returns
    -------
    dict
        ``loaded_pattern_toe_mm``, ``loaded_pattern_heel_mm`` (cone distances
        of the loaded band ends), ``loaded_pattern_length_per_face_width``,
        ``loaded_pattern_profile_share`` (share of the field's profile that
        carries load) and ``edge_load_share``: the share of the load carried
        by the outermost band at the toe and at the heel and by the first and
        last profile samples (the field's edges at tip and root) [-].
    """
    loaded = pattern > 0.0
    total = float(pattern.sum())
    if not loaded.any() or total <= 0.0:
        nan = float("nan")
        return {"loaded_pattern_toe_mm": nan, "loaded_pattern_heel_mm": nan,
                "loaded_pattern_length_per_face_width": 0.0,
                "loaded_pattern_profile_share": 0.0, "edge_load_share": nan}
    rows = np.flatnonzero(loaded.any(axis=1))
    columns = np.flatnonzero(loaded.any(axis=0))
    toe = cone_distance[rows[0]] - band_width[rows[0]] / 2
    heel = cone_distance[rows[-1]] + band_width[rows[-1]] / 2
    edge = np.zeros_like(loaded)
    edge[[0, -1], :] = True
    edge[:, [0, -1]] = True
    step = profile_angle[1] - profile_angle[0]
    profile_span = (columns[-1] - columns[0] + 1) * step / (profile_angle[-1] - profile_angle[0] + step)
    return {"loaded_pattern_toe_mm": float(toe * 1e3), "loaded_pattern_heel_mm": float(heel * 1e3),
            "loaded_pattern_length_per_face_width": float((heel - toe) / band_width.sum()),
            "loaded_pattern_profile_share": float(profile_span),
            "edge_load_share": float(pattern[edge].sum() / total)}


def unloaded_transmission_error(pair, pinion_angles, side="drive", n_face=7):
    """Unloaded transmission error from the flank surfaces (classical TCA).

    For a pinion rotation, each point P of the pinion's active flank fixes
    the gear rotation phi2(P) at which the gear's active flank passes through
    it; the gear touches at the most advanced of those rotations (any further
    back the flanks would interfere). At each of ``n_face`` cone distances
    the most advanced point is found by a bounded scalar maximisation over
    the pinion's polar angle, for the teeth near the mesh. The transmission
    error is the kinematic rotation phi1 z1/z2 minus the gear's. It uses only
    :meth:`lsbg.gear.geometry.GearPair.flank`, not the plane-of-action kernel.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    pinion_angles : array_like
        Pinion rotations [rad].
    side : {"drive"}
        Flank side (the coast side mirrors it).
    n_face : int
        Cone distances across the face width [-].

    Returns
    -------
    numpy.ndarray
        Transmission error phi1 z1/z2 - phi2 at first contact [rad] (positive:
        the gear lags); zero to rounding for conjugate flanks.
    """
    from scipy.optimize import minimize_scalar

    from lsbg.gear.vectors import rotate

    if side != "drive":
        raise ValueError(f"side = {side!r}: only the drive side is implemented")
    design = pair.design
    z1, z2 = design.teeth
    u1 = pair.rotation_axis[1]
    lo, hi = active_polar_range(pair, 1, side)
    gear_lo, gear_hi = active_polar_range(pair, 2, side)
    gear_pitch = 2 * math.pi / z2

    def gear_rotation(rho, polar, turn, kinematic):
        body, _ = pair.flank(1, side, rho, polar)
        point = rotate(body, u1, turn)
        gear_polar = math.acos(min(1.0, max(-1.0, float(point @ pair.axis[2]) / rho)))
        if not gear_lo <= gear_polar <= gear_hi:
            return kinematic - 1.0  # no gear flank there: far behind any contact
        flank, _ = pair.flank(2, side, rho, gear_polar)
        rotation = float(pair.azimuth(2, point) - pair.azimuth(2, flank))
        # the gear tooth nearest the kinematic position
        return rotation - gear_pitch * round((rotation - kinematic) / gear_pitch)

    rhos = np.linspace(design.inner_cone_distance, design.outer_cone_distance, n_face)
    out = []
    for phi1 in np.atleast_1d(np.asarray(pinion_angles, dtype=float)):
        kinematic = phi1 * z1 / z2
        best = -math.inf
        for tooth in range(-2, 3):
            turn = phi1 + 2 * math.pi * tooth / z1
            for rho in rhos:
                grid = np.linspace(lo, hi, 9)
                values = [gear_rotation(rho, p, turn, kinematic) for p in grid]
                i = int(np.argmax(values))
                if values[i] <= kinematic - 1.0:
                    continue
                fit = minimize_scalar(lambda p: -gear_rotation(rho, p, turn, kinematic),
                                      bounds=(grid[max(i - 1, 0)], grid[min(i + 1, 8)]),
                                      method="bounded", options={"xatol": 1e-14})
                best = max(best, values[i], -fit.fun)
        out.append(kinematic - best)
    return np.asarray(out)


def pair_loaded_tca(pair, load_torque, contact_params=None, flanks=None, phases=PHASES):
    """:func:`loaded_tca` of a gear pair on its real flanks: the line model, uniform bed.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    load_torque : float
        Torque on the gear [N m], >= 0.
    contact_params : lsbg.contact.ContactParameters, optional
        Its line-model fields are used (the model is set to "line"; default: the
        study's defaults).
    flanks : lsbg.tca.separation.RealFlanks, optional
        Flank modification and assembly displacements (default: the conjugate,
        aligned pair), e.g. ``RealFlanks.from_config({"lengthwise_crowning_um": 25},
        {})``.
    phases : int
        Mesh positions over one base pitch [-].

    Returns
    -------
    xarray.Dataset
        As :func:`loaded_tca`.
    """
    params = (contact_params or ContactParameters()).replace(model="line")
    separation = flanks.separation(pair) if flanks is not None else None
    return loaded_tca(MeshContact(pair, params, separation=separation), load_torque, phases)


def ltca_for_geometry(geometry_dir, load_torque, contact_params=None, phases=PHASES,
                      flanks=None):
    """:func:`pair_loaded_tca` of a geometry directory (``lsbg geometry``).

    Parameters
    ----------
    geometry_dir : str or pathlib.Path
    load_torque : float
        Torque on the gear [N m].
    contact_params : lsbg.contact.ContactParameters, optional
        Its line-model fields are used (the model is set to "line").
    phases : int
    flanks : lsbg.tca.separation.RealFlanks, optional
        Flank modification and assembly displacements (default: the
        conjugate, aligned pair).

    Returns
    -------
    xarray.Dataset
    """
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.directory import read_design

    return pair_loaded_tca(GearPair(read_design(geometry_dir)), load_torque, contact_params,
                           flanks, phases)
