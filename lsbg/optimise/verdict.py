"""A front's candidates under the verdict's models: converged positions and the FE loaded TCA.

The search scores designs with its quick loaded TCA (the uniform bed at
``optimise.phases`` positions, 24 by default). Picking the least of values
sampled at a few positions favours the designs whose sampling missed their
peak, and the claims are judged with the FE loaded TCA, not the uniform
bed. Before anything is chosen or released the candidates are evaluated
again here:

* :func:`converged`: at positions doubled from the search's until a
  stated criterion holds: every quantity compared (for the uniform bed
  :data:`CONVERGED_QUANTITIES`) of every design changes by less than
  ``tolerance`` (relative) when the positions double; the values at the
  positions so shown converged are kept. Where the largest resolution is
  reached first the run says so (``converged`` false).
* :func:`fe_state_figures`: the FE loaded TCA (:func:`lsbg.tooth.load_range.fe_load_range`,
  the compliance computed once per geometry and reused for every ease-off)
  over the load range, aligned or at every corner of the envelope, each group
  at its own converged positions (the aligned pair's transmission error
  converges slowest, the corners' pressure and root stress fastest);
  :func:`fe_combined` gives :data:`FE_QUANTITIES` of both.

SI inside; the quantities in the units of :data:`FE_QUANTITIES` and
:data:`lsbg.optimise.objectives.QUANTITIES`.
"""

from __future__ import annotations

import dataclasses

import numpy as np

__all__ = ["CONVERGED_QUANTITIES", "FE_QUANTITIES", "STATE_FIGURES", "Resolution", "converged",
           "evaluator_factory", "uniform_bed_values", "fe_state_figures", "fe_group_values", "fe_combined"]

#: The uniform-bed quantities whose convergence with the positions is required (the ones
#: the positions change: the loaded TCA's; the unloaded TCA's have their own grid).
CONVERGED_QUANTITIES = ("transmission_error", "rated_transmission_error",
                        "envelope_transmission_error", "contact_pressure", "mesh_loss")

#: The FE loaded TCA's figures of a design: name -> (unit, long name). The names shared
#: with :data:`lsbg.optimise.objectives.QUANTITIES` are defined as there.
FE_QUANTITIES = {
    "transmission_error": ("urad", "largest loaded transmission error peak to peak over the "
                                   "load range, aligned (FE)"),
    "rated_transmission_error": ("urad", "loaded transmission error peak to peak at the "
                                         "rated torque, aligned (FE)"),
    "envelope_transmission_error": ("urad", "largest loaded transmission error peak to peak "
                                            "at the rated torque over the envelope (FE)"),
    "contact_pressure": ("MPa", "largest Hertz pressure off the edges at the rated torque, "
                                "aligned (FE)"),
    "peak_contact_pressure": ("MPa", "largest Hertz pressure, edges included, over the load "
                                     "range, aligned and at the envelope's corners (FE)"),
    "root_stress": ("MPa", "largest root stress of pinion and gear over the load range, "
                           "aligned and at the envelope's corners (FE)"),
    "root_stress_pinion": ("MPa", "largest root stress of the pinion, as root_stress (FE)"),
    "root_stress_gear": ("MPa", "largest root stress of the gear, as root_stress (FE)"),
}


@dataclasses.dataclass(frozen=True)
class Resolution:
    """Where the positions' doubling stopped.

    Attributes
    ----------
    positions : int
        The positions of the values kept: the least whose doubling changes no value by
        ``tolerance`` or more (the largest where none does) [-].
    changes : tuple of float
        The largest relative change over the quantities and the designs at each
        doubling, ``changes[i]`` from ``start * 2**i`` to ``start * 2**(i+1)`` [-].
    converged : bool
        Whether the last change is below the tolerance (else the largest
        resolution was reached first).
    tolerance : float
        The criterion [-].
    """

    positions: int
    changes: tuple
    converged: bool
    tolerance: float

    def attributes(self, prefix):
        """The resolution as dataset attributes named ``prefix_*``."""
        return {f"{prefix}_positions": self.positions,
                f"{prefix}_converged": int(self.converged),
                f"{prefix}_tolerance": self.tolerance,
                f"{prefix}_changes": " ".join(f"{c:.4g}" for c in self.changes)}


def _largest_change(coarse, fine):
    """The largest relative change from ``coarse`` to ``fine`` over their arrays [-]."""
    change = 0.0
    for name, value in fine.items():
        a, b = np.asarray(coarse[name], float), np.asarray(value, float)
        scale = np.maximum(np.abs(b), 1e-12)
        finite = np.isfinite(a) & np.isfinite(b)
        if np.any(finite):
            change = max(change, float(np.max(np.abs(b - a)[finite] / scale[finite])))
    return change


def converged(evaluate, start, tolerance, largest, compared=None):
    """Values at positions doubled from ``start`` until they change by less than ``tolerance``.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(positions) -> {name: array}``, the quantities of every design
        at that many positions.
    start : int
        The first positions (the search's) [-], >= 8.
    tolerance : float
        The largest relative change allowed when the positions double [-], > 0.
    largest : int
        The most positions evaluated [-], >= 2 ``start``.
    compared : sequence of str, optional
        The quantities the criterion reads (default: every one).

    Returns
    -------
    values : dict
        ``evaluate``'s answer at :attr:`Resolution.positions`: the least positions
        whose doubling changes every compared value by less than ``tolerance``.
    resolution : Resolution

    Raises
    ------
    ValueError
        Naming ``tolerance`` or ``largest`` out of range.
    """
    if not tolerance > 0:
        raise ValueError(f"tolerance = {tolerance!r}: must be > 0")
    if largest < 2 * start:
        raise ValueError(f"largest = {largest!r}: must be at least twice start = {start!r}")
    positions, values, changes = start, evaluate(start), []
    while 2 * positions <= largest:
        finer = evaluate(2 * positions)
        changes.append(_largest_change(
            {n: v for n, v in values.items() if compared is None or n in compared},
            {n: v for n, v in finer.items() if compared is None or n in compared}))
        if changes[-1] < tolerance:
            break
        positions, values = 2 * positions, finer
    return values, Resolution(positions, tuple(changes), bool(changes[-1] < tolerance),
                              float(tolerance))


