"""The line model's stiffness per slice from the tooth's own compliance.

The uniform bed gives every slice of every contact line the same stiffness per
unit length k_l. :class:`SliceStiffness` replaces it, on the drive side, by a
stiffness k_j(Psi) per band j of the face width and per turn Psi of the contact
line in the plane of action: the effective (secant) stiffness that the loaded
TCA with the tooth's finite-element compliance finds at each slice
(:func:`lsbg.tooth.slices.slice_stiffness`). The line model then carries, at
rest, the loads of that LTCA, and a run sees the tooth's stiffness vary along
the face and over the mesh cycle.

The table is held on the line turn, not on the mesh phase, because a slice's
stiffness belongs to where its line is in the field (near the toe, the tip or
the root), whichever tooth pair it is.

SI inside.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["SliceStiffness", "stiffness_columns"]

#: Samples per band of the mean over a band's passage through the field [-].
MEAN_SAMPLES = 256


@dataclass(frozen=True)
class SliceStiffness:
    """Stiffness per unit length of each slice of the drive side's contact lines.

    Parameters
    ----------
    line_turn : numpy.ndarray, shape (rows,)
        Turns Psi of the contact line in the plane of action, evenly spaced,
        increasing [rad].
    cone_distance : numpy.ndarray, shape (bands,)
        Centres of the bands across the face width, increasing [m].
    stiffness : numpy.ndarray, shape (rows, bands)
        Stiffness per unit length of the band's slice [N/m^2] (N/m per m of
        line), finite and > 0.
    attrs : dict
        Provenance (the compliance's inputs hash, the load), copied into the
        attributes of every run that uses the table.
    """

    line_turn: np.ndarray
    cone_distance: np.ndarray
    stiffness: np.ndarray
    attrs: dict = field(default_factory=dict)

    def __post_init__(self):
        turn = np.asarray(self.line_turn, float)
        rho = np.asarray(self.cone_distance, float)
        k = np.asarray(self.stiffness, float)
        if turn.ndim != 1 or turn.size < 2 or not np.all(np.diff(turn) > 0):
            raise ValueError("slice stiffness: line_turn must be increasing, at least 2 rows")
        step = np.diff(turn)
        if not np.allclose(step, step[0], rtol=1e-6, atol=0.0):
            raise ValueError("slice stiffness: line_turn must be evenly spaced")
        if rho.ndim != 1 or rho.size < 1 or not np.all(np.diff(rho) > 0):
            raise ValueError("slice stiffness: cone_distance must be increasing")
        if k.shape != (turn.size, rho.size):
            raise ValueError(f"slice stiffness: stiffness has shape {k.shape}, expected "
                             f"({turn.size}, {rho.size}) (line_turn, cone_distance)")
        if not (np.all(np.isfinite(k)) and np.all(k > 0)):
            raise ValueError("slice stiffness: every stiffness must be finite and > 0")
        object.__setattr__(self, "line_turn", turn)
        object.__setattr__(self, "cone_distance", rho)
        object.__setattr__(self, "stiffness", k)

    @classmethod
    def from_dataset(cls, dataset):
        """The table of an LTCA dataset with the tooth's compliance.

        Parameters
        ----------
        dataset : xarray.Dataset
            With ``slice_stiffness`` (line_turn [rad], cone_distance [mm])
            [N/(mm um)] (:func:`lsbg.tooth.ltca.fe_loaded_tca`).
        """
        if "slice_stiffness" not in dataset:
            raise ValueError("the dataset has no slice_stiffness: not an LTCA with the "
                             "tooth's compliance (lsbg ltca under contact.compliance: fe)")
        k = dataset["slice_stiffness"].transpose("line_turn", "cone_distance")
        attrs = {"compliance": "fe",
                 "compliance_inputs_hash": str(dataset.attrs.get("compliance_inputs_hash", "")),
                 "compliance_load_torque_N_m": float(dataset.attrs.get("load_torque_N_m", math.nan))}
        return cls(dataset["line_turn"].values, dataset["cone_distance"].values * 1e-3,
                   k.values * 1e9, attrs)

    def factors(self, band_rho, line_stiffness):
        """The table at the given bands over the uniform bed's stiffness.

        Parameters
        ----------
        band_rho : numpy.ndarray, shape (bands,)
            Centres of the line model's bands [m] (interpolated linearly in
            the cone distance, held beyond the table's ends).
        line_stiffness : float
            The uniform bed's k_l [N/m^2].

        Returns
        -------
        numpy.ndarray, shape (rows, bands)
        """
        band_rho = np.asarray(band_rho, float)
        rows = np.array([np.interp(band_rho, self.cone_distance, row) for row in self.stiffness])
        return rows / float(line_stiffness)


def stiffness_columns(slice_stiffness, band_rho, line_stiffness, band_theta, psi_range):
    """Kernel columns of a slice-stiffness table and the mean factor of each band.

    Parameters
    ----------
    slice_stiffness : SliceStiffness
    band_rho : numpy.ndarray, shape (bands,)
        Band centres [m].
    line_stiffness : float
        The uniform bed's k_l [N/m^2].
    band_theta : numpy.ndarray, shape (bands,)
        Polar angle of each band's centre on the contact line [rad].
    psi_range : tuple of float
        (psi_lo, psi_hi), the field of contact's polar range [rad].

    Returns
    -------
    columns : numpy.ndarray, shape (bands, rows)
        Factor k_j(Psi) / k_l per band and row.
    first, inv_step : float
        First row's line turn [rad] and rows per radian [1/rad].
    mean : numpy.ndarray, shape (bands,)
        Each band's factor averaged over its passage through the field (the
        turns Psi with Psi + theta_j in [psi_lo, psi_hi]) [-].
    """
    factors = slice_stiffness.factors(band_rho, line_stiffness)
    turn = slice_stiffness.line_turn
    psi_lo, psi_hi = psi_range
    mean = np.empty(factors.shape[1])
    for j, theta in enumerate(band_theta):
        through = np.linspace(psi_lo - theta, psi_hi - theta, MEAN_SAMPLES)
        mean[j] = np.interp(through, turn, factors[:, j]).mean()
    return factors.T.copy(), float(turn[0]), float(1.0 / (turn[1] - turn[0])), mean
