"""The FE loaded TCA over a range of torques, its setup made once per position.

A gear's development report shows the transmission error, the contact
pattern and the stresses against the torque (ten or more torques from 10 %
to 150 % of the rated one). The FE loaded TCA (:func:`lsbg.tooth.ltca.fe_loaded_tca`)
solves one torque; most of its work at a mesh position does not depend on
the torque: the contact points, their weights on the flank grid, their dense
FE compliance, the flanks' curvature and thicknesses under them
(:func:`lsbg.tooth.ltca.position_setup`). :func:`fe_load_range` does that
once per position and then solves the complementarity problem at every
torque, in ascending order, each torque started from the last one's loads
at that position scaled by the torques' ratio (the first torque from the
last position's, as :func:`fe_loaded_tca` starts). The solution is unique
(:mod:`lsbg.tooth.local`): the answers are those of :func:`fe_loaded_tca` at
each torque, to the solver's tolerance.

The mesh stiffness is no further solve either (:func:`fe_loaded_tca`'s central
difference of the torque over the mismatch costs two per position and
torque): at a solution the active set's linear system gives the derivative
itself, dT2/d eps = e2 l_A . (C_AA + D_A)^-1 l_A with D_A the tangents of
Hertz's approach (:func:`tangent_stiffness`). The central difference at
+-0.1 % of the torque matches it to 1e-7 at the median position, to 0.4 %
where a point enters contact within the difference's step.

SI inside; the dataset speaks µrad, N/µm, MPa, N/mm and mm.
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.contact import kernels as k

__all__ = ["check_torques", "fe_load_range", "tangent_stiffness"]


def check_torques(torques):
    """Torques of a load range, checked and in ascending order [N m].

    Parameters
    ----------
    torques : float or array_like
        Gear torques [N m].

    Returns
    -------
    numpy.ndarray
        Sorted, 1-D.

    Raises
    ------
    ValueError
        Naming ``torques``: not numbers, more than one dimension, none, one
        not finite or not > 0, or one repeated.
    """
    try:
        values = np.atleast_1d(np.asarray(torques, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"torques = {torques!r}: must be numbers [N m]") from None
    if values.ndim != 1:
        raise ValueError(f"torques has shape {values.shape}: must be one list of torques [N m]")
    if values.size == 0:
        raise ValueError("torques = []: must hold at least one torque [N m]")
    if not np.all(np.isfinite(values) & (values > 0)):
        raise ValueError(f"torques = {values.tolist()!r}: every torque must be a finite "
                         f"number > 0 [N m]")
    values = np.sort(values)
    if np.any(np.diff(values) == 0):
        raise ValueError(f"torques = {values.tolist()!r}: each torque once")
    return values


def tangent_stiffness(position, loads):
    """The derivative of the torque over the mismatch at a solution [N m/rad].

    With the points in contact A held (a point entering contact carries no
    load and, Hertz's approach having an infinite tangent at zero load, adds
    no stiffness), the solution's equations
    C_AA F_A + d_A(F_A) - l_A eps = -s_A and e2 l_A . F_A = T2 give
    dF_A = (C_AA + D_A)^-1 l_A d eps, so dT2/d eps = e2 l_A . (C_AA + D_A)^-1 l_A,
    D_A the diagonal of Hertz's tangents d delta_i/d F_i.

    Parameters
    ----------
    position : lsbg.tooth.ltca.Position
    loads : numpy.ndarray
        Its solution's loads [N] (:meth:`lsbg.tooth.ltca.Position.solve`).

    Returns
    -------
    float
    """
    on = np.flatnonzero(loads > 0)
    system = position.matrix[np.ix_(on, on)]
    system[np.arange(on.size), np.arange(on.size)] += position.hertz.tangent(loads)[on]
    lever = position.points.lever[on]
    return position.cycle.contact.e2 * lever @ np.linalg.solve(system, lever)


class _Pattern:
    """The extent of the loaded points over a mesh cycle: cone distance and profile."""

    def __init__(self, cycle):
        table = cycle.contact.arrays[2][0, :cycle.bands]
        self.inner = table[:, k.B_RHO] - 0.5 * table[:, k.B_D_RHO]
        self.outer = table[:, k.B_RHO] + 0.5 * table[:, k.B_D_RHO]
        self.radius = cycle.contact.pair.design.mean_cone_distance
        self.rho = [math.inf, -math.inf]
        self.psi = [math.inf, -math.inf]

    def add(self, points, loads):
        """Take in one position's points and their loads [N]."""
        loaded = loads > 0
        band = points.band[loaded]
        self.rho = [min(self.rho[0], self.inner[band].min()),
                    max(self.rho[1], self.outer[band].max())]
        self.psi = [min(self.psi[0], points.psi_from[loaded].min()),
                    max(self.psi[1], points.psi_to[loaded].max())]

    def size(self):
        """Length over the face width and width across the profile [m]."""
        return self.rho[1] - self.rho[0], self.radius * (self.psi[1] - self.psi[0])


