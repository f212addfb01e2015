"""The matched designs of two traces' converged fronts, and each design's answers.

:func:`matched_designs` pairs the LSBG's converged front members with the SBG's
(:func:`lsbg.matched.pairs.match_members` on :data:`~lsbg.matched.pairs.MATCH_OBJECTIVES`,
normalised by the common box of ``lsbg trace-fronts``); the members pooled over
each trace's seeds, equal designs once. :func:`design_answers` gives one
design's stability (the proxy at both boundaries, the full runs where asked)
and its FE figures; :func:`ratio_statistics` the paired statistics of the log
std ratios over the pairs.

SI inside; the objectives in :data:`lsbg.optimise.objectives.QUANTITIES`' units.
"""

from __future__ import annotations

import math

import numpy as np

from lsbg.matched.pairs import MATCH_OBJECTIVES, match_members, normalised, paired_statistics, \
    unique_rows
from lsbg.matched.stability import BOUNDARIES, STABILITY_QUANTITIES, full_run_stds, proxy_stds

__all__ = ["ESTIMATES", "kept_members", "box_of", "matched_designs", "design_answers",
           "log_ratios", "ratio_statistics"]

#: How a std was obtained: the proxy (every pair) or the full run (a subset).
ESTIMATES = ("proxy", "full")


def kept_members(converged):
    """The members of a :func:`lsbg.optimise.fronts.converged_front_dataset` on their
    seed's converged front, equal designs once: indices into ``member``."""
    names = converged.attrs["objectives"].split()
    kept = np.flatnonzero(converged["kept"].values == 1)
    if not kept.size:
        return kept
    table = np.column_stack([converged[n].values[kept] for n in names])
    return kept[unique_rows(table)]


def box_of(trace_fronts, names=MATCH_OBJECTIVES):
    """The common box's corners (``lsbg trace-fronts``' ``box_low_*``, ``box_high_*``) of
    ``names``: ``low, high`` arrays in the objectives' units."""
    low = np.array([float(trace_fronts[f"box_low_{n}"]) for n in names])
    high = np.array([float(trace_fronts[f"box_high_{n}"]) for n in names])
    return low, high


def matched_designs(converged, box, caliper, limit=None):
    """The matched pairs of two traces' converged fronts.

    Parameters
    ----------
    converged : tuple of xarray.Dataset
        The LSBG's and the SBG's :func:`lsbg.optimise.fronts.converged_front_dataset`.
    box : tuple of numpy.ndarray
        :func:`box_of`.
    caliper : float
        The largest normalised distance of a pair [-].
    limit : int, optional
        At most this many pairs, the closest.

    Returns
    -------
    dict
        ``member`` (pairs, 2): each pair's members (indices into ``member`` of each
        trace's dataset); ``distance`` (pairs,) [-]; ``candidates`` (2,): each
        trace's kept designs; ``assigned``, ``dropped`` (by the caliper).
    """
    members = [kept_members(d) for d in converged]
    values = [normalised(np.column_stack([d[n].values[m] for n in MATCH_OBJECTIVES])
                         if m.size else np.zeros((0, len(MATCH_OBJECTIVES))), *box)
              for d, m in zip(converged, members)]
    match = match_members(values[0], values[1], caliper, limit)
    member = np.column_stack([members[0][match["a"]], members[1][match["b"]]]).astype(int) \
        if match["a"].size else np.zeros((0, 2), int)
    return {"member": member, "distance": match["distance"],
            "candidates": np.array([m.size for m in members]),
            "assigned": match["assigned"], "dropped": match["dropped"]}


def design_answers(model_at, simulations, start, full, load_torque, pinion_speed,
                   fe=None):
    """One design's stds at both boundaries, and its FE figures.

    Parameters
    ----------
    model_at : callable
        ``model_at(boundary) -> lsbg.dynamics.MeshingModel`` of the design.
    simulations : dict
        ``{boundary: lsbg.dynamics.SimulationSettings}`` of the full runs.
    start : float
        Start of the steady state [s].
    full : bool
        Whether the full runs are run too.
    load_torque : float
        The gear's load [N m].
    pinion_speed : float
        W [rad/s].
    fe : callable, optional
        ``fe() -> {name: value}``: the design's FE figures.

    Returns
    -------
    dict
        ``std`` (estimate, boundary, quantity) [deg/s, N] (NaN: the full run not run),
        ``fe`` ({name: value} or {}).
    """
    std = np.full((len(ESTIMATES), len(BOUNDARIES), len(STABILITY_QUANTITIES)), math.nan)
    for b, boundary in enumerate(BOUNDARIES):
        model = model_at(boundary)
        proxy = proxy_stds(model, boundary, load_torque, pinion_speed)
        std[0, b] = [proxy[q] for q in STABILITY_QUANTITIES]
        if full:
            run = full_run_stds(model, simulations[boundary], start)
            std[1, b] = [run[q] for q in STABILITY_QUANTITIES]
    return {"std": std, "fe": fe() if fe is not None else {}}


def log_ratios(std):
    """log std(SBG) / std(LSBG) per pair [-] (> 0: the LSBG calmer).

    Parameters
    ----------
    std : numpy.ndarray
        (pairs, 2 traces: the LSBG's first, ...).

    Returns
    -------
    numpy.ndarray
        (pairs, ...).
    """
    std = np.asarray(std, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.log(std[:, 1] / std[:, 0])


def ratio_statistics(ratios, seed=0):
    """:func:`lsbg.matched.pairs.paired_statistics` of each column of ``ratios``.

    Parameters
    ----------
    ratios : numpy.ndarray
        (pairs, estimate, boundary, quantity) log ratios [-].
    seed : int
        The bootstrap's seed.

    Returns
    -------
    dict
        ``{statistic: array (estimate, boundary, quantity)}``.
    """
    shape = ratios.shape[1:]
    out = {}
    for index in np.ndindex(*shape):
        stats = paired_statistics(ratios[(slice(None), *index)], seed=seed)
        for name, value in stats.items():
            out.setdefault(name, np.full(shape, math.nan))[index] = value
    return out
