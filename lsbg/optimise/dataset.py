"""A run's front as a CF-annotated dataset, and the chosen design back from it.

:func:`front_dataset` writes the designs of a run
(:class:`lsbg.optimise.search.Front`: its final population and the members of
its front, every feasible design it evaluated that no other dominates): each design's ease-off
coefficients (``lengthwise_crowning`` ... in um, the reliefs' lengths as
fractions), every quantity of its evaluation (objectives, constraints and
further figures, :data:`lsbg.optimise.objectives.QUANTITIES`), whether it is
feasible, on the front and chosen; the hypervolume, the feasible count and
the evaluations by generation; the shared design's quantities
(``reference_*``, the configuration's ``flank_modification``); and, as
attributes, the seed, the budget, the objectives, the choice rule, the
hypervolume's scales and reference point, the load, the envelope, the
lubricant, the bounds and the design. :func:`lsbg.optimise.choice.chosen_modification`
reads the chosen design back.
"""

from __future__ import annotations

import datetime

import numpy as np

from lsbg.optimise.objectives import CONSTRAINTS, OBJECTIVES, QUANTITIES
from lsbg.optimise.search import HYPERVOLUME_SCALES
from lsbg.optimise.space import VARIABLES

__all__ = ["VARIABLE_NAMES", "front_dataset"]

#: Long names of the ease-off coefficients, by FlankModification field.
VARIABLE_NAMES = {
    "lengthwise_crowning": "lengthwise crowning C_L",
    "profile_crowning": "profile crowning C_P",
    "bias": "bias B",
    "spiral_angle_correction": "spiral angle correction C_beta",
    "pressure_angle_correction": "pressure angle correction C_alpha",
    "pinion_tip_relief": "pinion tip relief C_a1",
    "gear_tip_relief": "gear tip relief C_a2",
    "pinion_tip_relief_length": "pinion tip relief's length L_1, of the active profile",
    "gear_tip_relief_length": "gear tip relief's length L_2, of the active profile",
}


def _attribute(value):
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    return value


def front_dataset(front, space, chosen, reference, attrs=None, checked=None):
    """The dataset of a run's front.

    Parameters
    ----------
    front : lsbg.optimise.search.Front
    space : lsbg.optimise.space.DesignSpace
    chosen : int
        Index of the chosen design in the run's designs (``front.x``), -1 for none.
    reference : dict
        The shared design's quantities (:meth:`lsbg.optimise.objectives.Evaluator.evaluate`).
    attrs : dict, optional
        Further attributes (the settings, the design, the command line).
    checked : array_like, optional
        The finer edge-contact check of the members the choice checked, NaN
        elsewhere (:func:`lsbg.optimise.run.checked_choice`) [-].

    Returns
    -------
    xarray.Dataset
        On ``individual`` and ``generation``; CF-1.11 ``units`` and
        ``long_name`` on every variable.
    """
    import xarray as xr

    import lsbg
    from lsbg.files import short_labels

    n = front.x.shape[0]
    individual = ("individual",)
    data = {}
    designs = [space.config_values(x) for x in front.x]
    for key, (field, *_) in VARIABLES.items():
        unit = "um" if key.endswith("_um") else "1"
        data[field] = (individual, np.array([d[key] for d in designs]), {
            "units": unit, "long_name": VARIABLE_NAMES[field],
            "free": int(key in space.keys)})
    for name, (unit, text) in QUANTITIES.items():
        role = ("objective" if name in front.objectives else
                "constraint" if name in CONSTRAINTS else "figure")
        data[name] = (individual, np.asarray(front.quantities[name], float),
                      {"units": unit, "long_name": text, "role": role})
        data[f"reference_{name}"] = ((), float(reference[name]), {
            "units": unit, "long_name": f"{text}, the shared design"})
    flags = {"feasible": (front.feasible, "1 where every constraint holds"),
             "front": (front.front, "1 on the feasible non-dominated front"),
             "chosen": (np.arange(n) == chosen, "1 for the design the choice rule picks"),
             "population_member": (np.arange(n) < front.population if front.population_member
                                   is None else front.population_member,
                                   "1 for the final population's designs")}
    for name, (flag, text) in flags.items():
        data[name] = (individual, np.asarray(flag, np.int8), {"units": "1", "long_name": text})
    data["checked_edge_contact"] = (individual, np.full(n, np.nan) if checked is None
                                    else np.asarray(checked, float), {
        "units": "1", "long_name": "share of positions with an edge contact at the V-H "
                                   "map's resolution, over the envelope (NaN: not checked)"})
    generation = ("generation",)
    data["hypervolume"] = (generation, front.hypervolume, {
        "units": "1", "long_name": "hypervolume of the run's front so far, "
                                   "objectives over their scales, reference point 1"})
    data["feasible_count"] = (generation, front.feasible_count, {
        "units": "1", "long_name": "feasible individuals of the population"})
    data["evaluations"] = (generation, front.evaluations, {
        "units": "1", "long_name": "designs evaluated by the generation's end"})
    now = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
    evaluations = int(front.evaluations[-1]) if front.evaluations.size else 0
    base = {
        "Conventions": "CF-1.11",
        "title": "Pareto front of the pinion's ease-off (lsbg.optimise)",
        "source": f"lsbg {lsbg.__version__} (lsbg.optimise.search.optimise), {front.algorithm} "
                  f"(pymoo), uniform-bed line model and surface TCA",
        "history": f"{now} lsbg.optimise.dataset.front_dataset",
        "lsbg_version": lsbg.__version__,
        "algorithm": front.algorithm,
        "seed": front.seed,
        "population": front.population,
        "generations": front.generations,
        "evaluations": evaluations,
        "run_seconds": float(front.seconds),
        "seconds_per_evaluation": float(front.seconds / max(evaluations, 1)),
        "objectives": " ".join(front.objectives),
        "constraints": " ".join(CONSTRAINTS),
        "chosen": int(chosen),
        "feasible_individuals": int(np.sum(front.feasible)),
        "population_feasible_individuals": int(front.feasible_count[-1])
        if front.feasible_count.size else 0,
        "front_individuals": int(np.sum(front.front)),
        "front_definition": "every feasible design evaluated in the run that no other "
                            "feasible design evaluated dominates (an external archive)",
        "final_hypervolume": float(front.hypervolume[-1]) if front.hypervolume.size else 0.0,
        "hypervolume_reference_point": " ".join(["1"] * len(front.objectives)),
        **{f"hypervolume_scale_{name}_{OBJECTIVES[name][0].replace('%', 'percent')}":
           HYPERVOLUME_SCALES[name] for name in front.objectives},
        **{f"bound_{key}": " ".join(f"{v:g}" for v in (
            (low / VARIABLES[key][1], high / VARIABLES[key][1])))
           for key, low, high in zip(space.keys, space.lower, space.upper)},
    }
    base.update(attrs or {})
    base = {k: _attribute(v) for k, v in base.items() if v is not None}
    return short_labels(xr.Dataset(
        data, coords={"individual": ("individual", np.arange(n), {
                          "long_name": "design: the final population, then the front's others"}),
                      "generation": ("generation", np.arange(1, front.hypervolume.size + 1), {
                          "long_name": "generation"})},
        attrs=base))
