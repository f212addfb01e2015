"""The line model at rest under load, point by point, over a mesh cycle.

The optimiser needs more of a loaded TCA than its transmission error: where
the load sits on the flank (its edges, its Hertz pressure, its sliding). At
each of a few mesh positions and each torque of the load range,
:func:`loaded_points` finds the line model's equilibrium exactly as
:func:`lsbg.tca.loaded.loaded_tca` does (:meth:`lsbg.contact.MeshContact.static_gear_angle`,
the same transmission error bit for bit), and lays out the contact points
of every tooth pair's line as the kernel cuts them (:func:`mesh_points`: the
bands of the face width, a band cut by the field's edge acting at the middle
of its inside part, as :func:`lsbg.tooth.contact_points.contact_points` does
one position at a time), with the separation s of the real flanks there. A
point then carries the uniform bed's load per unit length
q = k_l <l eps - s> (Simon 2007; Kolivand & Kahraman 2009: the ease-off
loads the potential contact lines).

Edges, as lsbg counts them (:attr:`lsbg.tooth.contact_points.ContactPoints.edge`,
:class:`lsbg.tooth.ltca.EdgeLoads`): a point whose band reaches an end of the
active profile (the field's psi_lo or psi_hi, where a member's tip runs or a
generated flank starts) and the outermost bands at the toe and the heel.

SI units.
"""

from __future__ import annotations

import dataclasses
import math
from collections import namedtuple
from dataclasses import dataclass

import numpy as np

from lsbg.contact import kernels as k
from lsbg.contact.bands import band_points
from lsbg.gear.flank import mesh_phase_pinion_angle
from lsbg.memo import arrays_key, cached, fields_key

__all__ = ["MeshPoints", "LoadedPoints", "SeparationCache", "mesh_points", "mesh_positions",
           "loaded_points"]


class SeparationCache:
    """Separation fields of one pair for many modifications and displacements.

    :class:`lsbg.tca.separation.SeparationField` relieves the pinion's flank
    at the points the line model asks for, which are the same for every
    modification and displacement: this keeps, per grid of points asked for,
    the conjugate flank's points and normals there
    (:func:`lsbg.tca.modification.relieved_flank` of no modification), their
    ease-off coordinates and pinion rotations, the current modification's
    relieved points on each grid (one design's displacements all ask for
    them) and each displacement's kernel constants, and removes each
    modification's relief along the normals, as ``relieved_flank`` does. The
    values are :class:`~lsbg.tca.separation.SeparationField`'s (tested to
    rounding), computed by the same operations on the same numbers whether
    kept or not (tested bit for bit).

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    """

    #: Grids of points kept (a line-model evaluation asks for three: the bands'
    #: centres and edges on the separation table's rows, and the mesh points).
    GRIDS = 8

    def __init__(self, pair):
        from lsbg.tca.modification import pinion_tip_end

        self.pair = pair
        self.tip = pinion_tip_end(pair)
        self._constants = {}
        self._grids = {}
        # the modification whose relieved points are kept, and those points per grid
        self._modification, self._relieved = None, {}

    def field(self, modification, misalignment):
        """The separation field ``field(turn, cone_distance)`` [m] of a modification
        and a displacement, with the ``attrs``, ``modification`` and
        ``misalignment`` of a :class:`~lsbg.tca.separation.SeparationField`;
        None for conjugate flanks on an aligned pair."""
        from lsbg.tca.modification import flank_attributes
        from lsbg.tca.separation import SeparationField

        modification = modification.load()
        if modification.is_zero and misalignment.is_zero:
            return None
        # the kernel constants depend on the displacement only (its exact bits)
        key = fields_key(misalignment)
        if key not in self._constants:
            self._constants[key] = SeparationField(
                self.pair, type(modification)(), misalignment)._constants
        constants = self._constants[key]
        cache = self

        def separation(turn, cone_distance):
            return cache.separation(modification, constants, turn, cone_distance)

        separation.modification, separation.misalignment = modification, misalignment
        separation.attrs = flank_attributes(modification, misalignment)
        return separation

    def separation(self, modification, constants, turn, cone_distance):
        """:meth:`lsbg.tca.separation.SeparationField.__call__` on the cached flank [m]."""
        from lsbg.tca import surface

        turn, rho = np.broadcast_arrays(np.asarray(turn, float), np.asarray(cone_distance, float))
        key = arrays_key(turn, rho)
        grid = cached(self._grids, key, lambda: self._grid(turn, rho), self.GRIDS)
        if modification != self._modification:
            self._modification, self._relieved = modification, {}
        if key not in self._relieved:
            relief = modification.relief(grid.u, grid.v, self.tip)
            points = grid.points - relief[..., None] * grid.normals
            self._relieved[key] = np.ascontiguousarray(points.reshape(-1, 3))
        gap = surface.point_separations(grid.angles, self._relieved[key], grid.flat_normals,
                                        constants)
        return gap.reshape(turn.shape)

    def _grid(self, turn, rho):
        """What a grid of points (turn, rho) gives every modification: the conjugate
        flank's points and normals, the ease-off coordinates and the pinion rotations."""
        from lsbg.tca.modification import (FlankModification, field_profile_coordinate,
                                           lengthwise_coordinate, relieved_flank)

        pair = self.pair
        plane = pair.planes["drive"]
        psi = turn + plane.curve.polar_angle(rho)
        points, normals, _ = relieved_flank(pair, FlankModification(), rho, psi)
        # tooth 0 carries the line of turn Psi at pinion rotation Psi / s1
        angles = np.ascontiguousarray((turn / pair.axis_normal_component(1, "drive")).ravel())
        return _FlankGrid(points, normals, np.ascontiguousarray(normals.reshape(-1, 3)),
                          lengthwise_coordinate(pair.design, rho),
                          field_profile_coordinate(plane, psi), angles)


