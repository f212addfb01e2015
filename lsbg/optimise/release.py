"""The release of a type's ease-off: the fronts' candidates under the verdict's models.

:func:`release_design` is what ``lsbg release`` runs, after the searches
(``lsbg optimise``, both seeds) and before the best design point's files:

1. **Candidates.** Each front's feasible members (every front given: the
   study's seed and the next), the ``candidates`` best of each by the
   preference (:mod:`lsbg.optimise.preference`) at the search's positions
   (the quantities the search has in place of the FE ones: :data:`PROXIES`).
2. **Converged uniform bed.** The candidates and the shared design at
   positions doubled from the search's until no loaded quantity of any of them
   changes by more than ``convergence`` (:func:`lsbg.optimise.verdict.converged`);
   a candidate whose loaded constraint (``edge_load``) fails there is dropped.
3. **FE loaded TCA.** The ``fe_candidates`` best of each front by the
   preference on the converged values, and the shared design, with the FE
   compliance (computed once per geometry), over the load range aligned and
   at the envelope's corners (:func:`lsbg.optimise.verdict.fe_quantities`), at
   positions doubled until the shared design's figures change by less than
   ``convergence``; the released design is evaluated once more at twice those
   positions and its change recorded.
4. **Release.** A candidate is released only if in the FE model it is no worse
   than the shared design in every one of ``criteria`` (within ``tolerance``)
   and better in at least one (:func:`lsbg.optimise.preference.released`);
   among the released, the least weighted sum in the quantities' units
   (``weights``), checked for edge contact at the V-H map's resolution. With
   none released the shared design stays. Each front's own answer (its
   candidates alone) is recorded beside the pooled one.

The verdict's figures of a design (:func:`verdict_values`): the FE loaded TCA's
(:data:`lsbg.optimise.verdict.FE_QUANTITIES`), and where FE has none the
converged uniform bed's (``mesh_loss``) or the unloaded TCA's
(``pattern_movement``).
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from lsbg.optimise import preference
from lsbg.optimise.choice import modification_of
from lsbg.optimise.objectives import QUANTITIES
from lsbg.optimise.verdict import (CONVERGED_QUANTITIES, FE_QUANTITIES, STATE_FIGURES,
                                   converged, fe_combined, fe_group_values, uniform_bed_values)

__all__ = ["PROXIES", "VERDICT_QUANTITIES", "ReleaseSettings", "release_problems",
           "candidates_of", "verdict_values", "release_design", "release_dataset",
           "released_modification", "seeds_agree"]

#: The quantities a preference may weigh and a release compare: the FE loaded TCA's, and
#: the bearing pattern's movement (unloaded TCA) and the mesh loss (converged uniform bed).
VERDICT_QUANTITIES = {**FE_QUANTITIES, "pattern_movement": QUANTITIES["pattern_movement"],
                      "mesh_loss": QUANTITIES["mesh_loss"]}
#: The uniform bed's quantity that stands for a verdict quantity before the FE loaded TCA
#: (None: no stand-in, left out of the pre-ranking).
PROXIES = {**{name: name if name in QUANTITIES else None for name in FE_QUANTITIES},
           "peak_contact_pressure": "contact_pressure",
           "pattern_movement": "pattern_movement", "mesh_loss": "mesh_loss"}
#: The loaded constraints, which the positions change.
LOADED_CONSTRAINTS = ("edge_load",)


@dataclasses.dataclass(frozen=True)
class ReleaseSettings:
    """The ``optimise.release`` section (lsbg/schemas/config.schema.yaml).

    Parameters
    ----------
    criteria : tuple of str
        The FE quantities a released design must not worsen [names of
        :data:`lsbg.optimise.verdict.FE_QUANTITIES`].
    tolerance : float
        Relative: worse is above the shared design's value times (1 + tolerance),
        better below (1 - tolerance) [-].
    weights : dict
        Weight per unit of each quantity of :data:`VERDICT_QUANTITIES` (per urad,
        per MPa, per mm, per %).
    convergence : float
        The largest relative change allowed when the positions double [-].
    largest_positions : int
        The most positions of either loaded TCA [-].
    candidates : int
        Candidates of each front re-evaluated at converged positions [-].
    fe_candidates : int
        Of those, evaluated with the FE loaded TCA per front [-].
    """

    criteria: tuple = ("transmission_error", "peak_contact_pressure", "root_stress")
    tolerance: float = 0.01
    weights: dict = dataclasses.field(default_factory=lambda: {
        "transmission_error": 1.0, "peak_contact_pressure": 0.02, "root_stress": 0.02,
        "pattern_movement": 1.0, "mesh_loss": 10.0})
    convergence: float = 0.01
    largest_positions: int = 768
    candidates: int = 12
    fe_candidates: int = 2

    @classmethod
    def from_config(cls, section):
        """The settings of an ``optimise.release`` section (defaults filled in).

        Raises
        ------
        ValueError
            The first of :func:`release_problems`.
        """
        problems = release_problems(section)
        if problems:
            raise ValueError(problems[0])
        default = cls()
        return cls(criteria=tuple(section.get("criteria", default.criteria)),
                   tolerance=float(section.get("tolerance", default.tolerance)),
                   weights={k: float(v) for k, v in section.get("weights",
                                                                default.weights).items()},
                   convergence=float(section.get("convergence", default.convergence)),
                   largest_positions=int(section.get("largest_positions",
                                                     default.largest_positions)),
                   candidates=int(section.get("candidates", default.candidates)),
                   fe_candidates=int(section.get("fe_candidates", default.fe_candidates)))

    def attributes(self):
        """The settings as dataset attributes (``release_*``)."""
        return {"release_criteria": " ".join(self.criteria),
                "release_tolerance": self.tolerance,
                "release_convergence": self.convergence,
                "release_largest_positions": self.largest_positions,
                "release_candidates": self.candidates,
                "release_fe_candidates": self.fe_candidates,
                **{f"release_weight_{name}_per_{VERDICT_QUANTITIES[name][0].replace('%', 'percent')}":
                   w for name, w in self.weights.items()}}


def release_problems(section, phases=24):
    """Every problem of an ``optimise.release`` section, one line each naming the key.

    Parameters
    ----------
    section : dict
        ``optimise.release``.
    phases : int
        The search's positions (``optimise.phases``), where the doubling starts [-].

    Returns
    -------
    list of str
    """
    problems = []
    criteria = list(section.get("criteria", ReleaseSettings.criteria))
    bad = [c for c in criteria if c not in FE_QUANTITIES]
    if bad or not criteria:
        problems.append(f"optimise.release.criteria = {criteria!r}: name at least one of "
                        f"{', '.join(FE_QUANTITIES)}")
    weights = section.get("weights")
    if weights is not None:
        bad = [w for w in weights if w not in VERDICT_QUANTITIES]
        if bad or not weights:
            problems.append(f"optimise.release.weights = {weights!r}: weigh at least one of "
                            f"{', '.join(VERDICT_QUANTITIES)}")
        elif any(not float(v) >= 0 for v in weights.values()):
            problems.append(f"optimise.release.weights = {weights!r}: weights must be >= 0")
    largest = section.get("largest_positions", ReleaseSettings.largest_positions)
    if largest < 2 * phases:
        problems.append(f"optimise.release.largest_positions = {largest!r}: at least twice "
                        f"optimise.phases = {phases!r} (the positions double from there)")
    return problems


def candidates_of(front, settings, reference):
    """A front's candidates: its feasible members, the best by the preference first.

    Parameters
    ----------
    front : xarray.Dataset
        :func:`lsbg.optimise.dataset.front_dataset`.
    settings : ReleaseSettings
    reference : dict
        The shared design's quantities at the search's positions.

    Returns
    -------
    numpy.ndarray of int
        At most ``settings.candidates`` individuals of the front.
    """
    members = np.flatnonzero((front["front"].values == 1) & (front["feasible"].values == 1))
    if not members.size:
        return members
    weights = {PROXIES[n]: w for n, w in settings.weights.items() if PROXIES.get(n)}
    values = {n: front[n].values[members] for n in weights}
    ranked = preference.weighted_order(values, reference, weights)
    return members[ranked[:settings.candidates]]


def verdict_values(fe, uniform, unloaded):
    """The verdict's figures: the FE ones, the converged uniform bed's mesh loss and the
    unloaded TCA's pattern movement (``{name: array}`` or ``{name: float}`` each)."""
    return {**fe, "mesh_loss": uniform["mesh_loss"], "pattern_movement": unloaded}


