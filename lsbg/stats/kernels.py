"""Compiled kernel of the circular block bootstrap (:mod:`lsbg.stats.bootstrap`).

A full-rate record has 40 000 samples and blocks of a few dozen, so one
interval sums about a million blocks per thousand replicates, and the reports
ask for a few hundred intervals. numpy gathered every block's start and end
from the prefix sums into temporaries; this loop reads them in place.
Imported only when a bootstrap runs, so that the statistics need numba only
then.
"""

import math

import numpy as np
from numba import njit


@njit(cache=True)
def circular_block_stds(sums, squares, starts, lengths, n):
    """Standard deviations (ddof = 1) of circular block-bootstrap replicates.

    Parameters
    ----------
    sums, squares : numpy.ndarray, shape (n + L + 1,)
        Prefix sums of the centred series wrapped by its first L samples, and
        of its squares (0 first) [unit, unit squared].
    starts : numpy.ndarray of int64, shape (n_boot, n_blocks)
        Start of each block of each replicate, in [0, n) [samples].
    lengths : numpy.ndarray of int64, shape (n_blocks,)
        Length of each block (the last one cut so that a replicate has n
        samples) [samples].
    n : int
        Samples per replicate [-].

    Returns
    -------
    numpy.ndarray, shape (n_boot,)
        Standard deviation of each replicate [unit of the series].
    """
    n_boot, n_blocks = starts.shape
    out = np.empty(n_boot)
    for r in range(n_boot):
        total = 0.0
        total_squares = 0.0
        for b in range(n_blocks):
            first = starts[r, b]
            last = first + lengths[b]
            total += sums[last] - sums[first]
            total_squares += squares[last] - squares[first]
        out[r] = math.sqrt(max(total_squares - total * total / n, 0.0) / (n - 1))
    return out
