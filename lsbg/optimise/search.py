"""The search: NSGA-II (or NSGA-III) over the design space, its hypervolume by generation.

:func:`optimise` runs pymoo's NSGA-II (Deb, Pratap, Agarwal & Meyarivan,
IEEE Trans. Evol. Comput. 6, 2002) or NSGA-III (Deb & Jain, 2014) with its
default operators (simulated binary crossover, polynomial mutation, binary
tournaments) on the design space scaled to the unit cube
(:class:`lsbg.optimise.space.DesignSpace`); the constraints are handled by
constraint domination (a feasible design beats an infeasible one, two
infeasible ones by their total violation). It is deterministic: pymoo draws
every random number from a generator seeded with ``seed``, and the
evaluations are deterministic.

The run's **front** is every feasible design it evaluated that no other
feasible design it evaluated dominates (an external archive, as in Zitzler &
Thiele's SPEA, IEEE Trans. Evol. Comput. 3, 1999): NSGA-II's last population
holds only ``population`` designs and can lose good ones to crowding in four
objectives, while the archive keeps all it found. Its **hypervolume** after
each generation is recorded (moocore's exact hypervolume, Fonseca, Paquete &
López-Ibáñez 2006) on objectives normalised by fixed scales, f / f_scale with f_scale of
:data:`HYPERVOLUME_SCALES` (zero is every objective's ideal, and each scale a
value the worst useful design reaches), with the reference point 1 in every
objective: the same box for every run of a problem, so that the histories
of two seeds, and of a small and a full budget, compare. The archive only
grows, so the history does not fall (a last population's can), and
generations without a feasible design have hypervolume 0.

SI inside the evaluations; the objectives in the units of
:data:`lsbg.optimise.objectives.QUANTITIES`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from lsbg.optimise.objectives import CONSTRAINTS, OBJECTIVES

__all__ = ["ALGORITHMS", "HYPERVOLUME_SCALES", "Front", "hypervolume", "merged_front",
           "evaluate_designs", "optimise"]

#: The algorithms by name.
ALGORITHMS = ("nsga2", "nsga3")
#: Each objective's scale of the hypervolume, in its unit: the normalised objective
#: is f / scale and the reference point 1. About the largest value of the design
#: space's designs (a 300-design random sample of the paper's pair at 35 deg and
#: 485 N m: TE peak to peak 31-136 urad, its first harmonic 14-64 urad, the
#: envelope's TE 31-159 urad, pattern movement 2.6-26 mm, pressure 1.4-4.2 GPa,
#: loss 1.1-1.9 %): the box holds the useful designs, the scales stay fixed
#: across runs.
HYPERVOLUME_SCALES = {"transmission_error": 150.0, "transmission_error_harmonic": 75.0,
                      "envelope_transmission_error": 150.0, "pattern_movement": 10.0,
                      "contact_pressure": 4000.0, "mesh_loss": 2.0}


def hypervolume(values, objectives):
    """Hypervolume of a set of objective vectors, normalised by :data:`HYPERVOLUME_SCALES`.

    Parameters
    ----------
    values : array_like, shape (n, m)
        Objective values in their units (rows of designs).
    objectives : sequence of str
        The m objectives' names.

    Returns
    -------
    float
        The volume the set dominates in the unit box up to the reference
        point (1, ..., 1) [-]; 0 for an empty set.
    """
    import moocore

    values = np.asarray(values, float).reshape(-1, len(objectives))
    if values.shape[0] == 0:
        return 0.0
    scales = np.array([HYPERVOLUME_SCALES[name] for name in objectives])
    normalised = values / scales
    inside = np.all(normalised < 1.0, axis=1)
    if not np.any(inside):
        return 0.0
    return float(moocore.hypervolume(normalised[inside], ref=np.ones(len(objectives))))


@dataclass(frozen=True)
class Front:
    """The outcome of a run: its final population, its front and its history.

    Attributes
    ----------
    x : numpy.ndarray, shape (n, variables)
        The scaled variables [-] of the final population's designs, then of
        the archive's front members not in it.
    quantities : dict
        ``{name: array (n,)}``: every quantity of each design's evaluation.
    objectives : tuple of str
    feasible : numpy.ndarray of bool, shape (n,)
    front : numpy.ndarray of bool, shape (n,)
        The run's front: the feasible designs no feasible design evaluated
        in the run dominates.
    hypervolume : numpy.ndarray, shape (generations,)
        The front's hypervolume so far, after each generation [-].
    feasible_count : numpy.ndarray, shape (generations,)
        Feasible individuals of each generation's population [-].
    evaluations : numpy.ndarray, shape (generations,)
        Evaluations made by each generation's end [-].
    seed, population, generations : int
    algorithm : str
    seconds : float
        Wall time of the run [s].
    population_member : numpy.ndarray of bool, shape (n,)
        The final population's designs (the first ``population`` rows).
    """

    x: np.ndarray
    quantities: dict
    objectives: tuple
    feasible: np.ndarray
    front: np.ndarray
    hypervolume: np.ndarray
    feasible_count: np.ndarray
    evaluations: np.ndarray
    seed: int
    population: int
    generations: int
    algorithm: str
    seconds: float
    population_member: np.ndarray = None

    @property
    def values(self):
        """Objective values, shape (n, objectives), in their units."""
        return np.column_stack([self.quantities[name] for name in self.objectives])


#: The scale of each constraint's violation in the search: the constraints are in
#: different units, and constraint domination compares the sum of the violations
#: over these scales, so that each counts alike: a tenth of the positions with an
#: edge contact, 1 % of the load at the edges, one raster cell (0.5 mm) of the
#: pattern's margin, 5 um of relief beyond the backlash, one state without contact.
CONSTRAINT_SCALES = {"edge_contact": 0.1, "edge_load": 0.01, "pattern_margin": 0.5,
                     "relief_backlash": 5.0, "contact_lost": 1.0}


def _violations(quantities):
    """The constraints' values over their scales (feasible at <= 0), in :data:`CONSTRAINTS`'
    order."""
    return [quantities[name] / CONSTRAINT_SCALES[name] for name in CONSTRAINTS]


def non_dominated(values):
    """True for the rows of ``values`` that no other row dominates (minimisation)."""
    values = np.asarray(values, float)
    keep = np.ones(values.shape[0], bool)
    for i in range(values.shape[0]):
        others = values[np.arange(values.shape[0]) != i]
        dominated = np.all(others <= values[i], axis=1) & np.any(others < values[i], axis=1)
        keep[i] = not np.any(dominated)
    return keep


def dominated_by(values, others):
    """True for the rows of ``values`` that some row of ``others`` dominates (minimisation)."""
    values, others = np.asarray(values, float), np.asarray(others, float)
    if values.shape[0] == 0 or others.shape[0] == 0:
        return np.zeros(values.shape[0], bool)
    a, b = values[:, None, :], others[None, :, :]
    return np.any(np.all(b <= a, axis=2) & np.any(b < a, axis=2), axis=1)


def merged_front(front, candidates):
    """The non-dominated rows of a front and new candidates, each set's own kept rows.

    Parameters
    ----------
    front : array_like, shape (n, m)
        Mutually non-dominated objective vectors.
    candidates : array_like, shape (k, m)
        New objective vectors.

    Returns
    -------
    keep_front : numpy.ndarray of bool, shape (n,)
    keep_candidates : numpy.ndarray of bool, shape (k,)
        The rows of each that no row of the union dominates.
    """
    front = np.asarray(front, float).reshape(-1, np.shape(candidates)[1])
    candidates = np.asarray(candidates, float)
    keep = non_dominated(candidates) & ~dominated_by(candidates, front)
    return ~dominated_by(front, candidates[keep]), keep


#: The evaluator of the forked workers (:func:`_worker_pool`), set before the fork.
_WORKER = {}


def _evaluate_in_worker(design):
    return _WORKER["evaluator"].evaluate(design)


def _worker_pool(evaluator, workers):
    """``workers`` forked processes that hold ``evaluator`` (None for one: no pool)."""
    if workers <= 1:
        return None
    import multiprocessing

    _WORKER["evaluator"] = evaluator
    return multiprocessing.get_context("fork").Pool(workers)


def evaluate_designs(evaluator, designs, pool=None, workers=1):
    """The quantities of each design, in order, in a pool's processes where there is one.

    Parameters
    ----------
    evaluator : lsbg.optimise.objectives.Evaluator
        Held by the pool's processes too (:func:`_worker_pool`).
    designs : list of lsbg.tca.modification.FlankModification
    pool : multiprocessing.pool.Pool, optional
    workers : int
        The pool's processes [-].

    Returns
    -------
    list of dict
        :meth:`lsbg.optimise.objectives.Evaluator.evaluate` of each design.
    """
    if pool is None or len(designs) < 2:
        return [evaluator.evaluate(design) for design in designs]
    # contiguous chunks, one per process: each worker's caches serve its own designs
    chunk = -(-len(designs) // max(int(workers), 1))
    return pool.map(_evaluate_in_worker, designs, chunksize=chunk)


def optimise(evaluator, space, objectives, population, generations, seed,
             algorithm="nsga2", log=None, initial=None, workers=1):
    """Run the multi-objective search of one pair's ease-off.

    Parameters
    ----------
    evaluator : lsbg.optimise.objectives.Evaluator
        The pair and how each design is evaluated.
    space : lsbg.optimise.space.DesignSpace
    objectives : sequence of str
        Names of :data:`lsbg.optimise.objectives.OBJECTIVES`, at least one.
    population, generations : int
        Individuals per generation and generations [-]: population x
        generations evaluations.
    seed : int
        The random generator's seed [-].
    algorithm : {"nsga2", "nsga3"}
    log : callable, optional
        ``log(text)`` once per generation.
    initial : array_like, shape (k, space.size), optional
        Scaled designs [-] that take the first k places of the initial
        population (a seeded start: the design the search is to improve on);
        the other places are drawn at random, as without them, from the same
        generator.
    workers : int
        Processes that evaluate each generation's new designs (forked from
        this one, :func:`evaluate_designs`); the front is the same for any
        number, the evaluations being deterministic.

    Returns
    -------
    Front

    Raises
    ------
    ValueError
        For an unknown objective or algorithm, an empty design space, or a
        budget below 2 x 1.
    """
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.algorithms.moo.nsga3 import NSGA3
    from pymoo.core.callback import Callback
    from pymoo.core.problem import Problem
    from pymoo.operators.sampling.rnd import FloatRandomSampling
    from pymoo.optimize import minimize
    from pymoo.util.ref_dirs import get_reference_directions

    objectives = tuple(objectives)
    unknown = [name for name in objectives if name not in OBJECTIVES]
    if unknown or not objectives:
        raise ValueError(f"objectives = {list(objectives)!r}: each one of {sorted(OBJECTIVES)}")
    if algorithm not in ALGORITHMS:
        raise ValueError(f"algorithm = {algorithm!r}: one of {ALGORITHMS}")
    if space.size == 0:
        raise ValueError("the design space has no free variable")
    if int(population) < 2 or int(generations) < 1:
        raise ValueError(f"population = {population!r}, generations = {generations!r}: at "
                         f"least 2 and 1")
    if int(workers) < 1:
        raise ValueError(f"workers = {workers!r}: at least 1")
    initial = np.clip(np.asarray([] if initial is None else initial, float)
                      .reshape(-1, space.size), 0.0, 1.0)[:int(population)]
    evaluated = {}  # the quantities of each design evaluated, by its variables' bytes
    archive = {"keys": [], "values": np.zeros((0, len(objectives)))}  # the run's front
    fresh = []  # the feasible designs evaluated since the last generation's end, by key

    class EaseOff(Problem):
        def __init__(self):
            super().__init__(n_var=space.size, n_obj=len(objectives),
                             n_ieq_constr=len(CONSTRAINTS), xl=0.0, xu=1.0)

        def _evaluate(self, x, out, *args, **kwargs):
            keys = [row.tobytes() for row in np.asarray(x, float)]
            new = [key for key in dict.fromkeys(keys) if key not in evaluated]
            designs = [space.modification(np.frombuffer(key, dtype=float)) for key in new]
            found = evaluate_designs(evaluator, designs, pool, int(workers))
            for key, quantities in zip(new, found):
                evaluated[key] = quantities
                if all(quantities[name] <= 0 for name in CONSTRAINTS):
                    fresh.append(key)
            rows = [evaluated[key] for key in keys]
            out["F"] = np.array([[q[name] for name in objectives] for q in rows])
            out["G"] = np.array([_violations(q) for q in rows])

    history = {"hypervolume": [], "feasible": [], "evaluations": []}

    class Record(Callback):
        def notify(self, algorithm):
            feasible = algorithm.pop.get("CV").ravel() <= 0
            if fresh:
                values = np.array([[evaluated[key][name] for name in objectives]
                                   for key in fresh])
                old, new = merged_front(archive["values"], values)
                archive["keys"] = ([k for k, kept in zip(archive["keys"], old) if kept]
                                   + [k for k, kept in zip(fresh, new) if kept])
                archive["values"] = np.vstack([archive["values"][old], values[new]])
            fresh.clear()
            history["hypervolume"].append(hypervolume(archive["values"], objectives))
            history["feasible"].append(int(feasible.sum()))
            history["evaluations"].append(int(algorithm.evaluator.n_eval))
            if log is not None:
                log(f"generation {algorithm.n_gen}: {int(feasible.sum())} feasible, "
                    f"hypervolume {history['hypervolume'][-1]:.5g}")

    class SeededSampling(FloatRandomSampling):
        def _do(self, problem, n_samples, *args, random_state=None, **kwargs):
            x = super()._do(problem, n_samples, *args, random_state=random_state, **kwargs)
            x[:len(initial)] = initial
            return x

    sampling = SeededSampling()
    if algorithm == "nsga2":
        method = NSGA2(pop_size=int(population), sampling=sampling)
    else:
        partitions = 1
        while math.comb(partitions + len(objectives), len(objectives) - 1) <= int(population):
            partitions += 1
        directions = get_reference_directions("das-dennis", len(objectives),
                                              n_partitions=max(partitions - 1, 1))
        method = NSGA3(ref_dirs=directions, pop_size=int(population), sampling=sampling)
    start = time.perf_counter()
    pool = _worker_pool(evaluator, int(workers))
    try:
        result = minimize(EaseOff(), method, ("n_gen", int(generations)), seed=int(seed),
                          callback=Record(), verbose=False)
    finally:
        if pool is not None:
            pool.terminate()
    seconds = time.perf_counter() - start
    final = np.asarray(result.pop.get("X"), float)
    keys = [row.tobytes() for row in final]
    members, last = set(archive["keys"]), set(keys)
    keys += [key for key in archive["keys"] if key not in last]
    x = np.vstack([final] + [np.frombuffer(key, dtype=float)[None, :] for key in keys[len(final):]])
    rows = [evaluated[key] for key in keys]
    quantities = {name: np.array([q[name] for q in rows]) for name in rows[0]}
    feasible = np.all(np.column_stack([quantities[name] for name in CONSTRAINTS]) <= 0, axis=1)
    front = np.array([key in members for key in keys], bool)
    return Front(x, quantities, objectives, feasible, front,
                 np.array(history["hypervolume"]), np.array(history["feasible"]),
                 np.array(history["evaluations"]), int(seed), int(population),
                 int(generations), algorithm, seconds, np.arange(len(keys)) < len(final))