def _preferred(values, reference, settings, among):
    """``among`` (indices) in the order of the weights (the verdict's values)."""
    among = np.asarray(among, int)
    if not among.size:
        return among
    part = {n: np.asarray(values[n])[among] for n in settings.weights}
    return among[preference.weighted_order(part, reference, settings.weights)]


def release_design(evaluator_at, settings, release, fronts, compliance, log=None):
    """Re-evaluate the fronts' candidates, release one design or keep the shared one.

    Parameters
    ----------
    evaluator_at : callable
        ``evaluator_at(positions) -> lsbg.optimise.objectives.Evaluator`` of the pair.
    settings : dict
        :func:`lsbg.optimise.checks.run_settings` (its ``reference``, the shared
        design, and ``evaluation.phases``, the search's positions).
    release : ReleaseSettings
    fronts : sequence of xarray.Dataset
        The searches' fronts of this pair (:func:`lsbg.optimise.dataset.front_dataset`).
    compliance : xarray.Dataset
        The pair's FE compliance.
    log : callable, optional
        ``log(text)``.

    Returns
    -------
    dict
        ``candidates`` (list of (front number, individual)), ``modifications``,
        ``search`` (the fronts' values at the search's positions), ``uniform``
        (converged), ``fe`` (the FE candidates' values, NaN for the others),
        ``verdict``, the shared design's ``reference_*`` of each, ``released``,
        ``checked`` (the V-H check's edge share, NaN where not checked),
        ``chosen`` (index in the candidates, -1: the shared design stays),
        ``front_chosen`` (each front's own answer), ``ranks`` (the chosen
        design's place under :data:`lsbg.optimise.preference.ALTERNATIVE_RULES`),
        ``uniform_resolution``, ``fe_resolutions`` (aligned, corners) and ``chosen_fe_change``
        [-], ``seconds``.
    """
    log = log or (lambda text: None)
    started = time.perf_counter()
    shared = settings["reference"]
    search_reference = {n: float(fronts[0][f"reference_{n}"]) for n in QUANTITIES}
    picked = [(f, int(i)) for f, front in enumerate(fronts)
              for i in candidates_of(front, release, search_reference)]
    modifications = [modification_of(fronts[f], i) for f, i in picked]
    search = {n: np.array([float(fronts[f][n].values[i]) for f, i in picked])
              for n in QUANTITIES}
    names = (*CONVERGED_QUANTITIES, *LOADED_CONSTRAINTS)

    def uniform_at(positions):
        return uniform_bed_values(evaluator_at, [shared, *modifications], positions, names)

    values, uniform_resolution = converged(uniform_at, settings["evaluation"].phases,
                                           release.convergence, release.largest_positions,
                                           CONVERGED_QUANTITIES)
    uniform_reference = {n: float(v[0]) for n, v in values.items()}
    uniform = {n: v[1:] for n, v in values.items()}
    log(f"uniform bed: {len(picked)} candidates converged at {uniform_resolution.positions} "
        f"positions (changes {', '.join(f'{c:.2%}' for c in uniform_resolution.changes)})")
    kept = np.flatnonzero(uniform["edge_load"] <= 0) if picked else np.array([], int)
    pattern = search["pattern_movement"]
    proxy_values = {**uniform, "pattern_movement": pattern}
    proxy_weights = {PROXIES[n]: w for n, w in release.weights.items() if PROXIES.get(n)}
    proxy_reference = {**uniform_reference,
                       "pattern_movement": search_reference["pattern_movement"]}
    fe_index = []
    for f in range(len(fronts)):
        mine = np.array([k for k in kept if picked[k][0] == f], int)
        if mine.size:
            part = {n: np.asarray(proxy_values[n])[mine] for n in proxy_weights}
            order = preference.weighted_order(part, proxy_reference, proxy_weights)
            fe_index += list(mine[order[:release.fe_candidates]])
    fe_index = np.array(fe_index, int)

    resolutions, reference_groups, groups = {}, {}, {}
    for group in STATE_FIGURES:
        values, resolutions[group] = converged(
            lambda n, group=group: fe_group_values(evaluator_at, compliance, [shared], n, group),
            settings["evaluation"].phases, release.convergence, release.largest_positions)
        reference_groups[group] = {n: float(v[0]) for n, v in values.items()}
        groups[group] = {n: np.full(len(picked), np.nan) for n in STATE_FIGURES[group]}
        if fe_index.size:
            got = fe_group_values(evaluator_at, compliance, [modifications[k] for k in fe_index],
                                  resolutions[group].positions, group)
            for n, v in got.items():
                groups[group][n][fe_index] = v
        log(f"FE loaded TCA, {group}: the shared design converged at "
            f"{resolutions[group].positions} positions (changes "
            f"{', '.join(f'{c:.2%}' for c in resolutions[group].changes)})")
    reference_fe = {n: float(v) for n, v in fe_combined(**reference_groups).items()}
    fe = fe_combined(**groups)
    verdict = verdict_values(fe, uniform, pattern)
    reference = verdict_values(reference_fe, uniform_reference,
                               search_reference["pattern_movement"])
    is_released = np.zeros(len(picked), bool)
    if fe_index.size:
        is_released[fe_index] = preference.released(
            {n: verdict[n][fe_index] for n in release.criteria}, reference, release.criteria,
            release.tolerance)
    checked = np.full(len(picked), np.nan)
    evaluator = evaluator_at(settings["evaluation"].phases)

    def first_passing(among):
        for k in _preferred(verdict, reference, release, among):
            if np.isnan(checked[k]):
                checked[k] = evaluator.edge_contact(modifications[k])
            if checked[k] <= 0.0:
                return int(k)
        return -1

    released_index = np.flatnonzero(is_released)
    chosen = first_passing(released_index)
    front_chosen = [first_passing([k for k in released_index if picked[k][0] == f])
                    for f in range(len(fronts))]
    ranks, change = {}, float("nan")
    if chosen >= 0:
        # the released designs the V-H check has not turned down
        passed = np.array([k for k in released_index if not checked[k] > 0.0], int)
        part = {n: verdict[n][passed] for n in VERDICT_QUANTITIES}
        for rule in preference.ALTERNATIVE_RULES:
            ordering = preference.order(rule, part, reference, release.weights,
                                        release.criteria, release.tolerance)
            ranks[rule] = preference.rank_of(int(np.flatnonzero(passed == chosen)[0]),
                                             ordering)
        # the released design at twice the positions: its own change
        again = fe_combined(**{g: fe_group_values(evaluator_at, compliance,
                                                  [modifications[chosen]],
                                                  2 * resolutions[g].positions, g)
                               for g in STATE_FIGURES})
        change = max(abs(float(again[n][0]) - fe[n][chosen]) / abs(float(again[n][0]))
                     for n in FE_QUANTITIES)
    return {"candidates": picked, "front_seeds": [int(f.attrs["seed"]) for f in fronts],
            "modifications": modifications, "search": search,
            "uniform": uniform, "fe": fe, "verdict": verdict,
            "reference_search": search_reference, "reference_uniform": uniform_reference,
            "reference_fe": reference_fe, "reference_verdict": reference,
            "released": is_released, "checked": checked, "chosen": chosen,
            "front_chosen": front_chosen, "ranks": ranks,
            "fe_evaluated": np.isin(np.arange(len(picked)), fe_index),
            "uniform_resolution": uniform_resolution, "fe_resolutions": resolutions,
            "chosen_fe_change": change, "seconds": time.perf_counter() - started}