def fe_load_range(contact, compliance, torques, phases=200, form_limit=True):
    """The FE loaded TCA at a range of torques, over one mesh cycle each.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        Line model of the pair (its bands, and its separation field for real
        flanks).
    compliance : xarray.Dataset
        :func:`lsbg.tooth.compliance.tooth_compliance` of the same design.
    torques : array_like
        Gear torques [N m], each finite and > 0, at least one (solved and
        returned in ascending order).
    phases : int
        Mesh positions over one base pitch [-] (at least 8).
    form_limit : bool
        Bound the field by the generated flanks' starts (default) or keep
        lsbg's field of contact (:func:`lsbg.tooth.ltca.fe_loaded_tca`).

    Returns
    -------
    xarray.Dataset
        On (``torque`` [N m], ``mesh_phase``) what :func:`fe_loaded_tca`
        gives per position: ``transmission_error`` [urad],
        ``max_contact_pressure``, ``max_flank_pressure``,
        ``root_stress_pinion``, ``root_stress_gear`` [MPa], the edge loads
        (``edge_load_share`` [1], ``edge_line_load``,
        ``relief_start_line_load`` [N/mm], ``relief_start_load_share``
        [1]); ``pair_torque`` (torque, mesh_phase, tooth_pair) [N m], the
        gear torque each tooth pair carries; with three torques or more
        ``mesh_stiffness`` [N/um] (see the module). Per torque:
        ``transmission_error_peak_to_peak``, ``transmission_error_mean`` and
        ``transmission_error_first_harmonic`` (the mesh frequency's
        amplitude) [urad], the loaded contact pattern's ``pattern_length``
        and ``pattern_width`` [mm] and the cycle's maxima
        (``cycle_max_*``). Attributes: the phases, the field, the
        compliance's inputs hash, the flanks (``contact.separation.attrs``).

    Raises
    ------
    ValueError
        Naming ``torques`` or ``phases`` out of range, or a compliance of
        another design.
    """
    import xarray as xr

    from lsbg.contact.mesh import MAX_PAIRS
    from lsbg.files import short_labels
    from lsbg.tca.loaded import harmonic_amplitudes
    from lsbg.tooth.ltca import EdgeLoads, MeshCycle, position_setup

    torques = check_torques(torques)
    cycle = MeshCycle(contact, compliance, phases, form_limit)
    phases, count, e2 = cycle.phases, torques.size, contact.e2
    design = contact.pair.design
    eps, stiffness = np.zeros((count, phases)), np.zeros((count, phases))
    pressure_max = np.zeros((count, phases))
    pair_torque = np.zeros((count, phases, MAX_PAIRS))
    edges = [EdgeLoads(contact, phases) for _ in torques]
    patterns = [_Pattern(cycle) for _ in torques]
    grid_loads = [[] for _ in torques]  # per torque, lsbg.tooth.ltca.Position.pair_loads
    previous = None  # keys and loads at the first torque of the last position
    for n, phi1 in enumerate(cycle.pinion):
        position = position_setup(cycle, phi1)
        points = position.points
        start = position.start(previous)
        for t, torque in enumerate(torques):
            loads, eps[t, n] = position.solve(torque, start)
            if t == 0:
                previous = position.key, loads
            if t + 1 < count:
                start = loads * (torques[t + 1] / torque)
            # T2 = f(eps), phi2 = phi1 e1/e2 - eps/e2: -dT2/dphi2 = e2 dT2/deps
            stiffness[t, n] = e2 * tangent_stiffness(position, loads) / contact.base_radius**2
            pressure = position.pressure(loads)
            pressure_max[t, n] = pressure.max()
            edges[t].add(n, points, loads, pressure)
            patterns[t].add(points, loads)
            line, _, on_grid, which = position.pair_loads(loads)
            kept = line < MAX_PAIRS
            moment = e2 * np.bincount(which, points.lever * loads, line.size)
            pair_torque[t, n, line[kept]] = moment[kept]
            grid_loads[t].append((np.full(line.size, n), on_grid))
    roots = [cycle.fe.root_stresses(g, phases) for g in grid_loads]
    te = eps / e2 * 1e6  # [urad]
    dims = ("torque", "mesh_phase")
    variables = {
        "transmission_error": (dims, te, {
            "units": "urad", "long_name": "loaded transmission error"}),
        "max_contact_pressure": (dims, pressure_max * 1e-6, {
            "units": "MPa", "long_name": "largest Hertz peak pressure"}),
        **{f"root_stress_{m}": (dims, np.array([r[m] for r in roots]) * 1e-6, {
            "units": "MPa", "long_name": f"root stress of the {m}",
            "description": f"largest tensile principal stress in the {m}'s root fillets "
                           f"under every tooth pair's loads"}) for m in ("pinion", "gear")},
        "pair_torque": ((*dims, "tooth_pair"), pair_torque, {
            "units": "N m", "long_name": "gear torque of each tooth pair",
            "description": "e2 times the sum of lever times load over the tooth pair's "
                           "points; the pairs' sum is the torque"}),
    }
    for name, (_, _, attrs) in edges[0].variables().items():
        values = np.array([e.variables()[name][1] for e in edges])
        variables[name] = (dims, values, attrs)
    variables["mesh_stiffness"] = (dims, stiffness * 1e-6, {
        "units": "N/um", "long_name": "mesh stiffness",
        "description": "e2 dT2/d(mismatch) / r_b^2, the derivative from the solution's "
                       "linear system (lsbg.tooth.load_range.tangent_stiffness)"})
    length, width = np.array([p.size() for p in patterns]).T * 1e3
    per_torque = {
        "transmission_error_peak_to_peak": (np.ptp(te, axis=1), "urad",
                                            "peak-to-peak transmission error"),
        "transmission_error_mean": (te.mean(axis=1), "urad", "mean transmission error"),
        "mesh_stiffness_mean": (stiffness.mean(axis=1) * 1e-6, "N/um", "mean mesh stiffness"),
        "transmission_error_first_harmonic": (
            np.array([harmonic_amplitudes(row, 1)[0] for row in te]), "urad",
            "TE amplitude at the mesh frequency"),
        "pattern_length": (length, "mm", "loaded pattern's length"),
        "pattern_width": (width, "mm", "loaded pattern's width"),
    }
    for name, label in (("max_contact_pressure", "Hertz pressure"),
                        ("max_flank_pressure", "flank pressure"),
                        ("root_stress_pinion", "pinion root stress"),
                        ("root_stress_gear", "gear root stress"),
                        ("edge_load_share", "edge load share"),
                        ("edge_line_load", "edge line load"),
                        ("relief_start_line_load", "relief start line load")):
        _, values, attrs = variables[name]
        per_torque[f"cycle_max_{name.removeprefix('max_')}"] = (
            values.max(axis=1), attrs["units"], f"cycle's largest {label}")
    descriptions = {
        "transmission_error_first_harmonic": "amplitude of the mesh frequency's harmonic "
                                             "(lsbg.tca.loaded.harmonic_amplitudes)",
        "pattern_length": "extent over the face width of the bands that carry load at any "
                          "position of the cycle, the bands' width included",
        "pattern_width": "extent across the profile of the loaded bands' line segments over "
                         "the cycle, as a length in the plane of action at the mean cone "
                         "distance",
    }
    for name, (values, units, label) in per_torque.items():
        attrs = {"units": units, "long_name": label}
        if name in descriptions:
            attrs["description"] = descriptions[name]
        variables[name] = ("torque", values, attrs)
    z1, z2 = design.teeth
    attrs = {
        "title": f"FE loaded TCA over a load range of a {design.trace} spiral bevel gear pair "
                 f"({z1}:{z2}, spiral angle {math.degrees(design.spiral_angle):g} deg)",
        "source": "lsbg.tooth.load_range.fe_load_range: FE influence coefficients + Hertz "
                  "line contact, complementarity per position and torque",
        "compliance": "fe",
        "compliance_inputs_hash": str(cycle.inputs_hash),
        "phases": int(phases),
        "torque_min_N_m": float(torques[0]),
        "torque_max_N_m": float(torques[-1]),
        "tip_relief": edges[0].relieved,
        **cycle.field_attrs(),
        **(contact.separation.attrs if contact.separation is not None else {}),
    }
    ds = xr.Dataset(
        variables,
        coords={"torque": ("torque", torques, {"units": "N m", "long_name": "gear torque"}),
                "mesh_phase": ("mesh_phase", cycle.fraction, {"units": "1"}),
                "tooth_pair": ("tooth_pair", np.arange(MAX_PAIRS))},
        attrs=attrs)
    return short_labels(ds)