#: A grid of :class:`SeparationCache`: the conjugate flank's points [m] and normals [-],
#: the normals as the kernel reads them, the ease-off coordinates u, v [-] and the
#: pinion rotations [rad].
_FlankGrid = namedtuple("_FlankGrid", "points normals flat_normals u v angles")


@dataclass(frozen=True)
class MeshPoints:
    """The line model's contact points at a set of pinion positions.

    Arrays of shape (positions, lines, bands): every tooth pair's line that
    can meet the field at each position, cut into the bands of the face
    width; ``inside`` marks the points whose band meets the field.

    Attributes
    ----------
    pinion_angle : numpy.ndarray, shape (positions,)
        Pinion rotation [rad].
    turn : numpy.ndarray, shape (positions, lines)
        Turn Psi of each line in the plane of action [rad].
    rho, psi : numpy.ndarray
        The point in the plane of action (distance from the apex [m], polar
        angle from the pitch line [rad]).
    lever, length, separation : numpy.ndarray
        Lever rho cos(beta_p) [m], length of the band's part of the line
        inside the field [m], initial separation of the real flanks [m].
    inside : numpy.ndarray of bool
    edge : numpy.ndarray of int
        -1 or +1 where the band reaches the field's end at psi_lo or psi_hi
        (an end of the active profile), 0 elsewhere [-].
    psi_from, psi_to : numpy.ndarray
        The part of the field the band's piece of line spans [rad].
    band : numpy.ndarray of int, shape (bands,)
        Band index, 0 at the toe [-].
    """

    pinion_angle: np.ndarray
    turn: np.ndarray
    rho: np.ndarray
    psi: np.ndarray
    lever: np.ndarray
    length: np.ndarray
    separation: np.ndarray
    inside: np.ndarray
    edge: np.ndarray
    psi_from: np.ndarray
    psi_to: np.ndarray
    band: np.ndarray

    @property
    def face_edge(self):
        """True for the points of the outermost bands, at the toe and the heel."""
        at_end = (self.band == 0) | (self.band == self.band.size - 1)
        return np.broadcast_to(at_end, self.rho.shape)

    def profile_edge(self, psi_lo=None, psi_hi=None):
        """True for the points whose band reaches an end of the active profile.

        Parameters
        ----------
        psi_lo, psi_hi : array_like, optional
            The active profile's ends per band [rad], inside the field (where
            the generated flanks start: :func:`lsbg.tooth.field.active_field`);
            by default the field's own ends. A band whose piece of line reaches
            or passes them is at an edge.

        Returns
        -------
        numpy.ndarray of bool
        """
        edge = self.edge != 0
        if psi_lo is not None:
            edge = edge | (self.psi_from <= np.asarray(psi_lo)) \
                | (self.psi_to >= np.asarray(psi_hi))
        return self.inside & edge

    def at_edge(self, psi_lo=None, psi_hi=None):
        """True for the points at an edge of the active flank: the toe's or the
        heel's band, or an end of the active profile (:meth:`profile_edge`)."""
        return self.profile_edge(psi_lo, psi_hi) | (self.inside & self.face_edge)


