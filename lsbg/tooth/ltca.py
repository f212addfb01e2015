"""Loaded tooth contact analysis with the tooth's own compliance (FE + Hertz).

At each mesh position the contact lines of the line model (the bands of the
face width on every tooth pair whose line meets the field) are the contact
points (:mod:`lsbg.tooth.contact_points`). Their loads F >= 0 and the mismatch eps solve the contact problem as
what it is, a complementarity problem:

    gap_i = d_i(F) - (lever_i eps - s_i) >= 0,   F_i >= 0,   F_i gap_i = 0,
    e2 sum_i lever_i F_i = T,

where lever_i eps - s_i is the rigid approach of point i (the line model's,
with the separation s of real flanks, :mod:`lsbg.tca.separation`) and
d_i(F) = sum_j (C1 + C2)_ij F_j + delta_i(F_i / l_i) the deflection: the
finite-element influence coefficients of both members
(:mod:`lsbg.tooth.compliance`, interpolated bilinearly over the flank grid,
coupled between neighbouring teeth, symmetrised:
:class:`lsbg.tooth.contact_points.FECompliance`) and the local Hertz approach
(:mod:`lsbg.tooth.local`). It is solved by an active-set method on the
points in contact with Newton's method on the Hertz term (its derivative is
analytic, :class:`lsbg.tooth.local.HertzLines`), each position started from
the last one's loads; the compliance is fixed per design point, so each
position is a few small dense solves. The field of contact is bounded by
where both members' generated flanks start (:func:`active_field`): a small
pinion's involute does not reach its base cone, where its curvature is
infinite.

Outputs beside the uniform line model's (:func:`lsbg.tca.loaded.loaded_tca`): the
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
from lsbg.tooth.contact_points import FECompliance, contact_points
from lsbg.tooth.field import active_field

__all__ = ["EdgeLoads", "MeshCycle", "Position", "fe_loaded_tca", "position_setup",
           "solve_contact"]

#: Relative change of the loads at which the Hertz fixed point stops [-].
TOLERANCE = 1e-10
#: Most active-set and fixed-point iterations per solve [-].
MAX_ITERATIONS = 200


def solve_contact(compliance, points, torque, e2, local, tangent=None, start=None):
    """Loads and mismatch of one mesh position, by complementarity.

    An active-set method on the points in contact, with Newton's method on
    the nonlinear local approach: on the active set A the equations

        C_AA F_A + d_A(F_A) - lever_A eps = -s_A,   e2 lever_A . F_A = T

    are linearised at the current loads, d_i(F) ~ d_i(F_i) + t_i (F - F_i)
    with t_i the ``tangent``; a point that has just entered contact (F_i = 0,
    where the tangent of Hertz's approach is infinite) is linearised by its
    secant at the mean load T / (e2 sum lever) instead. Points with a negative
    load leave A, points with a negative gap join it, until a complementary
    solution's loads change by less than :data:`TOLERANCE`. Without
    ``tangent`` the secant d_i(F_i)/F_i stands in for it, which is the fixed
    point iteration of a secant compliance (linear convergence; Newton's is
    quadratic: 3-4 solves instead of ~17 for Hertz's approach).

    Parameters
    ----------
    compliance : numpy.ndarray, shape (n, n)
        Symmetric influence coefficients of the points [m/N].
    points : lsbg.tooth.contact_points.ContactPoints
    torque : float
        Gear torque [N m], > 0.
    e2 : float
        sin of the gear's base cone angle [-].
    local : callable
        ``local(F)``: the local approach of each point under loads F [m],
        zero where F is.
    tangent : callable, optional
        ``tangent(F)``: d local_i / d F_i [m/N] where F_i > 0.
    start : numpy.ndarray, optional
        Loads to start from [N] (a solution at a nearby torque): its loaded
        points are the first active set. By default the points with the least
        separation per lever, unloaded.

    Returns
    -------
    loads : numpy.ndarray
        Normal force of each point [N].
    mismatch : float
        eps [rad].

    Raises
    ------
    RuntimeError
        If the active set or the Newton iteration does not settle.
    """
    lever, s = points.lever, points.separation
    n = lever.size
    if start is not None and (np.asarray(start) > 0).any():
        loads = np.where(np.asarray(start, float) > 0, np.asarray(start, float), 0.0)
        active = loads > 0
    else:
        # the points with the least separation per lever share the load first
        active = s / lever <= np.min(s / lever) + 1e-12
        loads = np.zeros(n)
    guess = torque / (e2 * lever.sum())
    entering = local(np.full(n, guess)) / guess
    # points linearised by their secant, a line through d(0) = 0 (see below)
    secant = np.zeros(n, bool) if tangent is not None else np.ones(n, bool)
    # local(loads), tangent(loads): once per loads (not per active set or secants)
    approach = slopes = None
    for _ in range(MAX_ITERATIONS):
        index = np.flatnonzero(active)
        size = index.size
        f = loads[index]
        on = f > 0
        slope = entering[index]  # a copy (fancy indexing)
        offset = np.zeros(size)
        newton = on & ~secant[index]
        if on.any():
            if approach is None:
                approach = local(loads)
            d = approach[index]
            slope[on] = d[on] / f[on]
            if newton.any():
                if slopes is None:
                    slopes = tangent(loads)
                slope[newton] = slopes[index][newton]
                offset[newton] = d[newton] - slope[newton] * f[newton]
        system = np.zeros((size + 1, size + 1))
        system[:-1, :-1] = compliance[index[:, None], index]
        system.reshape(-1)[:size * (size + 2):size + 2] += slope  # the diagonal's view
        system[:-1, -1] = -lever[index]
        system[-1, :-1] = e2 * lever[index]
        solution = np.linalg.solve(system, np.concatenate([-s[index] - offset, [torque]]))
        forces, mismatch = solution[:-1], solution[-1]
        negative = forces < 0
        if (negative & newton).any():
            # the tangent of the concave approach passes above d(0) = 0: a
            # point whose load tends to 0 could be dropped and re-opened
            # forever; its secant, exact at 0, decides whether it is in contact
            secant[index[newton & negative]] = True
            continue
        if negative.any():
            active[index[negative]] = False
            continue
        new = np.zeros(n)
        new[index] = forces
        # the unloaded points' gap: their local approach is zero
        rigid = lever * mismatch
        gap = compliance @ new - (rigid - s)
        open_ = ~active & (gap < -1e-12 * np.abs(rigid).max())
        if open_.any():
            active |= open_
            continue
        change = np.abs(new - loads).max() / max(new.max(), 1e-300)
        loads, approach, slopes = new, None, None
        if change < TOLERANCE:
            return loads, mismatch
    raise RuntimeError(f"the contact problem did not settle in {MAX_ITERATIONS} iterations "
                       f"(torque {torque!r} N m)")


class EdgeLoads:
    """The load an LTCA's points carry at the ends of the active profile and at the
    starts of tip reliefs, per mesh position.

    A point whose band reaches the end of the field
    (:attr:`lsbg.tooth.contact_points.ContactPoints.edge`) is carried by a
    member's tip edge, or by the start of a generated flank: Hertz's contact of
    two flanks (the ``pressure`` there) does not hold at such an edge, whose
    own radius the model does not know, so the load is reported as what it
    is, a share of the load and a line load. A point whose band spans the
    start of a tip relief (:meth:`lsbg.tca.modification.FlankModification.relief_starts`)
    sits on the kink of the relieved profile. The largest Hertz pressure off
    both is the flank's (``max_flank_pressure``).

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        Its separation field's modification places the reliefs' starts.
    phases : int
        Mesh positions [-].
    """

    def __init__(self, contact, phases):
        from lsbg.tca.modification import pinion_tip_end

        plane = contact.pair.planes["drive"]
        centre = 0.5 * (plane.field[0] + plane.field[1])
        half = 0.5 * (plane.field[1] - plane.field[0])
        modification = getattr(contact.separation, "modification", None)
        starts = ({} if modification is None
                  else modification.relief_starts(pinion_tip_end(contact.pair)))
        #: psi of each relief's start [rad]
        self.starts = np.array([centre + v * half for v in starts.values()])
        self.relieved = ", ".join(f"{name}'s tip" for name in starts) or "none"
        self.share = np.zeros(phases)
        self.line_load = np.zeros(phases)
        self.kink_share = np.zeros(phases)
        self.kink_line_load = np.zeros(phases)
        self.flank_pressure = np.zeros(phases)

    def add(self, n, points, loads, pressure):
        """Record position n: its points, loads [N] and Hertz pressures [Pa]."""
        total = loads.sum()
        q = loads / points.length
        edge = points.edge != 0
        kink = np.zeros(loads.size, bool)
        for psi in self.starts:
            kink |= (points.psi_from < psi) & (psi < points.psi_to)
        for mask, share, line in ((edge, self.share, self.line_load),
                                  (kink & ~edge, self.kink_share, self.kink_line_load)):
            if np.any(mask):
                share[n] = loads[mask].sum() / total
                line[n] = q[mask].max()
        flank = ~(edge | kink)
        self.flank_pressure[n] = pressure[flank].max() if np.any(flank) else 0.0

    def variables(self):
        """The dataset's variables on ``mesh_phase``."""
        return {
            "edge_load_share": ("mesh_phase", self.share, {
                "units": "1", "long_name": "share of the load at profile edges",
                "description": "share of the normal load carried by the bands whose contact "
                               "line ends on a tip or a generated flank's start"}),
            "edge_line_load": ("mesh_phase", self.line_load * 1e-3, {
                "units": "N/mm", "long_name": "largest line load at a profile edge"}),
            "relief_start_load_share": ("mesh_phase", self.kink_share, {
                "units": "1", "long_name": "share of the load at tip relief starts"}),
            "relief_start_line_load": ("mesh_phase", self.kink_line_load * 1e-3, {
                "units": "N/mm", "long_name": "largest line load at a tip relief start"}),
            "max_flank_pressure": ("mesh_phase", self.flank_pressure * 1e-6, {
                "units": "MPa", "long_name": "largest Hertz pressure off the edges",
                "description": "largest Hertz peak pressure of the bands that neither reach "
                               "an end of the active profile nor span a tip relief's start"}),
        }

    def attrs(self):
        """The cycle's figures as dataset attributes."""
        return {"max_edge_load_share": float(self.share.max()),
                "max_edge_line_load_N_mm": float(self.line_load.max() * 1e-3),
                "max_relief_start_line_load_N_mm": float(self.kink_line_load.max() * 1e-3),
                "max_flank_pressure_MPa": float(self.flank_pressure.max() * 1e-6),
                "tip_relief": self.relieved}


class MeshCycle:
    """What an FE loaded TCA needs before any position, whatever the torque: checked
    inputs, the field of contact, the points' compliance and the mesh positions.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        Line model of the pair (bands, separation of real flanks).
    compliance : xarray.Dataset
        :func:`lsbg.tooth.compliance.tooth_compliance` of the same design.
    phases : int
        Mesh positions over one base pitch [-] (at least 8).
    form_limit : bool
        Bound the field by the generated flanks' starts (:func:`active_field`)
        or keep lsbg's.

    Raises
    ------
    ValueError
        ``phases`` not a whole number >= 8, or a compliance of another design.
    """

    def __init__(self, contact, compliance, phases, form_limit=True):
        from lsbg.gear.flank import mesh_phase_pinion_angle

        if isinstance(phases, bool) or int(phases) != phases or phases < 8:
            raise ValueError(f"phases = {phases!r}: must be a whole number >= 8")
        design = contact.pair.design
        # the compliance holds only for the design it was computed for: every key
        difference = design.attrs_difference(compliance.attrs)
        if difference is not None:
            key, stored, value = difference
            raise ValueError(f"the compliance dataset has design {key} = {stored!r}, the "
                             f"contact's design {value!r}: compute it for this design point")
        self.contact, self.inputs_hash = contact, compliance.attrs.get("inputs_hash")
        self.bands = contact.params.slices
        self.band_rho = contact.arrays[2][0, :self.bands, k.B_RHO]  # band centres [m]
        self.psi_lo, self.psi_hi = contact.pair.planes["drive"].field[:2]  # lsbg's [rad]
        self.form_limit = bool(form_limit)
        self.field = None  # (psi_lo, psi_hi) per band [rad], None: lsbg's
        if form_limit:
            # the rack's edge: the FE segment's root fillet (lsbg.tooth.segment)
            edge = float(compliance.attrs.get("fe_fillet_radius", 0.25)) * design.mean_module \
                * math.cos(design.spiral_angle)
            self.field = active_field(contact.pair, edge, self.band_rho)
        self.fe = FECompliance(compliance, contact.pair, contact.orientation, self.band_rho,
                               self.field)
        self.phases = int(phases)
        self.fraction = np.arange(self.phases) / self.phases  # mesh phase [-]
        self.pinion = mesh_phase_pinion_angle(contact.pair, self.fraction)  # [rad]

    def field_attrs(self):
        """The field's attributes: form limit, outer bounds across the profile [deg]."""
        lo, hi = self.field if self.form_limit else (self.psi_lo, self.psi_hi)
        return {"form_limit": "generated flanks" if self.form_limit else "lsbg field",
                "field_psi_lo_deg": float(np.degrees(np.min(lo))),
                "field_psi_hi_deg": float(np.degrees(np.max(hi)))}


class Position:
    """One mesh position's contact problem, all of it that the torque leaves alone
    (:func:`position_setup`).

    Attributes
    ----------
    cycle : MeshCycle
    mismatch_turn : float
        Line turn of tooth pair 0 [rad].
    points : lsbg.tooth.contact_points.ContactPoints
    weights : numpy.ndarray, shape (n, f * p)
        Bilinear weights of the points on the flank grid [-].
    matrix : numpy.ndarray, shape (n, n)
        Their symmetric FE compliance [m/N].
    curvature : numpy.ndarray
        Relative curvature across the contact lines [1/m].
    hertz : lsbg.tooth.local.HertzLines
    key : numpy.ndarray of int
        Tooth pair times the bands plus the band: a point's from one position
        to the next [-].
    separations : dict
        Its lines' separations (:func:`lsbg.tooth.contact_points.contact_points`).
    """

    def __init__(self, cycle, mismatch_turn, points, weights, matrix, curvature, hertz, key,
                 separations):
        self.cycle, self.mismatch_turn, self.points = cycle, mismatch_turn, points
        self.weights, self.matrix, self.curvature = weights, matrix, curvature
        self.hertz, self.key, self.separations = hertz, key, separations

    def start(self, previous):
        """Loads [N] of the same tooth pairs and bands at the last position, given its
        ``(key, loads)`` (0 for a point new in mesh); None without one."""
        if previous is None:
            return None
        at = np.clip(np.searchsorted(previous[0], self.key), 0, previous[0].size - 1)
        return np.where(previous[0][at] == self.key, previous[1][at], 0.0)

    def solve(self, torque, start=None):
        """:func:`solve_contact` at a gear torque [N m]: loads [N], mismatch [rad]."""
        return solve_contact(self.matrix, self.points, torque, self.cycle.contact.e2,
                             self.hertz.approach, self.hertz.tangent, start=start)

    def pressure(self, loads):
        """Hertz peak pressure of each point [Pa] under its load [N]."""
        from lsbg.tooth.local import peak_pressure

        fe = self.cycle.fe
        return peak_pressure(loads / self.points.length, self.curvature, fe.young, fe.poisson)

    def pair_loads(self, loads):
        """Per tooth pair in mesh under the points' loads [N]: its line [-], its load
        [N], its loads on the flank grid, shape (pairs, f * p) [N], and the index
        into the lines of each point [-]."""
        line, which = np.unique(self.points.pair, return_inverse=True)
        each = np.zeros((line.size, self.points.pair.size))
        each[which, np.arange(self.points.pair.size)] = loads
        return line, np.bincount(which, loads, line.size), each @ self.weights, which


def position_setup(cycle, pinion_angle):
    """The contact problem at one mesh position, as far as it does not depend on the torque.

    The line model's points inside the cycle's field, their weights on the
    flank grid, their FE compliance, the relative curvature and both half
    thicknesses under them (Hertz's approach), and their keys.

    Parameters
    ----------
    cycle : MeshCycle
    pinion_angle : float
        Pinion angle of the position [rad] (:attr:`MeshCycle.pinion`).

    Returns
    -------
    Position
    """
    from lsbg.tooth.local import HertzLines

    contact, fe = cycle.contact, cycle.fe
    mismatch_turn = contact.orientation * pinion_angle * contact.e1
    separations = {}  # the lines' separations, for the line model's points too
    points = contact_points(contact, mismatch_turn, cycle.field, separations)
    w = fe.weights(points)
    curvature, h1, h2 = fe.point_values(points, w)
    hertz = HertzLines(points.length, curvature, h1, h2, fe.young, fe.poisson)
    # a point keeps its tooth pair (line turn less the mismatch turn, in
    # pitches) and band from one position to the next: the last position's
    # loads start this one's Newton iteration near its solution (which is
    # unique, the local approach being monotone: lsbg.tooth.local)
    key = np.rint((points.turn - mismatch_turn) / contact.pitch).astype(int) * cycle.bands \
        + points.band
    return Position(cycle, mismatch_turn, points, w, fe.matrix(points, w), curvature, hertz, key,
                    separations)


def _slice_records(points, nominal, loads, eps, bands):
    """The line model's slices at one position: the FE load each carries.

    Parameters
    ----------
    points : lsbg.tooth.contact_points.ContactPoints
        The LTCA's points (within the generated flanks' field).
    nominal : lsbg.tooth.contact_points.ContactPoints
        The line model's points at the same position (its whole field).
    loads : numpy.ndarray
        Loads of ``points`` [N].
    eps : float
        Mismatch [rad].
    bands : int
        Bands of the face width [-].

    Returns
    -------
    tuple of numpy.ndarray
        Per point of ``nominal``: line turn [rad], band [-], the FE load of the
        same tooth pair and band, moved to the line model's lever [N] (0 where
        the LTCA has no point), the line
        model's approach there, lever eps - s [m], its band length [m], and
        whether the LTCA has the point.
    """
    key = points.pair * bands + points.band
    wanted = nominal.pair * bands + nominal.band
    order = np.argsort(key)
    at = np.clip(np.searchsorted(key[order], wanted), 0, key.size - 1)
    present = key[order][at] == wanted
    # a band that the generated flank's start cuts acts at the middle of its part
    # inside, the line model's at the middle of its own: the same moment about the
    # gear's axis, so that the line model's equilibrium is the LTCA's
    force = np.where(present, loads[order][at] * points.lever[order][at] / nominal.lever, 0.0)
    return (nominal.turn, nominal.band, force, nominal.lever * eps - nominal.separation,
            nominal.length, present)


def fe_loaded_tca(contact, compliance, load_torque, phases=200, form_limit=True):
    """Loaded tooth contact analysis with the FE compliance over one mesh cycle.

    The contact points are the line model's bands within the field of contact
    that both members' generated flanks bound (:func:`active_field`, the
    rack's edge radius that of the FE segment's root fillets), not only the
    mating tips. lsbg's flanks are involutes down to the base cone, and where
    a mate's tip overshoots a small pinion's base cone (lsbg's ``undercut``)
    its field ends on that base cone's tangency line, where the involute's
    radius of curvature is zero: the Hertz pressure p0 = sqrt(q E*/(pi R))
    has no bound there, and the cycle's largest pressure was the one at the
    curvature table's inset from that line (R ~ 0.09 mm; 3.0e4-3.5e4 MPa
    for the paper's 9-tooth pinion, whatever the phases and bands). A pinion
    generated with these proportions is undercut there: its involute, and
    the path of contact, start about 0.4-0.6 deg of polar angle inside lsbg's
    field (R ~ 0.6-1.1 mm). ``form_limit=False`` keeps lsbg's field, the
    line model's.

    The largest pressure of the cycle is then met at that start of the
    pinion's flank, on the band by which a tooth pair enters (or leaves)
    contact: with flanks relieved less than the loaded deflection of the
    pairs in mesh, the entering pair meets that interference with a short
    line, whose load per length only the Hertz approach limits (~3 times the
    mean). Near the pitch line the pressure is that of q ~ 1000 N/mm on
    R ~ 7.5 mm, ~2.2 GPa.

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
    form_limit : bool
        Bound the field by the generated flanks' starts (default) or keep
        lsbg's field of contact.

    Returns
    -------
    xarray.Dataset
        On ``mesh_phase``: ``transmission_error`` [urad], ``mesh_stiffness``
        [N/um], ``max_contact_pressure`` [MPa], ``root_stress_pinion`` and
        ``root_stress_gear`` [MPa] (largest tensile principal stress in the
        fillets), ``pair_load`` (mesh_phase, tooth_pair) [N]; and
        ``contact_pressure`` (cone_distance, profile_angle) [MPa], the
        largest Hertz pressure met at each point of the field over the cycle;
        ``slice_stiffness`` (line_turn, cone_distance) [N/(mm um)], the line
        model's stiffness per slice that carries these loads
        (:mod:`lsbg.tooth.slices`); the load at the profile's ends and at tip
        reliefs' starts and the largest pressure off them (:class:`EdgeLoads`).
        Attributes: peak-to-peak TE, mean mesh stiffness (and per unit face
        width), the maxima of pressure and root stresses, the compliance's
        inputs hash, ``form_limit`` and the field's outer bounds across the
        profile over the face width (``field_psi_lo_deg``,
        ``field_psi_hi_deg``).
    """
    import xarray as xr

    from lsbg.contact.mesh import MAX_PAIRS
    from lsbg.tca.loaded import transmission_error_summary
    from lsbg.tooth.slices import slice_stiffness_grid

    if not (math.isfinite(load_torque) and load_torque > 0):
        raise ValueError(f"load_torque = {load_torque!r}: must be a number > 0 [N m]")
    cycle = MeshCycle(contact, compliance, phases, form_limit)
    design = contact.pair.design
    bands, band_rho, field, e2 = cycle.bands, cycle.band_rho, cycle.field, contact.e2
    z1, z2 = design.teeth
    fraction = cycle.fraction
    pattern_psi = np.linspace(cycle.psi_lo, cycle.psi_hi, 61)
    pattern = np.zeros((bands, pattern_psi.size))
    te, stiffness, pressure_max = np.zeros(phases), np.zeros(phases), np.zeros(phases)
    lines = MAX_PAIRS
    pair_load = np.zeros((phases, lines))
    edges = EdgeLoads(contact, phases)
    previous = None  # keys and loads of the last position's points
    grid_loads = []  # (position, loads of each tooth pair on the flank grid) [N]
    records = []     # the line model's slices at each position (lsbg.tooth.slices)
    for n, phi1 in enumerate(cycle.pinion):
        position = position_setup(cycle, phi1)
        points = position.points
        loads, eps = position.solve(load_torque, position.start(previous))
        previous = position.key, loads
        nominal = points if field is None else contact_points(
            contact, position.mismatch_turn, separations=position.separations)
        records.append(_slice_records(points, nominal, loads, eps, bands))
        # mesh stiffness: central difference of the torque over the mismatch;
        # from the solution at the torque itself Newton needs one or two steps
        step = 1e-3 * load_torque
        _, eps_hi = position.solve(load_torque + step, loads)
        _, eps_lo = position.solve(load_torque - step, loads)
        # T2 = f(eps), phi2 = phi1 e1/e2 - eps/e2: -dT2/dphi2 = e2 dT2/deps
        stiffness[n] = e2 * 2 * step / (eps_hi - eps_lo) / contact.base_radius**2
        te[n] = eps / e2
        pressure = position.pressure(loads)
        pressure_max[n] = pressure.max()
        edges.add(n, points, loads, pressure)
        line, total, on_grid, _ = position.pair_loads(loads)
        kept = line < lines
        pair_load[n, line[kept]] = total[kept]
        grid_loads.append((np.full(line.size, n), on_grid))
        band = np.argmin(np.abs(points.rho[:, None] - band_rho[None]), axis=1)
        column = np.clip(np.searchsorted(pattern_psi, points.psi), 0, pattern_psi.size - 1)
        np.maximum.at(pattern, (band, column), pressure)
    root = cycle.fe.root_stresses(grid_loads, phases)
    turn, band, force, approach, length, present = (np.concatenate(c) for c in zip(*records))
    line_turn, slice_k = slice_stiffness_grid(turn, band, force, approach, length, present,
                                              contact.pitch, phases, bands)
    attrs = {
        "title": f"Loaded TCA with the tooth's FE compliance of a {design.trace} spiral bevel "
                 f"gear pair ({z1}:{z2}, spiral angle {math.degrees(design.spiral_angle):g} deg)",
        "source": "lsbg.tooth.ltca.fe_loaded_tca: FE influence coefficients + Hertz line "
                  "contact, complementarity per position",
        "compliance": "fe",
        "compliance_inputs_hash": str(cycle.inputs_hash),
        "load_torque_N_m": float(load_torque),
        "phases": int(phases),
        **transmission_error_summary(te, stiffness, design.face_width),
        "max_contact_pressure_MPa": float(pressure_max.max() * 1e-6),
        "max_root_stress_pinion_MPa": float(root["pinion"].max() * 1e-6),
        "max_root_stress_gear_MPa": float(root["gear"].max() * 1e-6),
        **edges.attrs(),
        **cycle.field_attrs(),
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
            **edges.variables(),
            "pair_load": (("mesh_phase", "tooth_pair"), pair_load, {"units": "N"}),
            "contact_pressure": (("cone_distance", "profile_angle"), pattern * 1e-6, {
                "units": "MPa", "long_name": "largest Hertz pressure over the mesh cycle"}),
            "slice_stiffness": (("line_turn", "cone_distance"), slice_k * 1e-9, {
                "units": "N/(mm um)", "long_name": "the line model's stiffness per unit "
                "length of each slice that carries this LTCA's loads (secant)"}),
        },
        coords={"mesh_phase": ("mesh_phase", fraction, {"units": "1"}),
                "line_turn": ("line_turn", line_turn, {
                    "units": "rad", "long_name": "turn of the contact line in the plane of "
                                                 "action"}),
                "tooth_pair": ("tooth_pair", np.arange(lines)),
                "cone_distance": ("cone_distance", band_rho * 1e3, {"units": "mm"}),
                "profile_angle": ("profile_angle", np.degrees(pattern_psi),
                                  {"units": "degree"})},
        attrs=attrs)
