"""The contact of a gear pair: its kernel data built from the exact geometry.

:class:`MeshContact` turns a :class:`lsbg.gear.geometry.GearPair` and
:class:`lsbg.contact.parameters.ContactParameters` into the arrays the compiled
kernels of :mod:`lsbg.contact.kernels` read, and gives them a Python face:
:meth:`MeshContact.forces` (all outputs at one state),
:meth:`MeshContact.pair_contacts` (per tooth pair), the static equilibrium
(:meth:`MeshContact.static_gear_angle`) and, for the line model, the mesh
stiffness and the damping that gives the mesh mode its damping ratio.

The line model's stiffness per unit length k_l is tied to the standard mesh
stiffness of steel gears through the virtual cylindrical gear at the mean
point (:func:`calibrated_line_stiffness`, docs/model.md).
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lsbg.contact import kernels as k
from lsbg.contact.parameters import ContactParameters
from lsbg.contact.statics import static_mismatch
from lsbg.gear.geometry import MEMBERS, SIDES

#: Samples of the point model's phase table per base pitch. At the paper's
#: speed the contact lines turn one table step in about 0.26 µs, below the
#: 1 µs time step.
PHASE_SAMPLES_PER_PITCH = 20000

#: Mesh stiffness per unit face width of steel gears, ISO 6336-1 c_γ (and
#: ISO 10300-1 for bevel gears through the virtual cylindrical gear)
#: [N/m per m: 20 N/(mm·µm)].
ISO_MESH_STIFFNESS = 20e9

#: Rows of the line model's separation table per base pitch of line turn: the
#: relief of a crowned flank changes over a pitch by a parabola, which linear
#: interpolation at this spacing follows to about 1e-5 of its amplitude.
SEPARATION_ROWS_PER_PITCH = 128

#: Torque at which real flanks count as just touching in a static solve [N m].
FIRST_TOUCH_TORQUE = 1e-6

#: Most tooth pairs whose contact lines can meet the field at once, per side.
MAX_PAIRS = 8


class MeshForces(NamedTuple):
    """Contact outputs at one state (see :func:`lsbg.contact.kernels.mesh_forces`)."""

    gear_torque: float       #: about the gear's forward axis [N m]
    pinion_torque: float     #: about the pinion's forward axis [N m]
    max_penetration: float   #: deepest normal approach (<= 0: no contact) [m]
    tangential_force: float  #: on the gear, circumferential, summed [N]
    normal_force: float      #: sum of the normal forces [N]
    pairs: int               #: tooth pairs carrying load [-]


@dataclass(frozen=True)
class PairContact:
    """Contact of one tooth pair, for output and checks.

    Attributes
    ----------
    side : str
        "drive" or "coast".
    phase : float
        Turn Psi of the contact line in its plane of action [rad].
    lever : float
        l = rho cos(beta_p) at the deepest point: penetration per unit
        mismatch and torque arm per unit base-cone sine [m].
    penetration : float
        Deepest normal approach x on the contact line [m].
    penetration_rate : float
        dx/dt there [m/s].
    normal_force : float
        Normal force of the pair (point: IMPACT; line: sum over slices) [N].
    friction_coefficient : float
        mu at the sliding speed (line: load-weighted mean) [-].
    sliding_speed : float
        Tangential sliding speed at the point of action (line: load-weighted
        mean) [m/s].
    gear_torque, pinion_torque : float
        Torques of this pair's normal and friction forces about each member's
        forward axis [N m].
    tangential_force : float
        Contact force on the gear along its circumferential direction at the
        point(s) of action [N].
    radius : float
        Distance of the point of action from the gear axis (line:
        load-weighted mean) [m].
    cone_distance : float
        Distance rho of the point of action from the apex (line: the load's
        centroid) [m]; the point is
        ``pair.planes[side].point(rho, phase + curve.polar_angle(rho))``.
    contact_length : float
        Line model: length of the pair's contact line inside the field [m]
        (0 for the point model).
    """

    side: str
    phase: float
    lever: float
    penetration: float
    penetration_rate: float
    normal_force: float
    friction_coefficient: float
    sliding_speed: float
    gear_torque: float
    pinion_torque: float
    tangential_force: float
    radius: float
    cone_distance: float
    contact_length: float


def _deepest_points(plane, lo, hi, inside, samples=33, rows=1024):
    """Deepest point of each contact line segment: the maximum of the lever
    rho cos(beta_p) over ``samples`` evenly spaced points of the segment.

    Parameters
    ----------
    plane : lsbg.gear.plane.PlaneOfAction
    lo, hi : numpy.ndarray
        Ends of the segments [m] (:meth:`~lsbg.gear.plane.PlaneOfAction.line_segment`).
    inside : numpy.ndarray of bool
        Segments that are not empty; an empty one gets the lever 0 [-].
    samples : int
        Points per segment [-].
    rows : int
        Segments per block [-]: a block's (rows, samples) work arrays (0.3 MB)
        stay in cache, those of all segments at once (14 MB) do not. Each
        point's arithmetic is the same, so the result is too.

    Returns
    -------
    rho_star, lever : numpy.ndarray
        Distance of the deepest point from the apex and rho cos(beta_p) there [m].
    """
    t = np.linspace(0.0, 1.0, samples)
    rho_star, lever = np.empty(lo.size), np.empty(lo.size)
    for start in range(0, lo.size, rows):
        block = slice(start, start + rows)
        rho = lo[block, None] + (hi[block] - lo[block])[:, None] * t
        rho = np.where(inside[block, None], rho, plane.field[3])
        lever_all = rho * np.cos(plane.curve.ray_angle(rho))
        best = np.argmax(lever_all, axis=1)
        index = np.arange(best.size)
        rho_star[block], lever[block] = rho[index, best], lever_all[index, best]
    return rho_star, np.where(inside, lever, 0.0)


class MeshContact:
    """Contact kernel data of a gear pair, point or line model.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    params : ContactParameters, optional
        Contact model and law; the paper's (point model) by default.
    gear_inertia : float, optional
        Axial moment of inertia of the gear [kg m^2]. The line model needs it
        for its damping (a damping ratio of the mesh mode, whose natural
        frequency is sqrt(k_theta / J2) with the pinion's motion prescribed);
        without it the line model is undamped, which only static analyses
        (:mod:`lsbg.tca.loaded`) should use.
    samples_per_pitch : int
        Resolution of the point model's phase tables [-].
    separation : callable, optional
        Line model on real flanks: ``separation(turn, cone_distance)``, the
        initial separation of the drive flanks [m] at the point of the
        contact line of turn Psi [rad] at distance rho from the apex [m]
        (arrays broadcast), from the flank modification and the assembly
        displacements (:func:`lsbg.tca.separation.separation_field`). It is
        tabulated at ``SEPARATION_ROWS_PER_PITCH`` rows per base pitch and
        subtracted from each slice's approach. None: conjugate flanks (the
        coast side always keeps them).
    slice_stiffness : lsbg.contact.slices.SliceStiffness, optional
        Line model with the tooth's own compliance: the drive side's
        stiffness per unit length of each slice over the line's turn (from
        the loaded TCA with the FE compliance), in place of the uniform k_l;
        each slice's damping scales with it, so it keeps the damping ratio.
        None: the uniform bed (the coast side always keeps it).

    Attributes
    ----------
    arrays : tuple of numpy.ndarray
        (params, sides, table) for the kernels of :mod:`lsbg.contact.kernels`.
    e1, e2 : float
        sin of the base cone angles [-].
    pitch : float
        Base pitch Psi_p of the contact lines in the plane of action [rad].
    damping_coefficient : float
        Line model: c_l, viscous load per unit length per unit approach rate
        [N·s/m^2] (0 for the point model).
    """

    def __init__(self, pair, params=None, gear_inertia=None,
                 samples_per_pitch=PHASE_SAMPLES_PER_PITCH, separation=None,
                 slice_stiffness=None):
        self.pair = pair
        self.separation = separation
        self.slice_stiffness = slice_stiffness
        # each band's stiffness over k_l, averaged over its passage (1: uniform bed)
        self._band_factor = None
        self.params = params if params is not None else ContactParameters()
        design = pair.design
        self.e1 = math.sin(design.base_cone_angle(1))
        self.e2 = math.sin(design.base_cone_angle(2))
        self.pitch = design.base_pitch_angle
        self.gear_inertia = gear_inertia
        # Sign of u_i . N (the same for both members and both sides).
        self.orientation = math.copysign(1.0, pair.axis_normal_component(1, "drive"))
        if not all(math.copysign(1.0, pair.axis_normal_component(m, s)) == self.orientation
                   for m in MEMBERS for s in SIDES):
            raise ValueError("the planes of action turn in different senses for the two members")
        # Mismatch offsets from the tooth thickness placement (zero on the drive
        # side; on the coast side the mismatch at drive contact is -c j / R_m).
        off = pair.flank_offset
        self.coast_offset = off[(2, "coast")] * self.e2 - off[(1, "coast")] * self.e1
        self.coast_pinion_offset = off[(1, "coast")]
        if self.params.model == "point":
            if separation is not None:
                raise ValueError("a separation field (flank modification, misalignment) is "
                                 "defined for the line model; the point model keeps the "
                                 "paper's conjugate flanks")
            if slice_stiffness is not None:
                raise ValueError("a slice stiffness (the tooth's compliance) is defined for "
                                 "the line model")
            self._sides, self._table = self._point_tables(samples_per_pitch)
        else:
            self._bands = self._line_bands(self.params.slices)
            self._sides, self._table = self._separation_bands(separation)
            if slice_stiffness is not None:
                self._add_slice_stiffness(slice_stiffness)
        # Stiffness-proportional damping of each slice, c_l = 2 zeta k_l / omega_n,
        # gives the mesh mode the damping ratio zeta at the mean stiffness.
        self.damping_coefficient = 0.0
        if self.params.model == "line" and gear_inertia is not None:
            omega = 2 * math.pi * self.natural_frequency(gear_inertia)
            self.damping_coefficient = 2.0 * self.params.damping_ratio * self.params.line_stiffness / omega
        self.arrays = (self._kernel_params(), self._sides, self._table)

    # ------------------------------------------------------------ kernel data
    def _kernel_params(self):
        p = self.params
        values = np.zeros(k.N_PARAMS)
        values[k.P_E1], values[k.P_E2], values[k.P_PITCH] = self.e1, self.e2, self.pitch
        values[k.P_ORIENTATION] = self.orientation
        values[k.P_COAST_OFFSET] = self.coast_offset
        values[k.P_COAST_PINION_OFFSET] = self.coast_pinion_offset
        values[k.P_MODEL] = k.MODEL_CODES[p.model]
        values[k.P_K], values[k.P_EXPONENT], values[k.P_C_MAX], values[k.P_DEPTH] = p.k, p.e, p.c_max, p.d
        values[k.P_MU_S], values[k.P_MU_D], values[k.P_V_S], values[k.P_V_D] = p.mu_s, p.mu_d, p.v_s, p.v_d
        values[k.P_LINE_K], values[k.P_LINE_C] = p.line_stiffness, self.damping_coefficient
        values[k.P_U12] = float(self.pair.rotation_axis[1] @ self.pair.rotation_axis[2])
        values[k.P_LINE_SHIFT] = 0.5 if p.model == "point" else 0.0
        return values

    def _line_range(self, plane):
        """Turns Psi of the contact lines that can meet the field [rad]."""
        psi_lo, psi_hi, r_in, r_out = plane.field
        theta = plane.curve.polar_angle(np.array([r_in, r_out]))
        return psi_lo - theta.max(), psi_hi - theta.min()

    def _side_row(self, plane):
        row = np.zeros(k.N_SIDE)
        row[k.S_FIRST], row[k.S_LAST] = self._line_range(plane)
        row[k.S_PSI_LO], row[k.S_PSI_HI] = plane.field[:2]
        u1, u2 = self.pair.rotation_axis[1], self.pair.rotation_axis[2]
        row[k.S_U1P], row[k.S_U1Q] = u1 @ plane.pitch_dir, u1 @ plane.cross_dir
        row[k.S_U2P], row[k.S_U2Q] = u2 @ plane.pitch_dir, u2 @ plane.cross_dir
        n1, n2 = np.cross(plane.normal, u1), np.cross(plane.normal, u2)
        row[k.S_N1P], row[k.S_N1Q] = n1 @ plane.pitch_dir, n1 @ plane.cross_dir
        row[k.S_N2P], row[k.S_N2Q] = n2 @ plane.pitch_dir, n2 @ plane.cross_dir
        return row

    def _point_tables(self, samples_per_pitch):
        """Per side, what depends only on the line's turn Psi: the lever at the
        deepest point and the circumferential products there."""
        pair = self.pair
        step_ = self.pitch / samples_per_pitch
        sides = np.zeros((2, k.N_SIDE))
        tables = []
        for s, side in enumerate(SIDES):
            plane = pair.planes[side]
            sides[s] = self._side_row(plane)
            first, last = sides[s, k.S_FIRST], sides[s, k.S_LAST]
            n = int(math.ceil((last - first) / step_)) + 2
            phases = first + step_ * np.arange(n)
            lo, hi = plane.line_segment(phases)
            inside = hi > lo
            rho_star, lever = _deepest_points(plane, lo, hi, inside)
            point = plane.point(rho_star, phases + plane.curve.polar_angle(rho_star))
            a = np.cross(pair.rotation_axis[1], point)  # pinion circumferential x radius
            b = np.cross(pair.rotation_axis[2], point)  # gear circumferential x radius
            columns = np.zeros((n, k.N_PHASE_COLUMNS))
            columns[:, k.T_LEVER] = lever
            columns[:, k.T_AA], columns[:, k.T_AB] = np.sum(a * a, 1), np.sum(a * b, 1)
            columns[:, k.T_BB], columns[:, k.T_RADIUS] = np.sum(b * b, 1), np.linalg.norm(b, axis=1)
            columns[:, k.T_RHO] = rho_star
            columns[~inside] = 0.0
            sides[s, k.S_INV_STEP], sides[s, k.S_ROWS] = 1.0 / step_, n
            tables.append(columns)
        table = np.zeros((2, max(len(t) for t in tables), k.N_PHASE_COLUMNS))
        for s, columns in enumerate(tables):
            table[s, :len(columns)] = columns
        return sides, table

    def _line_bands(self, bands):
        """Per side, the bands (slices) of the face width: mid distance, lever,
        length of the curve inside the band, and the curve's polar angles, on
        conjugate flanks. Returns ``(sides, table, edges, rho)``: the kernel's
        rows and the bands' edges and mid distances [m] for
        :meth:`_separation_bands`."""
        design = self.pair.design
        edges = np.linspace(design.inner_cone_distance, design.outer_cone_distance, bands + 1)
        rho = 0.5 * (edges[:-1] + edges[1:])
        sides = np.zeros((2, k.N_SIDE))
        table = np.zeros((2, bands, k.N_COLUMNS))
        for s, side in enumerate(SIDES):
            plane = self.pair.planes[side]
            sides[s] = self._side_row(plane)
            sides[s, k.S_ROWS] = bands
            curve = plane.curve
            lever = rho * np.cos(curve.ray_angle(rho))
            lever_edge = edges * np.cos(curve.ray_angle(edges))
            theta, theta_edge = curve.polar_angle(rho), curve.polar_angle(edges)
            table[s, :, k.B_RHO], table[s, :, k.B_D_RHO] = rho, np.diff(edges)
            table[s, :, k.B_LEVER], table[s, :, k.B_D_LEVER] = lever, np.diff(lever_edge)
            table[s, :, k.B_COS], table[s, :, k.B_D_COS] = np.cos(theta), np.diff(np.cos(theta_edge))
            table[s, :, k.B_SIN], table[s, :, k.B_D_SIN] = np.sin(theta), np.diff(np.sin(theta_edge))
            table[s, :, k.B_LENGTH] = np.diff(edges) * rho / lever  # d rho / cos(beta_p)
            table[s, :, k.B_THETA_IN], table[s, :, k.B_THETA_OUT] = theta_edge[:-1], theta_edge[1:]
        return sides, table, edges, rho

    def _separation_bands(self, separation):
        """The kernel's (sides, table) of :meth:`_line_bands`' conjugate bands with,
        for a ``separation`` field, the drive side's separation table after them
        (the conjugate rows themselves are not changed)."""
        sides, table, edges, rho = self._bands
        sides = sides.copy()  # the conjugate rows stay as they are for other flanks
        if separation is None:
            return sides, table.copy()
        bands = rho.size
        # Drive side: the separation at each band's centre and its change
        # across the band, on rows of line turn over the lines' whole range.
        first, last = sides[0, k.S_FIRST], sides[0, k.S_LAST]
        step_ = self.pitch / SEPARATION_ROWS_PER_PITCH
        rows = int(math.ceil((last - first) / step_)) + 2
        turns = first + step_ * np.arange(rows)
        centre = separation(turns[:, None], rho[None, :])
        edge = separation(turns[:, None], edges[None, :])
        if not (np.all(np.isfinite(centre)) and np.all(np.isfinite(edge))):
            raise ValueError("the separation field is not finite on the contact lines")
        full = np.zeros((2, bands, k.N_COLUMNS + 2 * rows))
        full[:, :, :k.N_COLUMNS] = table
        full[0, :, k.B_SEPARATION::2] = centre.T
        full[0, :, k.B_SEPARATION + 1::2] = np.diff(edge, axis=1).T
        sides[0, k.S_SEP_FIRST], sides[0, k.S_SEP_INV_STEP] = first, 1.0 / step_
        sides[0, k.S_SEP_ROWS] = rows
        # contact can begin at a negative mismatch where the flanks interfere
        lever = table[0, :, k.B_LEVER]
        lever_edge = edges * np.cos(self.pair.planes["drive"].curve.ray_angle(edges))
        lead = min(float(np.min(centre / lever)), float(np.min(edge / lever_edge)))
        sides[0, k.S_SEP_LEAD] = min(0.0, 1.1 * lead)
        return sides, full

    def with_separation(self, separation):
        """This line-model contact on other real flanks.

        The same as ``MeshContact(pair, params, gear_inertia, separation=separation)``
        bit for bit, without building the conjugate bands again: an ease-off
        search builds a contact per design and displacement on one pair.

        Parameters
        ----------
        separation : callable or None
            As the constructor's ``separation``.

        Returns
        -------
        MeshContact

        Raises
        ------
        ValueError
            For the point model or a contact with a slice stiffness (whose
            columns follow the separation's).
        """
        self._require_line("with_separation")
        if self.slice_stiffness is not None:
            raise ValueError("with_separation is defined for the uniform bed (no slice "
                             "stiffness)")
        other = copy.copy(self)
        other.separation = separation
        # the kernel parameters do not depend on the separation (nor does the
        # damping: it follows the conjugate bands' mean stiffness)
        other._sides, other._table = other._separation_bands(separation)
        other.arrays = (self.arrays[0], other._sides, other._table)
        return other

    def _add_slice_stiffness(self, slice_stiffness):
        """Append the drive side's slice-stiffness columns to the band table."""
        from lsbg.contact.slices import stiffness_columns

        table = self._table
        theta = np.arctan2(table[0, :, k.B_SIN], table[0, :, k.B_COS])
        columns, first, inv_step, self._band_factor = stiffness_columns(
            slice_stiffness, table[0, :, k.B_RHO], self.params.line_stiffness, theta,
            tuple(self._sides[0, [k.S_PSI_LO, k.S_PSI_HI]]))
        start = table.shape[2]
        full = np.zeros(table.shape[:2] + (start + columns.shape[1],))
        full[:, :, :start] = table
        full[0, :, start:] = columns
        self._sides[0, k.S_STIFF_FIRST], self._sides[0, k.S_STIFF_INV_STEP] = first, inv_step
        self._sides[0, k.S_STIFF_ROWS], self._sides[0, k.S_STIFF_COLUMN] = columns.shape[1], start
        self._table = full

    # ------------------------------------------------------------ evaluation
    def mismatch(self, pinion_angle, gear_angle):
        """Drive-side rotation mismatch eps = phi1 e1 - phi2 e2, wrapped [rad].

        Positive when the pinion leads (drive flanks penetrate).
        """
        half = 0.5 * self.pitch
        return (pinion_angle * self.e1 - gear_angle * self.e2 + half) % self.pitch - half

    def forces(self, pinion_angle, gear_angle, pinion_speed=0.0, gear_speed=0.0) -> MeshForces:
        """Contact outputs at one state.

        Parameters
        ----------
        pinion_angle, gear_angle : float
            Forward rotations phi1, phi2 [rad] (0, 0: drive flanks of tooth 0
            touch at the mean point).
        pinion_speed, gear_speed : float
            Forward angular speeds [rad/s].

        Returns
        -------
        MeshForces
        """
        return MeshForces(*k.mesh_forces(float(pinion_angle), float(gear_angle),
                                         float(pinion_speed), float(gear_speed), *self.arrays))

    def pair_contacts(self, pinion_angle, gear_angle, pinion_speed=0.0, gear_speed=0.0,
                      slice_loads=False):
        """Contact of every tooth pair whose line meets the field of contact.

        Parameters
        ----------
        pinion_angle, gear_angle, pinion_speed, gear_speed : float
            As :meth:`forces` [rad, rad/s].
        slice_loads : bool
            Line model: also return each pair's load per unit length per
            slice (band of the face width).

        Returns
        -------
        list of PairContact
            Drive side first.
        numpy.ndarray, shape (pairs, slices)
            Only with ``slice_loads``: load per unit length [N/m].
        """
        details = np.zeros((2 * MAX_PAIRS, k.N_DETAILS))
        bands = self.params.slices if self.params.model == "line" else 0
        loads = np.zeros((2 * MAX_PAIRS if bands else 0, bands))
        *_, count = k.mesh_details(float(pinion_angle), float(gear_angle), float(pinion_speed),
                                   float(gear_speed), *self.arrays, details, loads)
        if count >= 2 * MAX_PAIRS:
            raise ValueError(f"more than {2 * MAX_PAIRS} tooth pairs in contact: "
                             f"raise lsbg.contact.mesh.MAX_PAIRS")
        pairs = [PairContact(SIDES[int(row[k.D_SIDE])], *map(float, row[1:])) for row in details[:count]]
        return (pairs, loads[:count]) if slice_loads else pairs

    def static_gear_angle(self, load_torque, pinion_angle=0.0):
        """Gear rotation at which the contact carries ``load_torque`` at rest.

        Parameters
        ----------
        load_torque : float
            Resisting torque on the gear [N m], >= 0.
        pinion_angle : float
            Pinion rotation [rad].

        Returns
        -------
        float
            Gear rotation phi2 [rad] (the drive flanks are pressed together by
            the elastic approach that carries the load).

        Raises
        ------
        ValueError
            If the contact cannot carry the load within a tenth of a base
            pitch of approach.
        """
        base = pinion_angle * self.e1 / self.e2
        if load_torque <= 0.0:
            if self.separation is None:
                return base
            # real flanks: first touch, where the torque just rises
            load_torque = FIRST_TOUCH_TORQUE
        eps = static_mismatch(float(pinion_angle), base, self.e2, float(load_torque),
                                0.1 * self.pitch, *self.arrays)
        if not math.isfinite(eps):
            raise ValueError(f"load_torque = {load_torque!r}: the contact cannot carry it "
                             f"within a tenth of a base pitch of approach")
        return base - eps / self.e2

    # ------------------------------------------------------ line model: stiffness
    def _require_line(self, what):
        if self.params.model != "line":
            raise ValueError(f"{what} is defined for the line model (contact model "
                             f"{self.params.model!r})")

    def mean_torsional_stiffness(self):
        """Mean torsional mesh stiffness of the line model over a base pitch [N m/rad].

        k_theta = dT2/dphi2 = k_l e2^2 sum over the loaded slices of lever^2
        length. Over one base pitch each band is inside the field for the
        fraction (psi_hi - psi_lo) / Psi_p (the profile contact ratio) of the
        time, so the mean is closed form:
        ``k_l e2^2 eps_profile sum_j lever_j^2 length_j`` (drive side). With
        the tooth's slice stiffness each band's term carries its stiffness
        over k_l averaged over its passage through the field.
        """
        self._require_line("mean_torsional_stiffness")
        sides, table = self._sides, self._table
        profile = (sides[0, k.S_PSI_HI] - sides[0, k.S_PSI_LO]) / self.pitch
        terms = table[0, :, k.B_LEVER] ** 2 * table[0, :, k.B_LENGTH]
        integral = np.sum(terms if self._band_factor is None else terms * self._band_factor)
        return float(self.params.line_stiffness * self.e2**2 * profile * integral)

    @property
    def base_radius(self):
        """Gear's base radius at the mean point, r_b2 = R_m sin(delta_b2) [m].

        The lever of a force perpendicular to the ray in the plane of action
        at the mean point: the mesh force along the line of action there is
        F = T2 / r_b2, and the displacement along it is R_m eps.
        """
        return self.pair.design.mean_cone_distance * self.e2

    def mean_mesh_stiffness(self):
        """Mean mesh stiffness along the line of action at the mean point [N/m].

        ``k_mesh = k_theta / r_b2^2``: the mesh force F = T2 / r_b2 per unit
        displacement R_m eps = r_b2 phi2 along the transverse line of action
        of the virtual cylindrical gear at the mean point (ISO 10300).
        """
        return self.mean_torsional_stiffness() / self.base_radius**2

    def natural_frequency(self, gear_inertia):
        """Natural frequency of the mesh mode at the mean stiffness [Hz].

        The pinion follows its prescribed motion, so the gear of inertia J2
        rests on the mesh spring: f_n = sqrt(k_theta / J2) / (2 pi).

        Parameters
        ----------
        gear_inertia : float
            Axial moment of inertia of the gear [kg m^2].
        """
        return math.sqrt(self.mean_torsional_stiffness() / gear_inertia) / (2 * math.pi)


def calibrated_line_stiffness(pair, mesh_stiffness=ISO_MESH_STIFFNESS, side="drive"):
    """Line stiffness k_l that gives a pair a mean mesh stiffness per face width.

    With the normal load per unit length w = k_l x and x = rho cos(beta_p) eps,
    the torque of the lines inside the field is
    T2 = k_l eps e2 sum over the lines of the integral of rho^2 cos(beta_p) d rho,
    whose mean over a base pitch is a field integral (each point of the field
    is crossed once per pitch):
    ``<T2> = k_l eps e2 eps_profile int_{R_i}^{R_e} rho^2 cos(beta_p) d rho``.
    Referred to the virtual cylindrical gear at the mean point (force
    T2 / (R_m e2) along the line of action, displacement R_m eps), the mean
    mesh stiffness per unit face width is
    ``c_gamma = k_l eps_profile int rho^2 cos(beta_p) d rho / (R_m^2 b)``, so
    ``k_l = c_gamma R_m^2 b / (eps_profile int rho^2 cos(beta_p) d rho)``.
    For a helical gear (rho ~ R_m, beta_p the base helix angle) this is
    c_gamma = k_l eps_alpha cos(beta_b).

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    mesh_stiffness : float, default ISO 6336-1 c_γ = 20 N/(mm·µm)
        Mean mesh stiffness per unit face width [N/m^2].
    side : {"drive", "coast"}

    Returns
    -------
    float
        k_l [N/m^2]; 19.42 N/(mm·µm) for the paper's LSBG at 35°.
    """
    from scipy.integrate import quad

    design = pair.design
    plane = pair.planes[side]
    profile = (plane.field[1] - plane.field[0]) / design.base_pitch_angle
    integral, _ = quad(lambda rho: rho**2 * math.cos(float(plane.curve.ray_angle(rho))),
                       design.inner_cone_distance, design.outer_cone_distance, epsabs=0.0,
                       epsrel=1e-12)
    return mesh_stiffness * design.mean_cone_distance**2 * design.face_width / (profile * integral)
