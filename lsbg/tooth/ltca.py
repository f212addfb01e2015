"""Loaded tooth contact analysis with the tooth's own compliance (FE + Hertz).

At each mesh position the contact lines of the line model (the bands of the
face width on every tooth pair whose line meets the field) are the contact
points. Their loads F >= 0 and the mismatch eps solve the contact problem as
what it is, a complementarity problem:

    gap_i = d_i(F) - (lever_i eps - s_i) >= 0,   F_i >= 0,   F_i gap_i = 0,
    e2 sum_i lever_i F_i = T,

where lever_i eps - s_i is the rigid approach of point i (the line model's,
with the separation s of real flanks, :mod:`lsbg.tca.separation`) and
d_i(F) = sum_j (C1 + C2)_ij F_j + delta_i(F_i / l_i) the deflection: the
finite-element influence coefficients of both members
(:mod:`lsbg.tooth.compliance`, interpolated bilinearly over the flank grid,
coupled between neighbouring teeth, symmetrised) and the local Hertz approach
(:mod:`lsbg.tooth.local`). It is solved by an active-set method on the
points in contact with the Hertz term as a secant compliance, iterated to a
fixed point; the compliance is fixed per design point, so each position is a
small dense solve.

Outputs beside the uniform line model's (:func:`lsbg.ltca.loaded_tca`): the
loaded transmission error, the mesh stiffness, the load of each tooth pair,
the Hertz peak pressure over the flank and its maximum per position, and the
root stress of pinion and gear (the largest tensile principal stress at the
fillet points of the tooth carrying the most stressful pair).

SI inside; the dataset speaks µrad, N/µm, MPa and mm.
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.contact import kernels as k

__all__ = ["ContactPoints", "contact_points", "solve_contact", "fe_loaded_tca"]

#: Relative change of the loads at which the Hertz fixed point stops [-].
TOLERANCE = 1e-10
#: Points of the exact relative curvature across the field [-].
CURVATURE_POINTS = 121
#: Most active-set and fixed-point iterations per solve [-].
MAX_ITERATIONS = 200


def _interpolation(axis, values):
    """Linear interpolation weights of values on an axis, extrapolating at the ends.

    Returns
    -------
    (index, weight) : numpy.ndarray, numpy.ndarray, shape (n,)
        value = (1 - w) f[i] + w f[i + 1].
    """
    i = np.clip(np.searchsorted(axis, values) - 1, 0, axis.size - 2)
    w = (values - axis[i]) / (axis[i + 1] - axis[i])
    return i, w


def _weights(compliance, rho, psi):
    """Bilinear weights of points on the flank grid, shape (n, f * p)."""
    f = compliance.sizes["face"]
    p = compliance.sizes["profile"]
    i, wi = _interpolation(compliance["cone_distance"].values, rho)
    j, wj = _interpolation(compliance["profile_angle"].values, psi)
    weights = np.zeros((rho.size, f, p))
    n = np.arange(rho.size)
    for di, a in ((0, 1 - wi), (1, wi)):
        for dj, b in ((0, 1 - wj), (1, wj)):
            weights[n, i + di, j + dj] += a * b
    return weights.reshape(rho.size, f * p)


class ContactPoints:
    """The bands of every tooth pair's contact line inside the field at one position.

    Attributes
    ----------
    pair : numpy.ndarray of int
        Tooth pair of each point, counted in base pitches from the first line [-].
    rho, psi : numpy.ndarray
        Position in the plane of action [m, rad].
    lever, length, separation : numpy.ndarray
        Lever rho cos(beta_p) [m], band length [m], initial separation [m].
    """

    def __init__(self, pair, rho, psi, lever, length, separation):
        self.pair, self.rho, self.psi = pair, rho, psi
        self.lever, self.length, self.separation = lever, length, separation


def contact_points(contact, mismatch_turn):
    """Contact points of the line model at a line turn of tooth pair 0.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        Line model (its bands and, for real flanks, its separation field).
    mismatch_turn : float
        Turn Psi of the contact line of tooth 0 in the plane of action [rad].

    Returns
    -------
    ContactPoints
    """
    sides, table = contact.arrays[1], contact.arrays[2]
    first, last = sides[0, k.S_FIRST], sides[0, k.S_LAST]
    psi_lo, psi_hi = sides[0, k.S_PSI_LO], sides[0, k.S_PSI_HI]
    bands = int(sides[0, k.S_ROWS])
    band = table[0, :bands]
    pitch = contact.pitch
    turn = mismatch_turn + math.ceil((first - mismatch_turn) / pitch) * pitch
    rows = []
    n = 0
    while turn <= last:
        # as the line model's kernel does (lsbg.contact.kernels._line_side): a
        # band cut by the field's edge acts at the middle of its inside part
        a, b = turn + band[:, k.B_THETA_IN], turn + band[:, k.B_THETA_OUT]
        lo, hi = np.minimum(a, b), np.maximum(a, b)
        top, bottom = np.minimum(hi, psi_hi), np.maximum(lo, psi_lo)
        inside = top > bottom
        fraction = np.where(inside, (top - bottom) / np.where(hi > lo, hi - lo, 1.0), 0.0)
        t = np.where(fraction < 1.0, 0.5 * (top + bottom - a - b) / (b - a), 0.0)
        if np.any(inside):
            rho = band[:, k.B_RHO] + t * band[:, k.B_D_RHO]
            cos_t = band[:, k.B_COS] + t * band[:, k.B_D_COS]
            sin_t = band[:, k.B_SIN] + t * band[:, k.B_D_SIN]
            psi = turn + np.arctan2(sin_t, cos_t)
            lever = band[:, k.B_LEVER] + t * band[:, k.B_D_LEVER]
            length = fraction * band[:, k.B_LENGTH]
            s = (contact.separation(np.full(rho.size, turn), rho)
                 if contact.separation is not None else np.zeros(rho.size))
            rows.append(tuple(np.asarray(v)[inside] for v in (
                np.full(rho.size, n), rho, psi, lever, length, np.asarray(s, float))))
        turn += pitch
        n += 1
    if not rows:
        raise ValueError("no contact line meets the field of contact")
    return ContactPoints(*(np.concatenate(c) for c in zip(*rows)))


class FECompliance:
    """Compliance of the contact points of a design point, from its FE dataset.

    Parameters
    ----------
    dataset : xarray.Dataset
        :func:`lsbg.tooth.compliance.tooth_compliance`.
    pair : lsbg.geometry.GearPair
    orientation : {-1, 1}
        :attr:`lsbg.contact.MeshContact.orientation`.
    band_rho : numpy.ndarray
        Cone distances of the line model's bands [m].
    """

    def __init__(self, dataset, pair, orientation, band_rho):
        from lsbg.tooth.local import relative_curvature

        self.dataset, self.pair = dataset, pair
        # a line one base pitch further on is carried by the teeth one pitch
        # away in the sense of MeshContact.orientation (tested)
        self.orientation = int(orientation)
        self.young = float(dataset.attrs["material_young_modulus"])
        self.poisson = float(dataset.attrs["material_poisson_ratio"])
        f, p = dataset.sizes["face"], dataset.sizes["profile"]
        self.blocks = {}
        for name in ("pinion", "gear"):
            c = dataset[f"compliance_{name}"].values.reshape(3, f * p, f * p)
            self.blocks[name] = c
        # the relative curvature, exact on a fine grid of the whole field at the
        # line model's band centres (it grows without bound towards a base cone,
        # where the pinion's field of contact can end: no coarse grid follows it)
        psi_lo, psi_hi = pair.planes["drive"].field[:2]
        inset = 0.005 * (psi_hi - psi_lo)  # the field's edge can sit on a base cone
        self.curvature_psi = np.linspace(psi_lo + inset, psi_hi - inset, CURVATURE_POINTS)
        self.curvature_rho = np.asarray(band_rho, float)
        rho, psi = np.meshgrid(self.curvature_rho, self.curvature_psi, indexing="ij")
        self.radius = (1.0 / relative_curvature(pair, rho.ravel(), psi.ravel())).reshape(rho.shape)
        self.depth = {name: dataset[f"half_thickness_{name}"].values.ravel()
                      for name in ("pinion", "gear")}
        self.stress = {name: dataset[f"fillet_stress_{name}"].values.reshape(
            -1, 3, 3, f * p) for name in ("pinion", "gear")}

    def weights(self, points):
        """Bilinear weights of the points on the flank grid, shape (n, f * p)."""
        return _weights(self.dataset, points.rho, points.psi)

    def matrix(self, points, w):
        """Symmetric compliance of contact points, both members [m/N]; ``w`` their
        :meth:`weights`."""
        offset = self.orientation * (points.pair[:, None] - points.pair[None, :])
        out = np.zeros((points.rho.size, points.rho.size))
        for o, tooth in enumerate((-1, 0, 1)):
            mask = offset == tooth
            if not mask.any():
                continue
            total = self.blocks["pinion"][o] + self.blocks["gear"][o]
            out[mask] = (w @ total @ w.T)[mask]
        return 0.5 * (out + out.T)

    def point_values(self, points, w):
        """Relative curvature [1/m] and both half thicknesses [m] at the points; ``w``
        their :meth:`weights`."""
        band = np.argmin(np.abs(points.rho[:, None] - self.curvature_rho[None]), axis=1)
        # the radius of curvature runs nearly linearly along the profile
        radius = np.array([np.interp(s, self.curvature_psi, self.radius[b])
                           for b, s in zip(band, points.psi)])
        return 1.0 / radius, w @ self.depth["pinion"], w @ self.depth["gear"]


def solve_contact(compliance, points, torque, e2, local):
    """Loads and mismatch of one mesh position, by complementarity.

    Parameters
    ----------
    compliance : numpy.ndarray, shape (n, n)
        Symmetric influence coefficients of the points [m/N].
    points : ContactPoints
    torque : float
        Gear torque [N m], > 0.
    e2 : float
        sin of the gear's base cone angle [-].
    local : callable
        ``local(F)``: the local approach of each point under loads F [m].

    Returns
    -------
    loads : numpy.ndarray
        Normal force of each point [N].
    mismatch : float
        eps [rad].

    Raises
    ------
    RuntimeError
        If the active set or the Hertz fixed point does not settle.
    """
    lever, s = points.lever, points.separation
    n = lever.size
    # start: the points with the least separation per lever share the load
    active = s / lever <= np.min(s / lever) + 1e-12
    loads = np.zeros(n)
    guess = torque / (e2 * lever.sum())
    secant = local(np.full(n, guess)) / guess
    for _ in range(MAX_ITERATIONS):
        index = np.flatnonzero(active)
        m = compliance[np.ix_(index, index)] + np.diag(secant[index])
        system = np.zeros((index.size + 1, index.size + 1))
        system[:-1, :-1] = m
        system[:-1, -1] = -lever[index]
        system[-1, :-1] = e2 * lever[index]
        rhs = np.concatenate([-s[index], [torque]])
        solution = np.linalg.solve(system, rhs)
        forces, mismatch = solution[:-1], solution[-1]
        if np.any(forces < 0):
            active[index[forces < 0]] = False
            continue
        new = np.zeros(n)
        new[index] = forces
        gap = compliance @ new + secant * new - (lever * mismatch - s)
        open_ = ~active & (gap < -1e-12 * np.abs(lever * mismatch).max())
        if np.any(open_):
            active |= open_
            continue
        loaded = new > 0
        updated = secant.copy()
        updated[loaded] = local(new)[loaded] / new[loaded]
        change = np.max(np.abs(new - loads)) / max(np.max(new), 1e-300)
        loads, secant = new, updated
        if change < TOLERANCE:
            return loads, mismatch
    raise RuntimeError(f"the contact problem did not settle in {MAX_ITERATIONS} iterations "
                       f"(torque {torque!r} N m)")


def fe_loaded_tca(contact, compliance, load_torque, phases=200):
    """Loaded tooth contact analysis with the FE compliance over one mesh cycle.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        Line model of the pair (its bands, and its separation field for real
        flanks).
    compliance : xarray.Dataset
        :func:`lsbg.tooth.compliance.tooth_compliance` of the same design.
    load_torque : float
        Gear torque [N m], > 0.
    phases : int
        Mesh positions over one base pitch [-] (at least 8).

    Returns
    -------
    xarray.Dataset
        On ``mesh_phase``: ``transmission_error`` [urad], ``mesh_stiffness``
        [N/um], ``max_contact_pressure`` [MPa], ``root_stress_pinion`` and
        ``root_stress_gear`` [MPa] (largest tensile principal stress in the
        fillets), ``pair_load`` (mesh_phase, tooth_pair) [N]; and
        ``contact_pressure`` (cone_distance, profile_angle) [MPa], the
        largest Hertz pressure met at each point of the field over the cycle.
        Attributes: peak-to-peak TE, mean mesh stiffness (and per unit face
        width), the maxima of pressure and root stresses, the compliance's
        inputs hash.
    """
    import xarray as xr

    from lsbg.contact.mesh import MAX_PAIRS
    from lsbg.ltca import mesh_phase_pinion_angle, transmission_error_summary
    from lsbg.tooth.elasticity import largest_principal
    from lsbg.tooth.local import local_approach, peak_pressure

    if not (math.isfinite(load_torque) and load_torque > 0):
        raise ValueError(f"load_torque = {load_torque!r}: must be a number > 0 [N m]")
    if isinstance(phases, bool) or int(phases) != phases or phases < 8:
        raise ValueError(f"phases = {phases!r}: must be a whole number >= 8")
    design = contact.pair.design
    hash_ = compliance.attrs.get("inputs_hash")
    # the compliance holds only for the design it was computed for: every key
    for key, value in design.to_config().items():
        stored = compliance.attrs.get(f"design_{key}")
        if stored is None or (stored != value if isinstance(value, str)
                              else not math.isclose(float(stored), float(value), rel_tol=1e-12)):
            raise ValueError(f"the compliance dataset has design {key} = {stored!r}, the "
                             f"contact's design {value!r}: compute it for this design point")
    bands = contact.params.slices
    band_rho = contact.arrays[2][0, :bands, k.B_RHO]
    fe = FECompliance(compliance, contact.pair, contact.orientation, band_rho)
    e2 = contact.e2
    z1, z2 = design.teeth
    fraction = np.arange(int(phases)) / int(phases)
    pinion = mesh_phase_pinion_angle(contact, fraction)
    f, p = compliance.sizes["face"], compliance.sizes["profile"]
    grid_rho = compliance["cone_distance"].values
    grid_psi = compliance["profile_angle"].values
    psi_lo, psi_hi = contact.pair.planes["drive"].field[:2]
    pattern_psi = np.linspace(psi_lo, psi_hi, 61)
    pattern = np.zeros((bands, pattern_psi.size))
    te = np.zeros(phases)
    stiffness = np.zeros(phases)
    pressure_max = np.zeros(phases)
    root = {"pinion": np.zeros(phases), "gear": np.zeros(phases)}
    lines = MAX_PAIRS
    pair_load = np.zeros((phases, lines))
    for n, phi1 in enumerate(pinion):
        points = contact_points(contact, contact.orientation * phi1 * contact.e1)
        w = fe.weights(points)
        matrix = fe.matrix(points, w)
        curvature, h1, h2 = fe.point_values(points, w)

        def local(forces):
            return local_approach(forces / points.length, curvature, h1, h2, fe.young, fe.poisson)

        loads, eps = solve_contact(matrix, points, load_torque, e2, local)
        # mesh stiffness: central difference of the torque over the mismatch
        step = 1e-3 * load_torque
        _, eps_hi = solve_contact(matrix, points, load_torque + step, e2, local)
        _, eps_lo = solve_contact(matrix, points, load_torque - step, e2, local)
        # T2 = f(eps), phi2 = phi1 e1/e2 - eps/e2: -dT2/dphi2 = e2 dT2/deps
        stiffness[n] = e2 * 2 * step / (eps_hi - eps_lo) / contact.base_radius**2
        te[n] = eps / e2
        q = loads / points.length
        pressure = peak_pressure(q, curvature, fe.young, fe.poisson)
        pressure_max[n] = pressure.max()
        for line in np.unique(points.pair):
            on = points.pair == line
            if line < lines:
                pair_load[n, line] = loads[on].sum()
            for name in ("pinion", "gear"):
                stress = fe.stress[name] @ (w[on].T @ loads[on])  # (q, 3, 3)
                root[name][n] = max(root[name][n], float(largest_principal(stress).max()))
            band = np.argmin(np.abs(points.rho[on][:, None] - band_rho[None]), axis=1)
            column = np.clip(np.searchsorted(pattern_psi, points.psi[on]), 0, pattern_psi.size - 1)
            np.maximum.at(pattern, (band, column), pressure[on])
    attrs = {
        "title": f"Loaded TCA with the tooth's FE compliance of a {design.trace} spiral bevel "
                 f"gear pair ({z1}:{z2}, spiral angle {math.degrees(design.spiral_angle):g} deg)",
        "source": "lsbg.tooth.ltca.fe_loaded_tca: FE influence coefficients + Hertz line "
                  "contact, complementarity per position",
        "compliance": "fe",
        "compliance_inputs_hash": str(hash_),
        "load_torque_N_m": float(load_torque),
        "phases": int(phases),
        **transmission_error_summary(te, stiffness, design.face_width),
        "max_contact_pressure_MPa": float(pressure_max.max() * 1e-6),
        "max_root_stress_pinion_MPa": float(root["pinion"].max() * 1e-6),
        "max_root_stress_gear_MPa": float(root["gear"].max() * 1e-6),
        **(contact.separation.attrs if contact.separation is not None else {}),
    }
    return xr.Dataset(
        {
            "transmission_error": ("mesh_phase", te * 1e6, {"units": "urad"}),
            "mesh_stiffness": ("mesh_phase", stiffness * 1e-6, {"units": "N/um"}),
            "max_contact_pressure": ("mesh_phase", pressure_max * 1e-6, {
                "units": "MPa", "long_name": "largest Hertz peak pressure on the flanks"}),
            "root_stress_pinion": ("mesh_phase", root["pinion"] * 1e-6, {
                "units": "MPa", "long_name": "largest tensile principal stress in the "
                                             "pinion's root fillets"}),
            "root_stress_gear": ("mesh_phase", root["gear"] * 1e-6, {
                "units": "MPa", "long_name": "largest tensile principal stress in the "
                                             "gear's root fillets"}),
            "pair_load": (("mesh_phase", "tooth_pair"), pair_load, {"units": "N"}),
            "contact_pressure": (("cone_distance", "profile_angle"), pattern * 1e-6, {
                "units": "MPa", "long_name": "largest Hertz pressure over the mesh cycle"}),
        },
        coords={"mesh_phase": ("mesh_phase", fraction, {"units": "1"}),
                "tooth_pair": ("tooth_pair", np.arange(lines)),
                "cone_distance": ("cone_distance", band_rho * 1e3, {"units": "mm"}),
                "profile_angle": ("profile_angle", np.degrees(pattern_psi),
                                  {"units": "degree"})},
        attrs=attrs)
