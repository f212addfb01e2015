"""One trace's ease-off optimisation from a configuration: search, choice, dataset.

:func:`optimise_pair` is what ``lsbg optimise`` runs: the settings of
:func:`lsbg.optimise.checks.run_settings` (read and checked before anything
is evaluated), the shared design (the configuration's ``flank_modification``)
evaluated for comparison, the search (:func:`lsbg.optimise.search.optimise`;
with ``start_from_shared`` the shared design takes the first place of its
initial population), the choice rule on the feasible front (:func:`lsbg.optimise.choice.choose`) or,
with ``choose_from = "below_shared"``, on the front's members whose loaded
TE peak to peak at the rated torque is below the shared design's
(:func:`choice_candidates`; the whole front if none is),
the chosen design checked for edge contact at the V-H map's resolution
(:meth:`lsbg.optimise.objectives.Evaluator.edge_contact`; one that fails is
dropped and the rule chooses again from the rest), and the front's dataset
(:func:`lsbg.optimise.dataset.front_dataset`).
"""

from __future__ import annotations

import numpy as np

from lsbg.optimise.choice import choose
from lsbg.optimise.dataset import front_dataset
from lsbg.optimise.objectives import Evaluator
from lsbg.optimise.search import optimise

__all__ = ["optimise_pair", "settings_attributes", "choice_candidates", "checked_choice"]

#: Where the choice rule picks from: ``below_shared``, the front's members whose loaded
#: TE peak to peak at the rated torque is below the shared design's (the design the
#: choice replaces must not get worse in the paper's own measure of smoothness; the
#: whole front if no member is); ``front``, every member of the front.
CHOOSE_FROM = ("below_shared", "front")


def settings_attributes(settings):
    """The dataset attributes of a run's settings (:func:`lsbg.optimise.checks.run_settings`)."""
    evaluation = settings["evaluation"]
    lubricant = evaluation.lubricant
    return {
        "choice_rule": settings["choice"],
        "choose_from": settings["choose_from"],
        "start_from_shared": settings["start_from_shared"],
        "workers": settings["workers"],
        "permissible_pressure_MPa": settings["permissible_pressure"],
        "rated_torque_N_m": evaluation.rated_torque,
        "load_factors": " ".join(f"{f:g}" for f in evaluation.load_factors),
        "phases": evaluation.phases,
        "envelope_corners": ", ".join(label for label, _ in evaluation.corners) or "none",
        **{f"misalignment_{k}": v for k, v in (evaluation.base.to_config().items()
                                               if evaluation.base is not None else ())},
        "pinion_speed_deg_s": float(np.degrees(evaluation.pinion_speed)),
        "friction_law": evaluation.friction_law,
        "oil_viscosity_mm2_s": lubricant.kinematic_viscosity * 1e6,
        "oil_density_kg_m3": lubricant.density,
        "flank_roughness_Ra_um": lubricant.roughness * 1e6,
        "pattern_margin": evaluation.pattern_margin,
        "edge_load_tolerance": evaluation.edge_load_tolerance,
        "marking_compound_um": evaluation.marking * 1e6,
        "tca_positions": evaluation.tca_positions,
        "check_positions": evaluation.check_positions,
        "check_grid": f"{evaluation.check_grid[0]} x {evaluation.check_grid[1]}",
        "edge_radius_mm": (evaluation.edge_radius * 1e3 if evaluation.edge_radius is not None
                           else "none"),
        **{f"reference_flank_modification_{k}": ("" if v is None else v)
           for k, v in settings["reference"].to_config().items()},
    }