def evaluator_factory(pair, evaluation):
    """``evaluator_at(positions) -> Evaluator`` of a pair, each resolution built once.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    evaluation : lsbg.optimise.objectives.EvaluationSettings
        The search's (``phases`` replaced by the positions asked for).

    Returns
    -------
    callable
    """
    from functools import lru_cache

    from lsbg.optimise.objectives import Evaluator

    @lru_cache(maxsize=None)
    def evaluator_at(positions):
        return Evaluator(pair, dataclasses.replace(evaluation, phases=positions))

    return evaluator_at


def uniform_bed_values(evaluator_at, modifications, positions, names=None):
    """The loaded TCA's quantities of designs under the uniform bed at a resolution
    (:meth:`lsbg.optimise.objectives.Evaluator.loaded`).

    Parameters
    ----------
    evaluator_at : callable
        ``evaluator_at(positions) -> lsbg.optimise.objectives.Evaluator``.
    modifications : sequence of lsbg.tca.modification.FlankModification
    positions : int
        Loaded TCA positions over a base pitch [-].
    names : sequence of str, optional
        The quantities returned (default: every one).

    Returns
    -------
    dict
        ``{name: array over the designs}``, in :data:`lsbg.optimise.objectives.QUANTITIES`' units.
    """
    evaluator = evaluator_at(positions)
    rows = [evaluator.loaded(m) for m in modifications]
    names = list(rows[0]) if names is None else list(names)
    return {name: np.array([row[name] for row in rows], float) for name in names}


#: The FE figures of each group of states: the aligned pair's and the corners'.
STATE_FIGURES = {"aligned": ("transmission_error", "rated_transmission_error", "contact_pressure",
                             "peak_contact_pressure", "root_stress_pinion", "root_stress_gear"),
                 "corners": ("envelope_transmission_error", "peak_contact_pressure",
                             "root_stress_pinion", "root_stress_gear")}


def fe_state_figures(evaluator, compliance, modification, positions, group):
    """The FE loaded TCA's figures of one design over a group of states, the load range each.

    Parameters
    ----------
    evaluator : lsbg.optimise.objectives.Evaluator
        Its pair, states (aligned and the envelope's corners), torques and line model.
    compliance : xarray.Dataset
        The pair's FE compliance (:func:`lsbg.tooth.config.compliance_for_design`).
    modification : lsbg.tca.modification.FlankModification
    positions : int
        Mesh positions over a base pitch [-], >= 8.
    group : {"aligned", "corners"}
        The aligned pair, or every corner of the envelope.

    Returns
    -------
    dict
        :data:`STATE_FIGURES` of the group, in :data:`FE_QUANTITIES`' units: over the
        corners the largest (``envelope_transmission_error`` at the rated torque, the
        pressure and the root stresses over the load range).
    """
    from lsbg.tooth.load_range import fe_load_range

    s = evaluator.settings
    torques = s.torques  # the load range and the rated torque
    in_range = np.isin(torques, [f * s.rated_torque for f in s.load_factors])
    rated = int(np.flatnonzero(torques == s.rated_torque)[0])
    states = evaluator.states[:1] if group == "aligned" else evaluator.states[1:]
    out = dict.fromkeys(STATE_FIGURES[group], 0.0)
    for _, misalignment in states:
        fe = fe_load_range(evaluator.contact(modification, misalignment), compliance,
                           torques, positions)
        peak_to_peak = fe["transmission_error_peak_to_peak"].values
        if group == "aligned":
            out["transmission_error"] = float(peak_to_peak[in_range].max())
            out["rated_transmission_error"] = float(peak_to_peak[rated])
            out["contact_pressure"] = float(fe["cycle_max_flank_pressure"].values[rated])
        else:
            out["envelope_transmission_error"] = max(out["envelope_transmission_error"],
                                                     float(peak_to_peak[rated]))
        out["peak_contact_pressure"] = max(out["peak_contact_pressure"],
                                           float(fe["cycle_max_contact_pressure"].values.max()))
        for member in ("pinion", "gear"):
            key = f"root_stress_{member}"
            out[key] = max(out[key], float(fe[f"cycle_max_{key}"].values.max()))
    return out


def fe_group_values(evaluator_at, compliance, modifications, positions, group):
    """:func:`fe_state_figures` of designs: ``{name: array over the designs}``."""
    rows = [fe_state_figures(evaluator_at(positions), compliance, m, positions, group)
            for m in modifications]
    return {name: np.array([row[name] for row in rows], float) for name in STATE_FIGURES[group]}


def fe_combined(aligned, corners):
    """:data:`FE_QUANTITIES` of the aligned pair's and the corners' figures (arrays or floats)."""
    def most(*values):
        return np.maximum.reduce([np.asarray(v, float) for v in values])

    out = {name: np.asarray(aligned[name], float) for name in
           ("transmission_error", "rated_transmission_error", "contact_pressure")}
    out["envelope_transmission_error"] = most(aligned["rated_transmission_error"],
                                              corners["envelope_transmission_error"])
    for name in ("peak_contact_pressure", "root_stress_pinion", "root_stress_gear"):
        out[name] = most(aligned[name], corners[name])
    out["root_stress"] = most(out["root_stress_pinion"], out["root_stress_gear"])
    return {name: out[name] for name in FE_QUANTITIES}
