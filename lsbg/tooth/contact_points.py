"""The FE LTCA's contact points at one mesh position, and their compliance.

The loaded TCA with the tooth's own compliance (:mod:`lsbg.tooth.ltca`)
solves, at each mesh position, for the loads of a set of points. They are the
line model's (:class:`lsbg.contact.MeshContact`): the bands of the face width
on every tooth pair whose contact line meets the field of contact, each at
the middle of its part inside the field (:func:`contact_points`), with its
lever, its length and the initial separation of real flanks there
(:class:`ContactPoints`).

Their compliance comes from the design point's FE dataset
(:func:`lsbg.tooth.compliance.tooth_compliance`): its influence coefficients
interpolated bilinearly from the flank grid to the points, coupled between
neighbouring teeth and symmetrised, with the flanks' exact relative
curvature and half thicknesses at the points for the local Hertz term
(:class:`FECompliance`).

SI units.
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.contact import kernels as k
from lsbg.contact.bands import band_points

__all__ = ["ContactPoints", "contact_points", "FECompliance"]

#: Points of the exact relative curvature across the field [-].
CURVATURE_POINTS = 121


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
    band : numpy.ndarray of int or None
        Band of the line model's face width of each point [-].
    turn : numpy.ndarray or None
        Turn Psi of each point's contact line [rad]; the lines of one tooth
        pair at two mesh positions differ by the change of the mismatch turn.
    edge : numpy.ndarray of int or None
        -1 or +1 where the point's band reaches the end of the field at
        psi_lo or psi_hi (its contact line ends on a member's tip or on the
        start of a generated flank inside the band: the load there is an edge
        contact's, not Hertz's between two flanks), 0 inside [-].
    psi_from, psi_to : numpy.ndarray or None
        The part of the field the band's line segment spans [rad].
    """

    def __init__(self, pair, rho, psi, lever, length, separation, band=None, turn=None,
                 edge=None, psi_from=None, psi_to=None):
        self.pair, self.rho, self.psi = pair, rho, psi
        self.lever, self.length, self.separation = lever, length, separation
        self.band, self.turn = band, turn
        self.edge, self.psi_from, self.psi_to = edge, psi_from, psi_to


def contact_points(contact, mismatch_turn, field=None, separations=None):
    """Contact points of the line model at a line turn of tooth pair 0.

    Parameters
    ----------
    contact : lsbg.contact.MeshContact
        Line model (its bands and, for real flanks, its separation field).
    mismatch_turn : float
        Turn Psi of the contact line of tooth 0 in the plane of action [rad].
    field : (array_like, array_like), optional
        Polar angles (psi_lo, psi_hi) bounding the field across the profile
        [rad], scalars or one per band (:func:`active_field`), within the line
        model's; by default the line model's.
    separations : dict, optional
        The separation of each contact line's bands [m] by the line's turn
        and the bands' cone distances, filled in here and read by the next
        call at the same position: the line model's points and the field's
        share most lines (all but those a field's end cuts into a band of).

    Returns
    -------
    ContactPoints
    """
    sides, table = contact.arrays[1], contact.arrays[2]
    first, last = sides[0, k.S_FIRST], sides[0, k.S_LAST]
    psi_lo, psi_hi = sides[0, k.S_PSI_LO], sides[0, k.S_PSI_HI]
    if field is not None:
        psi_lo, psi_hi = np.maximum(psi_lo, field[0]), np.minimum(psi_hi, field[1])
    bands = int(sides[0, k.S_ROWS])
    band = table[0, :bands]
    pitch = contact.pitch
    turn = mismatch_turn + math.ceil((first - mismatch_turn) / pitch) * pitch
    rows = []
    n = 0
    while turn <= last:
        # as the line model's kernel does; an end of the field inside a band is an
        # edge (the line's end)
        at = band_points(band, turn, psi_lo, psi_hi)
        inside, rho = at.inside, at.rho
        if np.any(inside):
            s = _separation(contact, turn, rho, {} if separations is None else separations)
            rows.append(tuple(np.asarray(v)[inside] for v in (
                np.full(rho.size, n), rho, at.psi, at.lever, at.length, s,
                np.arange(rho.size), np.full(rho.size, turn), at.edge,
                np.broadcast_to(at.bottom, rho.shape), np.broadcast_to(at.top, rho.shape))))
        turn += pitch
        n += 1
    if not rows:
        raise ValueError("no contact line meets the field of contact")
    return ContactPoints(*(np.concatenate(c) for c in zip(*rows)))