def seeds_agree(front_chosen, verdict, criteria, tolerance):
    """Whether every seed's own answer is the same: all keep the shared design, or all
    release designs whose criteria are within ``tolerance`` of each other.

    Parameters
    ----------
    front_chosen : sequence of int
        Each front's own answer (index in the candidates, -1: the shared design stays).
    verdict : dict
        ``{name: array over the candidates}``, the verdict's figures.
    criteria : sequence of str
    tolerance : float
        Relative [-].

    Returns
    -------
    bool
    """
    chosen = [int(k) for k in front_chosen]
    if all(k < 0 for k in chosen):
        return True
    if any(k < 0 for k in chosen):
        return False
    for name in criteria:
        values = np.asarray(verdict[name], float)[chosen]
        if values.max() - values.min() > tolerance * np.abs(values).max():
            return False
    return True


def release_dataset(result, release, attrs=None):
    """The release's dataset: the candidates and the shared design under every model.

    Parameters
    ----------
    result : dict
        :func:`release_design`.
    release : ReleaseSettings
    attrs : dict, optional
        Further attributes (the design, the command line).

    Returns
    -------
    xarray.Dataset
        On ``candidate``: the front (``front_seed``) and individual each came
        from, its ease-off coefficients, ``search_*`` (the search's positions),
        ``uniform_*`` (converged), ``fe_*`` (NaN where not evaluated) and
        ``verdict_*`` figures, ``score`` (the weighted sum against the shared
        design), ``fe_evaluated``, ``released``, ``checked_edge_contact`` and
        ``chosen``; scalars ``reference_<model>_<name>`` of the shared design.
        Attributes: the settings, both resolutions, ``chosen`` (-1: the shared
        design stays), each front's own answer, ``seeds_agree`` (1: every seed's own
        answer the same, :func:`seeds_agree`), the chosen design's rank under
        each alternative rule, ``chosen_fe_change``.
    """
    import xarray as xr

    import lsbg
    from lsbg.files import short_labels
    from lsbg.optimise.dataset import VARIABLE_NAMES
    from lsbg.optimise.space import VARIABLES

    picked, dims = result["candidates"], ("candidate",)
    seeds = result["front_seeds"]
    data = {"front_seed": (dims, np.array([seeds[f] for f, _ in picked], int), {
                "units": "1", "long_name": "seed of the search whose front it came from"}),
            "individual": (dims, np.array([i for _, i in picked], int), {
                "units": "1", "long_name": "its individual in that front's dataset"})}
    for key, (field, *_) in VARIABLES.items():
        unit, scale = ("um", 1e6) if key.endswith("_um") else ("1", 1.0)
        data[field] = (dims, np.array([getattr(m, field) * scale
                                       for m in result["modifications"]]),
                       {"units": unit, "long_name": VARIABLE_NAMES[field]})
    models = (("search", QUANTITIES, "the search's uniform-bed loaded TCA"),
              ("uniform", QUANTITIES, "the uniform bed at converged positions"),
              ("fe", FE_QUANTITIES, "the FE loaded TCA at converged positions"),
              ("verdict", VERDICT_QUANTITIES, "the verdict's models"))
    for model, table, words in models:
        for name, value in result[model].items():
            unit, text = table.get(name, QUANTITIES.get(name, ("1", name)))
            data[f"{model}_{name}"] = (dims, np.asarray(value, float), {
                "units": unit, "long_name": f"{text}, {words}"})
            data[f"reference_{model}_{name}"] = ((), float(result[f"reference_{model}"][name]), {
                "units": unit, "long_name": f"{text}, {words}, the shared design"})
    weights = release.weights
    score = (preference.scores({n: result["verdict"][n] for n in weights},
                               result["reference_verdict"], weights)
             if picked else np.zeros(0))
    data["score"] = (dims, np.asarray(score, float) * np.where(result["fe_evaluated"], 1, np.nan),
                     {"units": "1", "long_name": "weighted sum of the verdict's figures less "
                                                 "the shared design's (NaN: no FE)"})
    n = len(picked)
    for name, flag, text in (
            ("fe_evaluated", result["fe_evaluated"], "1 where the FE loaded TCA evaluated it"),
            ("released", result["released"], "1 where no criterion is worse than the shared "
                                              "design's and one is better, under FE"),
            ("chosen", np.arange(n) == result["chosen"], "1 for the released design")):
        data[name] = (dims, np.asarray(flag, np.int8), {"units": "1", "long_name": text})
    data["checked_edge_contact"] = (dims, result["checked"], {
        "units": "1", "long_name": "share of positions with an edge contact at the V-H map's "
                                   "resolution, over the envelope (NaN: not checked)"})
    base = {"Conventions": "CF-1.11",
            "title": "The release of an ease-off: the fronts' candidates under the verdict's "
                     "models (lsbg.optimise.release)",
            "source": f"lsbg {lsbg.__version__} (lsbg.optimise.release.release_design)",
            "lsbg_version": lsbg.__version__,
            "chosen": int(result["chosen"]),
            "shared_kept": int(result["chosen"] < 0),
            "front_seeds": " ".join(str(s) for s in seeds),
            **{f"seed{s}_chosen": int(k) for s, k in zip(seeds, result["front_chosen"])},
            "seeds_agree": int(seeds_agree(result["front_chosen"], result["verdict"],
                                           release.criteria, release.tolerance)),
            **{f"rank_under_{rule}": r for rule, r in result["ranks"].items()},
            "chosen_fe_change": float(result["chosen_fe_change"]),
            "released_candidates": int(np.sum(result["released"])),
            "fe_candidates_evaluated": int(np.sum(result["fe_evaluated"])),
            "run_seconds": float(result["seconds"]),
            **result["uniform_resolution"].attributes("uniform"),
            **{k: v for group, resolution in result["fe_resolutions"].items()
               for k, v in resolution.attributes(f"fe_{group}").items()},
            **release.attributes()}
    base.update(attrs or {})
    return short_labels(xr.Dataset(data, coords={"candidate": ("candidate", np.arange(n), {
        "units": "1", "long_name": "candidate: each front's best by the preference"})}, attrs=base))


def released_modification(dataset):
    """The released ease-off of a release's dataset, None where the shared design stays.

    Parameters
    ----------
    dataset : xarray.Dataset
        :func:`release_dataset`.

    Returns
    -------
    lsbg.tca.modification.FlankModification or None
    """
    index = int(dataset.attrs["chosen"])
    return None if index < 0 else modification_of(dataset, index)