@dataclass(frozen=True)
class LoadedPoints:
    """The line model's equilibria at several torques over the same positions.

    Attributes
    ----------
    points : MeshPoints
    torque : numpy.ndarray, shape (torques,)
        Gear torques [N m].
    transmission_error : numpy.ndarray, shape (torques, positions)
        phi1 z1/z2 - phi2 [rad], as :func:`lsbg.tca.loaded.loaded_tca`.
    approach : numpy.ndarray, shape (torques, positions, lines, bands)
        l eps - s at each point [m] (> 0: the flanks are pressed together).
    line_load : numpy.ndarray, shape (torques, positions, lines, bands)
        Load per unit length of contact line q = k_l <l eps - s> [N/m].
    line_stiffness : float
        k_l [N/m^2].
    e2 : float
        sin of the gear's base cone angle [-].
    """

    points: MeshPoints
    torque: np.ndarray
    transmission_error: np.ndarray
    approach: np.ndarray
    line_load: np.ndarray
    line_stiffness: float
    e2: float

    @property
    def force(self):
        """Normal force of each point's band, q times its length [N]."""
        return self.line_load * self.points.length

    def carried_torque(self):
        """Gear torque the point loads carry at each position, e2 sum(l F) [N m],
        shape (torques, positions)."""
        return self.e2 * np.sum(self.force * self.points.lever, axis=(2, 3))


def mesh_points(contact, pinion_angles, layout=None):
    """The line model's contact points of every tooth pair at some pinion rotations.

    The bands of the face width on each line that can meet the field, cut
    by the field's edges as the line kernel cuts them
    (:func:`lsbg.contact.kernels.mesh_forces`; one position at a time:
    :func:`lsbg.tooth.contact_points.contact_points`), with the separation of
    the contact's real flanks (none: conjugate flanks).

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        A line-model contact.
    pinion_angles : array_like
        Pinion rotations phi1 [rad].
    layout : MeshPoints, optional
        This function's points at the same rotations for a contact of the
        same pair and parameters on any flanks (conjugate ones, say): the
        points do not depend on the flanks, so only the separation is
        computed (an ease-off search's contacts all share them).

    Returns
    -------
    MeshPoints
    """
    phi1 = np.atleast_1d(np.asarray(pinion_angles, dtype=float))
    if layout is None:
        layout = _mesh_layout(contact, phi1)
    elif not np.array_equal(layout.pinion_angle, phi1):
        raise ValueError("the layout's points are at other pinion rotations")
    inside, rho = layout.inside, layout.rho
    separation = np.zeros(rho.shape)
    if contact.separation is not None and np.any(inside):
        turns = np.broadcast_to(layout.turn[..., None], rho.shape)
        separation[inside] = contact.separation(turns[inside], rho[inside])
    return dataclasses.replace(layout, separation=separation)