def _separation(contact, turn, rho, known):
    """The separation of real flanks [m] on the line of turn ``turn`` [rad] at the
    cone distances ``rho`` [m], from ``known`` (see :func:`contact_points`)
    when it holds the same line and distances."""
    if contact.separation is None:
        return np.zeros(rho.size)
    # the values alone: the field's rows and the line model's are laid out otherwise,
    # so lsbg.memo.arrays_key would never meet (1048 of 2096 calls are met here); the
    # separation read back is the one computed afresh, bit for bit (checked on the
    # study's FE loaded TCAs)
    key = (turn, rho.tobytes())
    if key not in known:
        known[key] = np.asarray(contact.separation(np.full(rho.size, turn), rho), float)
    return known[key]


class FECompliance:
    """Compliance of the contact points of a design point, from its FE dataset.

    Parameters
    ----------
    dataset : xarray.Dataset
        :func:`lsbg.tooth.compliance.tooth_compliance`.
    pair : lsbg.gear.geometry.GearPair
    orientation : {-1, 1}
        :attr:`lsbg.contact.MeshContact.orientation`.
    band_rho : numpy.ndarray
        Cone distances of the line model's bands [m].
    field : (array_like, array_like), optional
        The field across the profile the contact points lie in (psi_lo,
        psi_hi) [rad], scalars or per band; by default lsbg's.
    """

    def __init__(self, dataset, pair, orientation, band_rho, field=None):
        from lsbg.tooth.local import relative_curvature

        self.dataset, self.pair = dataset, pair
        # a line one base pitch further on is carried by the teeth one pitch
        # away in the sense of MeshContact.orientation (tested)
        self.orientation = int(orientation)
        self.young = float(dataset.attrs["material_young_modulus"])
        self.poisson = float(dataset.attrs["material_poisson_ratio"])
        f, p = dataset.sizes["face"], dataset.sizes["profile"]
        # in the layout a file gives (C order), whatever made the dataset: the matrix
        # products' last bits depend on it (a compliance computed in this process
        # holds its fillet stress as a strided view)
        self.blocks = {name: np.ascontiguousarray(dataset[f"compliance_{name}"].values).reshape(
            3, f * p, f * p) for name in ("pinion", "gear")}
        # the relative curvature, exact on a fine grid of the whole field at the
        # line model's band centres (it grows without bound towards a base cone,
        # where the pinion's field of contact can end: no coarse grid follows it)
        psi_lo, psi_hi = pair.planes["drive"].field[:2]
        if field is not None:
            psi_lo, psi_hi = float(np.min(field[0])), float(np.max(field[1]))
        # an edge on a base cone's tangency line (lsbg's field where a mate's
        # tip overshoots it) is where the involute's radius of curvature is
        # zero: the table stops short of it by an inset, and points beyond
        # take the curvature there; a form limit (active_field) is no such edge
        inset = 0.005 * (psi_hi - psi_lo)
        tangency = np.array(list(pair.planes["drive"].tangency_angle.values()))
        self.curvature_psi = np.linspace(
            psi_lo + (inset if np.any(np.abs(tangency - psi_lo) < inset) else 0.0),
            psi_hi - (inset if np.any(np.abs(tangency - psi_hi) < inset) else 0.0),
            CURVATURE_POINTS)
        self.curvature_rho = np.asarray(band_rho, float)
        rho, psi = np.meshgrid(self.curvature_rho, self.curvature_psi, indexing="ij")
        self.radius = (1.0 / relative_curvature(pair, rho.ravel(), psi.ravel())).reshape(rho.shape)
        self.depth = {name: dataset[f"half_thickness_{name}"].values.ravel()
                      for name in ("pinion", "gear")}
        self.stress = {name: np.ascontiguousarray(dataset[f"fillet_stress_{name}"].values)
                       .reshape(-1, 3, 3, f * p) for name in ("pinion", "gear")}
        self._bounds = {}  # per member, _principal_bounds

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

    def _principal_bounds(self, name):
        """Bounds of the principal stresses of each fillet point under a unit load at
        each grid node, and the largest tensor's norm, computed once per member.

        A stress tensor's principal stresses lie within m -+ sqrt(2 J/3)
        (:func:`lsbg.tooth.elasticity.mean_and_deviator`).

        Returns
        -------
        upper, lower : numpy.ndarray, shape (q, f * p)
            Bounds of the largest and the smallest principal stress [Pa/N].
        scale : float
            The largest Frobenius norm of a fillet point's tensor [Pa/N].
        """
        from lsbg.tooth.elasticity import mean_and_deviator

        if name not in self._bounds:
            stress = self.stress[name]
            mean, j2 = mean_and_deviator(*(stress[:, i, j] for i, j in
                                           ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))))
            radius = np.sqrt(2 * j2 / 3)
            scale = float(np.sqrt(3 * mean**2 + j2).max())
            self._bounds[name] = mean + radius, mean - radius, scale
        return self._bounds[name]

    def _largest_tension(self, name, on_grid):
        """The largest principal stress over a member's fillet points under each row
        of loads on the flank grid [Pa], where it is > 0 (a value <= 0 otherwise).

        ``largest_principal_over_points`` of every fillet point's stress to the
        last bit, with the principal stresses of only the points that can hold
        a row's positive maximum (a few per row in a loaded tooth's fillets).
        The stress is linear in the loads, S = sum_k w_k A_k, and the largest
        principal stress is convex and positively homogeneous: lambda_1(S) <=
        sum_k w_k lambda_1(A_k) for w_k >= 0, w_k lambda_3(A_k) for w_k < 0,
        each bounded by :meth:`_principal_bounds`. The exact maxima of the
        points with the largest bound of each row (a lower bound of the row's
        maximum) leave out every point whose bound is below it, less 1e-9 of
        the loads' sum times the largest tensor (the products' rounding is
        ~1e-14 of it). Each point's stress is the same product as for all
        points (one matrix product per point and tensor row,
        :func:`numpy.matmul`'s loop), so its tensor, and its principal
        stresses, are the same to the last bit.

        Parameters
        ----------
        name : {"pinion", "gear"}
        on_grid : numpy.ndarray, shape (lines, f * p)
            Loads of each row on the flank grid [N].

        Returns
        -------
        numpy.ndarray, shape (lines,)
        """
        from lsbg.tooth.elasticity import largest_principal, largest_principal_over_points

        upper_node, lower_node, scale = self._principal_bounds(name)
        bound = upper_node @ np.maximum(on_grid, 0.0).T  # (q, lines) [Pa]
        if (on_grid < 0).any():  # extrapolated weights
            bound += lower_node @ np.minimum(on_grid, 0.0).T
        slack = 1e-9 * scale * np.abs(on_grid).sum(axis=1)

        def stress(points):  # (points, 3, 3, lines) [Pa]
            return self.stress[name][points] @ on_grid.T

        seeds = np.unique(np.argmax(bound, axis=0))
        out = largest_principal_over_points(np.moveaxis(stress(seeds), -1, 0))
        # a row whose maximum is <= 0 adds nothing to the root stress (0 where
        # no point is in tension): only points that may be in tension are taken
        point, row = np.nonzero(bound > np.maximum(out, 0.0) - slack)
        points, which = np.unique(point, return_inverse=True)
        np.maximum.at(out, row, largest_principal(stress(points)[which, :, :, row]))
        return out

    def root_stresses(self, grid_loads, phases):
        """Largest tensile principal stress in both members' fillets at each position.

        Parameters
        ----------
        grid_loads : list of (numpy.ndarray, numpy.ndarray)
            Per position: its index once per tooth pair [-] and the pairs' loads
            on the flank grid, shape (pairs, f * p) [N]
            (:meth:`lsbg.tooth.ltca.Position.pair_loads`).
        phases : int
            Positions [-].

        Returns
        -------
        dict
            ``pinion``, ``gear``: shape (phases,) [Pa], 0 where no fillet point
            is in tension.
        """
        from lsbg.tooth.cholesky import single_threaded_blas

        # every tooth pair's loads at every position in one product per member
        position = np.concatenate([g[0] for g in grid_loads])
        on_grid = np.concatenate([g[1] for g in grid_loads])  # (lines, f * p)
        root = {}
        # OpenBLAS's threads split a product's rows and columns, not its sums (the
        # same bits); with the other core busy they wait for each other: 3-5 times
        # slower here
        with single_threaded_blas():
            for name in ("pinion", "gear"):
                root[name] = np.zeros(phases)
                np.maximum.at(root[name], position, self._largest_tension(name, on_grid))
        return root
