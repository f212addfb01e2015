"""The line model's slice stiffness from the loaded TCA with the tooth's compliance.

At each mesh position the complementarity LTCA (:mod:`lsbg.tooth.ltca`)
finds, at every contact point (a band of the face width on one tooth pair's
contact line), the load per unit length q and the approach x of the flanks
there (the mismatch's lever times the rotation, less the initial separation
of real flanks): the bulk deflection of the three teeth in mesh of both members under
all the loads, plus the local Hertz compression. Their ratio k = q / x is the
stiffness per unit length that a slice of the line model must have to carry
the same load at the same approach: the effective (secant) stiffness of the
tooth there, coupling to its neighbours included. On the line model's slices
(:class:`lsbg.contact.slices.SliceStiffness`) it reproduces the LTCA's
equilibrium, and a dynamic run sees the tooth's stiffness vary across the face
and over the mesh cycle.

Each slice is held on the turn Psi of its contact line, which the LTCA steps
evenly (``phases`` positions per base pitch), so the slices of all positions
and tooth pairs fall on one even grid of line turns, and the line model at
those turns carries exactly the LTCA's loads. Where a band carries no load at
a turn because the flanks are apart there (outside the loaded pattern, lifted
off by the crowning), the table takes the band's stiffness at the nearest
loaded turn: a slice that touches there in a run starts with the stiffness of
its neighbourhood. Where the LTCA has no flank (beyond the generated pinion
flank's start, :mod:`lsbg.tooth.field`), the slice gets next to none.

SI inside.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["slice_stiffness_grid", "ABSENT"]

#: Stiffness of a slice that must carry nothing (no generated flank there), as a
#: fraction of the loaded slices' median [-]: positive, so the table is one.
ABSENT = 1e-9


def slice_stiffness_grid(line_turn, band, force, approach, length, present, pitch, phases,
                         bands):
    """Effective stiffness of each band of the line model on an even grid of line turns.

    Parameters
    ----------
    line_turn : numpy.ndarray, shape (n,)
        Turn Psi of each slice's contact line [rad].
    band : numpy.ndarray of int, shape (n,)
        Band of the face width of each slice [-].
    force : numpy.ndarray, shape (n,)
        The LTCA's load on the slice [N], >= 0 (0 where it has no point).
    approach : numpy.ndarray, shape (n,)
        The line model's approach of the slice, lever eps - s [m].
    length : numpy.ndarray, shape (n,)
        The line model's length of the slice (the band's part inside its field) [m].
    present : numpy.ndarray of bool, shape (n,)
        Whether the LTCA has the point (False beyond the generated flanks).
    pitch : float
        Base pitch of the contact lines Psi_p [rad].
    phases : int
        LTCA positions per base pitch [-]: the grid's step is pitch / phases.
    bands : int
        Bands across the face width [-].

    Returns
    -------
    turns : numpy.ndarray, shape (rows,)
        The grid of line turns [rad], increasing.
    stiffness : numpy.ndarray, shape (rows, bands)
        Stiffness per unit length [N/m^2]: force / (length approach) where the
        slice carries load; where the LTCA has no flank (beyond the generated
        flanks) or keeps a slice unloaded that the line model would press
        (the neighbours' deflection opened it), :data:`ABSENT` of the
        loaded median, so that the line model carries nothing there either;
        elsewhere (flanks apart) the band's value at the nearest loaded turn.

    Raises
    ------
    ValueError
        If the slices are not on an even grid of turns, or none is loaded.
    """
    line_turn = np.asarray(line_turn, float)
    band = np.asarray(band, int)
    force, approach = np.asarray(force, float), np.asarray(approach, float)
    length, present = np.asarray(length, float), np.asarray(present, bool)
    step = pitch / int(phases)
    base = float(line_turn.min())
    row = np.rint((line_turn - base) / step).astype(int)
    if np.max(np.abs(line_turn - (base + row * step))) > 1e-6 * step:
        raise ValueError("the contact points' line turns are not on an even grid")
    rows = int(row.max()) + 1
    loaded = present & (force > 0.0) & (approach > 0.0) & (length > 0.0)
    if not np.any(loaded):
        raise ValueError("no contact point carries load: no slice stiffness")
    stiffness = np.full((rows, int(bands)), math.nan)
    stiffness[row[loaded], band[loaded]] = force[loaded] / (length[loaded] * approach[loaded])
    tiny = ABSENT * float(np.nanmedian(stiffness))
    # no flank there, or the neighbours' deflection keeps it from touching
    stiffness[row[~loaded & (~present | (approach > 0.0))],
              band[~loaded & (~present | (approach > 0.0))]] = tiny
    turns = base + step * np.arange(rows)
    everything = np.arange(rows)
    for j in range(int(bands)):
        column = stiffness[:, j]
        known = np.flatnonzero(np.isfinite(column) & (column != tiny))
        if known.size == 0:
            column[~np.isfinite(column)] = tiny  # a band the load never reaches
            continue
        # apart flanks: the nearest loaded turn of the same band
        after = np.clip(np.searchsorted(known, everything), 0, known.size - 1)
        before = np.clip(after - 1, 0, known.size - 1)
        pick = np.where(np.abs(known[before] - everything) <= np.abs(known[after] - everything),
                        known[before], known[after])
        missing = ~np.isfinite(column)
        column[missing] = column[pick[missing]]
    return turns, stiffness