def choice_candidates(front, choose_from, shared_transmission_error):
    """The members of a front that the choice rule picks from.

    Parameters
    ----------
    front : lsbg.optimise.search.Front
    choose_from : {"below_shared", "front"}
        :data:`CHOOSE_FROM`.
    shared_transmission_error : float
        The shared design's loaded TE peak to peak at the rated torque [urad].

    Returns
    -------
    numpy.ndarray of int
        Indices in the run's designs (``front.x``): the front's members whose
        ``rated_transmission_error`` is below ``shared_transmission_error``
        for ``below_shared`` if there are any, else every member.

    Raises
    ------
    ValueError
        For a ``choose_from`` not in :data:`CHOOSE_FROM`.
    """
    if choose_from not in CHOOSE_FROM:
        raise ValueError(f"optimise.choose_from = {choose_from!r}: one of {CHOOSE_FROM}")
    members = np.flatnonzero(front.front)
    if choose_from == "below_shared":
        below = members[front.quantities["rated_transmission_error"][members]
                        < shared_transmission_error]
        if below.size:
            return below
    return members


def checked_choice(evaluator, front, space, rule, permissible_pressure, members=None):
    """The choice rule's member of the front that passes the finer edge-contact check.

    Parameters
    ----------
    evaluator : lsbg.optimise.objectives.Evaluator
    front : lsbg.optimise.search.Front
    space : lsbg.optimise.space.DesignSpace
    rule : str
    permissible_pressure : float
        [MPa].
    members : array_like of int, optional
        The candidates (:func:`choice_candidates`; default: every member of the
        front). Where none of them passes, the rest of the front is tried.

    Returns
    -------
    chosen : int
        Index in the run's designs (``front.x``), -1 if no member of the front passes.
    checked : numpy.ndarray, shape (designs,)
        The finer check's edge-contact share of each member checked, NaN elsewhere [-].
    """
    checked = np.full(front.x.shape[0], np.nan)
    everyone = np.flatnonzero(front.front)
    first = everyone if members is None else np.asarray(members, int)
    rest = sorted(set(everyone.tolist()) - set(first.tolist()))
    for candidates in (list(first), rest):
        while candidates:
            k = candidates[choose(front.values[candidates], front.objectives, rule,
                                  permissible_pressure)]
            checked[k] = evaluator.edge_contact(space.modification(front.x[k]))
            if checked[k] <= 0.0:
                return int(k), checked
            candidates.remove(k)
    return -1, checked


def optimise_pair(pair, settings, seed=None, log=None):
    """Optimise one pair's ease-off and choose its design.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    settings : dict
        :func:`lsbg.optimise.checks.run_settings` of the configuration.
    seed : int, optional
        In place of the settings' seed.
    log : callable, optional
        ``log(text)``: a line per generation.

    Returns
    -------
    xarray.Dataset
        :func:`lsbg.optimise.dataset.front_dataset`, with the settings and the
        design as attributes.
    """
    evaluator = Evaluator(pair, settings["evaluation"])
    reference = evaluator.evaluate(settings["reference"])
    if settings["permissible_pressure"] is None:
        # the pressure of the design the choice replaces, in the same model
        settings = {**settings, "permissible_pressure": float(reference["contact_pressure"])}
    space = settings["space"]
    front = optimise(evaluator, space, settings["objectives"],
                     settings["population"], settings["generations"],
                     settings["seed"] if seed is None else seed, settings["algorithm"], log,
                     initial=[space.scaled(settings["reference"])]
                     if settings["start_from_shared"] else None,
                     workers=settings["workers"])
    members = choice_candidates(front, settings["choose_from"],
                                reference["rated_transmission_error"])
    chosen, checked = checked_choice(evaluator, front, space, settings["choice"],
                                     settings["permissible_pressure"], members)
    attrs = {**settings_attributes(settings),
             "choice_candidates": int(members.size),
             "chosen_below_shared_transmission_error": bool(
                 chosen >= 0 and front.quantities["rated_transmission_error"][chosen]
                 < reference["rated_transmission_error"]),
             **{f"design_{k}": v for k, v in pair.design.to_config().items()}}
    return front_dataset(front, space, chosen, reference, attrs, checked)