def _mesh_layout(contact, phi1):
    """:func:`mesh_points` without the separation (zero) at pinion rotations phi1 [rad]."""
    sides, table = contact.arrays[1], contact.arrays[2]
    first, last = sides[0, k.S_FIRST], sides[0, k.S_LAST]
    psi_lo, psi_hi = sides[0, k.S_PSI_LO], sides[0, k.S_PSI_HI]
    bands = int(sides[0, k.S_ROWS])
    band = table[0, :bands]
    pitch = contact.pitch
    # the turn of tooth 0's line at the pinion's rotation, then every line after it
    mismatch_turn = contact.orientation * phi1 * contact.e1
    start = mismatch_turn + np.ceil((first - mismatch_turn) / pitch) * pitch
    lines = math.floor((last - first) / pitch) + 2
    turn = start[:, None] + pitch * np.arange(lines)[None, :]
    at = band_points(band, turn, psi_lo, psi_hi, last)
    inside, rho = at.inside, at.rho
    return MeshPoints(phi1, turn, rho, at.psi, at.lever, at.length, np.zeros(rho.shape), inside,
                      at.edge.astype(np.int8), np.where(inside, at.bottom, np.nan),
                      np.where(inside, at.top, np.nan), np.arange(bands))


def mesh_positions(pair, phases):
    """The pinion rotations of :func:`loaded_points` over one base pitch [rad].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    phases : int
        Mesh positions over one base pitch [-].
    """
    return mesh_phase_pinion_angle(pair, np.arange(int(phases)) / int(phases))


def loaded_points(contact, torques, phases, layout=None):
    """The line model's equilibria at each torque over one mesh cycle, point by point.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        A line-model contact on the uniform bed (its separation field for
        real flanks).
    torques : array_like
        Gear torques [N m], >= 0 (0: first touch).
    phases : int
        Mesh positions over one base pitch [-], at least 4; the positions of
        :func:`lsbg.tca.loaded.loaded_tca` with as many phases.
    layout : MeshPoints, optional
        :func:`mesh_points` of a contact of the same pair and parameters at
        these positions (:func:`mesh_positions`), on any flanks: the points
        are taken from it, the separation computed.

    Returns
    -------
    LoadedPoints

    Raises
    ------
    ValueError
        For a point-model contact, the tooth's own compliance (the loads
        here are the uniform bed's), a negative torque, fewer than 4 phases,
        a layout at other positions, or a torque the contact cannot carry.
    """
    if contact.params.model != "line" or contact.slice_stiffness is not None:
        raise ValueError("loaded points are defined for the line model on the uniform bed")
    torques = np.atleast_1d(np.asarray(torques, dtype=float))
    if not np.all(np.isfinite(torques)) or np.any(torques < 0):
        raise ValueError(f"torques = {torques.tolist()!r}: must be numbers >= 0 [N m]")
    if isinstance(phases, bool) or int(phases) != phases or phases < 4:
        raise ValueError(f"phases = {phases!r}: must be a whole number >= 4")
    z1, z2 = contact.pair.design.teeth
    pinion = mesh_positions(contact.pair, phases)
    points = mesh_points(contact, pinion, layout)
    te = np.zeros((torques.size, pinion.size))
    eps = np.zeros((torques.size, pinion.size))
    for i, torque in enumerate(torques):
        for n, phi1 in enumerate(pinion):
            phi2 = contact.static_gear_angle(float(torque), float(phi1))
            te[i, n] = phi1 * z1 / z2 - phi2
            eps[i, n] = contact.mismatch(phi1, phi2)
    approach = points.lever * eps[:, :, None, None] - points.separation
    approach = np.where(points.inside, approach, -np.inf)
    stiffness = contact.params.line_stiffness
    line_load = stiffness * np.maximum(approach, 0.0)
    return LoadedPoints(points, torques, te, approach, line_load, stiffness, contact.e2)

