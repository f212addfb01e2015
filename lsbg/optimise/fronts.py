"""Trace against trace: the fronts of several searches per trace compared as sets.

The release answers for two designs; the claims are about the tooth trace. Here
each trace's fronts (``optimise.seeds`` searches, ``lsbg optimise``) are compared
on converged objectives (docs/optimise.md, "Trace against trace", where the
verdict rule is stated):

* :func:`converged_front`: every member of every front evaluated again at the
  release's converged uniform-bed positions on the search's model
  (:func:`lsbg.optimise.verdict.uniform_bed_values`, the release's own
  re-evaluation), those failing ``edge_load`` there dropped, and each seed's
  non-dominated set kept (``lsbg converge-front``, one trace).
* :func:`trace_statistics`: in the common box (each objective normalised over
  every converged front of both traces, the hypervolume's reference point
  :data:`REFERENCE` in every normalised objective) the hypervolume per seed,
  its median and spread per trace, Mann-Whitney U and Vargha-Delaney A12, the
  additive epsilon-indicator both ways, the share of each pooled front the
  other dominates, and the EAF difference in every 2-D projection with a
  permutation test over the seeds' trace labels (``lsbg trace-fronts``).
* :func:`verdict`: the rule of docs/optimise.md.

The objectives are minimised, in :data:`lsbg.optimise.objectives.QUANTITIES`' units;
normalised values are dimensionless.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from lsbg.optimise.choice import modification_of
from lsbg.optimise.objectives import QUANTITIES
from lsbg.optimise.verdict import uniform_bed_values

__all__ = ["REFERENCE", "LARGE_EFFECT", "VERDICTS", "converged_front", "non_dominated",
           "common_box", "vargha_delaney_a12", "epsilon_both_ways", "dominated_share",
           "eaf_difference", "permutation_p", "verdict", "trace_statistics",
           "converged_front_dataset", "seed_sets", "trace_fronts_dataset"]

#: The hypervolume's reference point in every normalised objective [-].
REFERENCE = 1.1
#: Vargha and Delaney's large effect: A12 at or beyond 0.71 (or at or below 0.29) [-].
LARGE_EFFECT = 0.71
#: The verdict's codes: 1 the first trace (the LSBG) better, -1 the second, 0 a tie.
VERDICTS = {1: "the LSBG's fronts are better", -1: "the SBG's fronts are better", 0: "a tie"}


def non_dominated(values):
    """Which rows of ``values`` (members x objectives, minimised) no other row dominates.

    Parameters
    ----------
    values : numpy.ndarray
        (n, m), any units.

    Returns
    -------
    numpy.ndarray of bool
        (n,); duplicates are all kept.
    """
    values = np.asarray(values, float)
    keep = np.ones(len(values), bool)
    for i, row in enumerate(values):
        dominates = np.all(values <= row, axis=1) & np.any(values < row, axis=1)
        keep[i] = not dominates.any()
    return keep


def converged_front(evaluator_at, fronts, positions, objectives, log=None):
    """Every front member at ``positions``, those failing ``edge_load`` dropped, each
    seed's non-dominated set marked.

    Parameters
    ----------
    evaluator_at : callable
        ``evaluator_at(positions) -> lsbg.optimise.objectives.Evaluator`` of the pair.
    fronts : sequence of xarray.Dataset
        One trace's searches (:func:`lsbg.optimise.dataset.front_dataset`), one per seed.
    positions : int
        Loaded TCA positions over a base pitch: the release's converged ones [-].
    objectives : sequence of str
        The searches' objectives (names of :data:`lsbg.optimise.objectives.QUANTITIES`).
    log : callable, optional
        ``log(text)``.

    Returns
    -------
    dict
        ``seed`` and ``individual`` of each member (of the fronts' feasible members),
        ``search`` and ``converged`` ({objective: array}), ``edge_load`` at the
        positions, ``kept`` (feasible there and on its seed's non-dominated set),
        ``seeds``, ``positions``.
    """
    log = log or (lambda text: None)
    loaded = [n for n in objectives if n != "pattern_movement"]
    seeds, individuals, search, converged = [], [], {n: [] for n in objectives}, \
        {n: [] for n in objectives}
    edge = []
    for front in fronts:
        members = np.flatnonzero((front["front"].values == 1) & (front["feasible"].values == 1))
        seed = int(front.attrs["seed"])
        seeds += [seed] * members.size
        individuals += list(members)
        if not members.size:
            log(f"seed {seed}: no feasible member on the front")
            continue
        values = uniform_bed_values(evaluator_at, [modification_of(front, int(i))
                                                   for i in members],
                                    positions, (*loaded, "edge_load"))
        edge += list(values["edge_load"])
        for n in objectives:
            search[n] += list(front[n].values[members])
            # the unloaded TCA's pattern movement does not change with the loaded positions
            converged[n] += list(values[n] if n in loaded else front[n].values[members])
        log(f"seed {seed}: {members.size} members at {positions} positions")
    seeds = np.array(seeds, int)
    edge = np.array(edge, float)
    table = np.column_stack([converged[n] for n in objectives]) if seeds.size else \
        np.zeros((0, len(objectives)))
    kept = np.zeros(seeds.size, bool)
    for seed in np.unique(seeds):
        mine = np.flatnonzero((seeds == seed) & (edge <= 0))
        kept[mine[non_dominated(table[mine])]] = True
    return {"seed": seeds, "individual": np.array(individuals, int),
            "search": {n: np.array(v, float) for n, v in search.items()},
            "converged": {n: np.array(v, float) for n, v in converged.items()},
            "edge_load": edge, "kept": kept,
            "seeds": [int(f.attrs["seed"]) for f in fronts], "positions": int(positions)}


def common_box(sets):
    """The least and largest value of each objective over ``sets`` (the box's corners).

    Parameters
    ----------
    sets : sequence of numpy.ndarray
        (n_k, m) each, in the objectives' units; empty ones ignored.

    Returns
    -------
    low, high : numpy.ndarray
        (m,); where an objective has one value, ``high`` is ``low`` + 1 unit.
    """
    rows = np.vstack([s for s in sets if len(s)])
    low, high = rows.min(axis=0), rows.max(axis=0)
    return low, np.where(high > low, high, low + 1.0)


def vargha_delaney_a12(a, b):
    """Vargha-Delaney A12: P(a > b) + P(a = b) / 2 over all pairs [-]."""
    a, b = np.asarray(a, float)[:, None], np.asarray(b, float)[None, :]
    return float(np.mean((a > b) + 0.5 * (a == b)))


def epsilon_both_ways(a, b):
    """The additive epsilon-indicator I(a, b) and I(b, a) (``moocore.epsilon_additive``).

    Parameters
    ----------
    a, b : numpy.ndarray
        (n, m) normalised, minimised.

    Returns
    -------
    tuple of float
        I(a, b): the least eps by which ``a`` moved down weakly dominates ``b``; and
        I(b, a). NaN where either set is empty.
    """
    import moocore

    if not len(a) or not len(b):
        return math.nan, math.nan
    return (float(moocore.epsilon_additive(a, ref=b)), float(moocore.epsilon_additive(b, ref=a)))


def dominated_share(a, b):
    """The share of the members of ``a`` that a member of ``b`` dominates [-] (NaN: ``a``
    empty)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    if not len(a):
        return math.nan
    if not len(b):
        return 0.0
    worse = [np.any(np.all(b <= row, axis=1) & np.any(b < row, axis=1)) for row in a]
    return float(np.mean(worse))


def eaf_difference(sets_a, sets_b, reference=REFERENCE):
    """The EAF difference of two groups of 2-D sets in the box [0, reference]^2.

    Parameters
    ----------
    sets_a, sets_b : sequence of numpy.ndarray
        (n_k, 2) normalised points of each seed's front, as many sets in each group;
        an empty set attains nothing.
    reference : float
        The box's upper corner in both objectives [-].

    Returns
    -------
    rectangles : numpy.ndarray
        (r, 4): x low, y low, x high, y high of each rectangle of constant difference,
        clipped to the box.
    difference : numpy.ndarray
        (r,): the share of ``sets_a`` attaining it less that of ``sets_b`` [-], in [-1, 1].
    statistic : float
        The area-weighted mean of |difference| over the box [-].
    """
    import moocore

    if len(sets_a) != len(sets_b):
        raise ValueError(f"{len(sets_a)} sets against {len(sets_b)}: the EAF difference "
                         f"needs as many seeds of each trace")
    if not any(len(s) for s in (*sets_a, *sets_b)):
        return np.zeros((0, 4)), np.zeros(0), 0.0
    corner = np.array([[reference, reference]])

    def stacked(sets):
        # each set also holds the box's corner, which attains nothing inside the box, so
        # that an empty set keeps its number
        return np.vstack([np.column_stack([np.vstack([s, corner]), np.full(len(s) + 1, k + 1)])
                          for k, s in enumerate(sets)])

    out = moocore.eafdiff(stacked(sets_a), stacked(sets_b), rectangles=True)
    rectangles = np.clip(out[:, :4], 0.0, reference)
    difference = out[:, 4] / len(sets_a)
    area = ((rectangles[:, 2] - rectangles[:, 0]) * (rectangles[:, 3] - rectangles[:, 1]))
    keep = area > 0
    statistic = float(np.sum(area[keep] * np.abs(difference[keep])) / reference ** 2)
    return rectangles[keep], difference[keep], statistic


def permutation_p(sets_a, sets_b, statistic):
    """The permutation test over the trace labels of the pooled sets.

    Parameters
    ----------
    sets_a, sets_b : sequence
        The two groups' sets.
    statistic : callable
        ``statistic(group_a, group_b) -> float``, larger the more the groups differ.

    Returns
    -------
    p : float
        The share of all labelings (the pooled sets into groups of the two sizes,
        the observed one included) whose statistic is at least the observed one [-].
    labelings : int
    """
    pooled = list(sets_a) + list(sets_b)
    observed = statistic(list(sets_a), list(sets_b))
    values = []
    for chosen in itertools.combinations(range(len(pooled)), len(sets_a)):
        rest = [k for k in range(len(pooled)) if k not in chosen]
        values.append(statistic([pooled[k] for k in chosen], [pooled[k] for k in rest]))
    values = np.array(values)
    return float(np.mean(values >= observed - 1e-12 * max(abs(observed), 1.0))), len(values)


def verdict(a12, epsilon_ab, epsilon_ba):
    """The rule of docs/optimise.md: 1 the first trace better, -1 the second, 0 a tie,
    NaN no verdict (a trace without a feasible member)."""
    if not all(np.isfinite([a12, epsilon_ab, epsilon_ba])):
        return math.nan
    if a12 >= LARGE_EFFECT and epsilon_ab < epsilon_ba:
        return 1
    if a12 <= 1 - LARGE_EFFECT and epsilon_ba < epsilon_ab:
        return -1
    return 0


def trace_statistics(fronts_a, fronts_b, objectives):
    """The statistics of docs/optimise.md between two traces' converged fronts.

    Parameters
    ----------
    fronts_a, fronts_b : sequence of numpy.ndarray
        Each seed's converged non-dominated set, (n_k, m) in the objectives' units
        (the LSBG's first).
    objectives : sequence of str
        The m objectives' names.

    Returns
    -------
    dict
        ``low``, ``high`` (the box), ``hypervolume_a``, ``hypervolume_b`` (per seed,
        normalised [-]), ``mann_whitney_u``, ``mann_whitney_p``, ``a12``,
        ``epsilon_ab``, ``epsilon_ba``, ``dominated_share_a`` (the share of the first
        trace's pooled front that the second's dominates), ``dominated_share_b``,
        ``projections`` (the objectives' pairs), ``eaf`` (per projection:
        rectangles, difference, statistic, p), ``eaf_p`` (the mean statistic over the
        projections, its permutation p), ``labelings``, ``verdict``.
    """
    import moocore
    from scipy.stats import mannwhitneyu

    objectives = list(objectives)
    if not any(len(s) for s in (*fronts_a, *fronts_b)):
        low = high = np.full(len(objectives), np.nan)
    else:
        low, high = common_box([*fronts_a, *fronts_b])

    def normalised(s):
        return (np.asarray(s, float).reshape(-1, len(objectives)) - low) / (high - low)

    norm_a, norm_b = [normalised(s) for s in fronts_a], [normalised(s) for s in fronts_b]
    reference = np.full(len(objectives), REFERENCE)

    def hypervolume(s):
        return float(moocore.hypervolume(s, ref=reference)) if len(s) else 0.0

    hv_a = np.array([hypervolume(s) for s in norm_a])
    hv_b = np.array([hypervolume(s) for s in norm_b])
    test = mannwhitneyu(hv_a, hv_b, alternative="two-sided", method="exact")
    pooled_a, pooled_b = (np.vstack([*s, np.zeros((0, len(objectives)))]) for s in (norm_a, norm_b))
    pooled_a, pooled_b = pooled_a[non_dominated(pooled_a)], pooled_b[non_dominated(pooled_b)]
    eps_ab, eps_ba = epsilon_both_ways(pooled_a, pooled_b)
    empty = not len(pooled_a) or not len(pooled_b)
    projections = list(itertools.combinations(range(len(objectives)), 2))
    eaf = []
    for i, j in projections:
        a2, b2 = [s[:, [i, j]] for s in norm_a], [s[:, [i, j]] for s in norm_b]

        def stat(x, y):
            return eaf_difference(x, y)[2]

        rectangles, difference, value = eaf_difference(a2, b2)
        p, labelings = permutation_p(a2, b2, stat)
        eaf.append({"rectangles": rectangles, "difference": difference,
                    "statistic": value, "p": p})

    def mean_statistic(x, y):
        return float(np.mean([eaf_difference([s[:, list(pr)] for s in x],
                                             [s[:, list(pr)] for s in y])[2]
                              for pr in projections]))

    eaf_p, labelings = permutation_p(norm_a, norm_b, mean_statistic)
    a12 = vargha_delaney_a12(hv_a, hv_b)
    return {"low": low, "high": high, "hypervolume_a": hv_a, "hypervolume_b": hv_b,
            "mann_whitney_u": float(test.statistic), "mann_whitney_p": float(test.pvalue),
            "a12": a12, "epsilon_ab": eps_ab, "epsilon_ba": eps_ba,
            "dominated_share_a": dominated_share(pooled_a, pooled_b),
            "dominated_share_b": dominated_share(pooled_b, pooled_a),
            "pooled_sizes": (len(pooled_a), len(pooled_b)),
            "projections": [(objectives[i], objectives[j]) for i, j in projections],
            "eaf": eaf, "eaf_statistic": mean_statistic(norm_a, norm_b), "eaf_p": eaf_p,
            "labelings": labelings,
            "verdict": math.nan if empty else verdict(a12, eps_ab, eps_ba)}


def _base_attrs(title, function):
    import lsbg

    return {"Conventions": "CF-1.11", "title": title,
            "source": f"lsbg {lsbg.__version__} (lsbg.optimise.fronts.{function})",
            "lsbg_version": lsbg.__version__}


def converged_front_dataset(result, objectives, attrs=None):
    """:func:`converged_front` as a CF dataset on ``member``.

    Parameters
    ----------
    result : dict
        :func:`converged_front`.
    objectives : sequence of str
    attrs : dict, optional
        Further attributes (the design, the command line).

    Returns
    -------
    xarray.Dataset
        ``seed``, ``individual``, ``search_<objective>`` and ``<objective>`` (converged)
        per member, ``edge_load`` and ``kept``; attributes ``objectives``, ``seeds``,
        ``positions``.
    """
    import xarray as xr

    dims = ("member",)
    data = {"seed": (dims, result["seed"], {"units": "1", "long_name": "seed of its search"}),
            "individual": (dims, result["individual"], {
                "units": "1", "long_name": "its individual in that search's front dataset"}),
            "edge_load": (dims, result["edge_load"], {
                "units": "1", "long_name": "edge load constraint at the converged positions "
                                           "(feasible at <= 0)"}),
            "kept": (dims, result["kept"].astype(np.int8), {
                "units": "1", "long_name": "1 where feasible at the converged positions and "
                                           "on its seed's non-dominated set"})}
    for name in objectives:
        unit, text = QUANTITIES[name]
        data[name] = (dims, result["converged"][name], {
            "units": unit, "long_name": f"{text}, at the converged positions"})
        data[f"search_{name}"] = (dims, result["search"][name], {
            "units": unit, "long_name": f"{text}, at the search's positions"})
    base = {**_base_attrs("A trace's fronts at converged positions", "converged_front"),
            "objectives": " ".join(objectives),
            "seeds": " ".join(map(str, result["seeds"])), "positions": result["positions"]}
    base.update(attrs or {})
    return xr.Dataset(data, coords={"member": ("member", np.arange(result["seed"].size), {
        "units": "1", "long_name": "front member, every seed's"})}, attrs=base)


def seed_sets(dataset):
    """Each seed's converged non-dominated set of a :func:`converged_front_dataset`:
    ``[(n_k, m) array in the objectives' units]`` in the order of its ``seeds``."""
    objectives = dataset.attrs["objectives"].split()
    table = np.column_stack([dataset[n].values for n in objectives]) if dataset.sizes[
        "member"] else np.zeros((0, len(objectives)))
    kept = dataset["kept"].values == 1
    return [table[kept & (dataset["seed"].values == int(s))]
            for s in dataset.attrs["seeds"].split()]


def trace_fronts_dataset(stats, first, second, attrs=None):
    """:func:`trace_statistics` as a CF dataset.

    Parameters
    ----------
    stats : dict
        :func:`trace_statistics`.
    first, second : xarray.Dataset
        The two traces' :func:`converged_front_dataset` (the LSBG's first).
    attrs : dict, optional

    Returns
    -------
    xarray.Dataset
    """
    import xarray as xr

    objectives = first.attrs["objectives"].split()
    traces = [str(d.attrs["design_trace"]) for d in (first, second)]
    seeds = [list(map(int, d.attrs["seeds"].split())) for d in (first, second)]
    runs = max(map(len, seeds))
    seed_table = np.full((2, runs), -1)
    hv = np.full((2, runs), np.nan)
    members = np.zeros((2, runs), int)
    for k, (d, key) in enumerate(((first, "hypervolume_a"), (second, "hypervolume_b"))):
        seed_table[k, :len(seeds[k])] = seeds[k]
        hv[k, :len(seeds[k])] = stats[key]
        members[k, :len(seeds[k])] = [len(s) for s in seed_sets(d)]
    one = "1"
    data = {"seed": (("trace", "run"), seed_table, {"units": one, "long_name": "seed of the "
                                                    "search (-1: none)"}),
            "front_members": (("trace", "run"), members, {
                "units": one, "long_name": "members of its converged non-dominated set"}),
            "hypervolume": (("trace", "run"), hv, {
                "units": one, "long_name": f"hypervolume of the seed's converged front in the "
                                           f"common box, reference point {REFERENCE} in every "
                                           f"normalised objective"}),
            "hypervolume_median": (("trace",), np.nanmedian(hv, axis=1), {
                "units": one, "long_name": "median over the seeds of the hypervolume"}),
            "hypervolume_spread": (("trace",), np.nanmax(hv, axis=1) - np.nanmin(hv, axis=1), {
                "units": one, "long_name": "largest less least hypervolume over the seeds"}),
            "pooled_front_members": (("trace",), np.array(stats["pooled_sizes"]), {
                "units": one, "long_name": "members of the non-dominated set of all its seeds' "
                                           "converged fronts"}),
            "dominated_share": (("trace",), np.array([stats["dominated_share_a"],
                                                      stats["dominated_share_b"]]), {
                "units": one, "long_name": "share of the trace's pooled front that a member of "
                                           "the other trace's dominates"}),
            "epsilon_additive": (("trace",), np.array([stats["epsilon_ab"], stats["epsilon_ba"]]),
                                 {"units": one, "long_name": "additive epsilon-indicator of the "
                                  "trace's pooled front against the other's, normalised: the "
                                  "least shift down by which it weakly dominates the other"}),
            "mann_whitney_u": ((), stats["mann_whitney_u"], {
                "units": one, "long_name": "Mann-Whitney U of the first trace's hypervolumes "
                                           "against the second's"}),
            "mann_whitney_p": ((), stats["mann_whitney_p"], {
                "units": one, "long_name": "its exact two-sided p"}),
            "a12": ((), stats["a12"], {
                "units": one, "long_name": "Vargha-Delaney A12: P(first trace's hypervolume > "
                                           "second's) + P(=) / 2 over the seed pairs"}),
            "eaf_difference_statistic": (("projection",), np.array(
                [e["statistic"] for e in stats["eaf"]]), {
                "units": one, "long_name": "area-weighted mean |EAF difference| over the "
                                           f"projection's box [0, {REFERENCE}]^2"}),
            "eaf_difference_p": (("projection",), np.array([e["p"] for e in stats["eaf"]]), {
                "units": one, "long_name": "permutation p of that statistic over the seeds' "
                                           "trace labels"}),
            "eaf_difference_mean_statistic": ((), stats["eaf_statistic"], {
                "units": one, "long_name": "the statistic's mean over the projections"}),
            "eaf_difference_mean_p": ((), stats["eaf_p"], {
                "units": one, "long_name": "its permutation p over the seeds' trace labels"}),
            "verdict": ((), float(stats["verdict"]), {
                "units": one, "long_name": "docs/optimise.md's rule: 1 the first trace better, "
                                           "-1 the second, 0 a tie, NaN no verdict"})}
    largest = max([len(e["difference"]) for e in stats["eaf"]] + [1])
    rectangles = np.full((len(stats["eaf"]), largest, 4), np.nan)
    difference = np.full((len(stats["eaf"]), largest), np.nan)
    for k, e in enumerate(stats["eaf"]):
        rectangles[k, :len(e["difference"])] = e["rectangles"]
        difference[k, :len(e["difference"])] = e["difference"]
    data["eaf_rectangle"] = (("projection", "rectangle", "bound"), rectangles, {
        "units": one, "long_name": "rectangles of constant EAF difference, normalised "
                                   "(NaN: padding)"})
    data["eaf_difference"] = (("projection", "rectangle"), difference, {
        "units": one, "long_name": "share of the first trace's seeds attaining the rectangle "
                                   "less the second's"})
    for k, name in enumerate(objectives):
        unit = QUANTITIES[name][0]
        for corner, value in (("low", stats["low"][k]), ("high", stats["high"][k])):
            data[f"box_{corner}_{name}"] = ((), float(value), {
                "units": unit, "long_name": f"the common box's {corner} {name}: normalised 0 "
                                            f"at low, 1 at high"})
    n = [len(s) for s in seeds]
    least_mw = 2.0 / math.comb(sum(n), n[0])
    base = {**_base_attrs("Trace against trace: the fronts compared on converged objectives "
                          "(docs/optimise.md)", "trace_statistics"),
            "objectives": " ".join(objectives), "traces": " ".join(traces),
            "reference_point": REFERENCE,
            "normalisation": "each objective (f - low) / (high - low), low and high its least "
                             "and largest over every converged front of both traces",
            "verdict_rule": f"the first trace better where a12 >= {LARGE_EFFECT} and its "
                            f"epsilon_additive is below the other's; the second where a12 <= "
                            f"{1 - LARGE_EFFECT:.2f} and its epsilon_additive is below; a tie "
                            f"otherwise",
            "verdict_text": VERDICTS.get(stats["verdict"], "no verdict: a trace has no "
                                                          "feasible front member"),
            "labelings": int(stats["labelings"]),
            "least_attainable_p": least_mw,
            "least_attainable_p_note": (
                f"{n[0]} against {n[1]} seeds: {stats['labelings']} labelings, so the least "
                f"two-sided exact Mann-Whitney p and the least permutation p of the EAF "
                f"statistic (the same for a labeling and its swap) are {least_mw:.3g}"),
            "indicative": int(min(n) < 5),
            "positions": " ".join(str(d.attrs["positions"]) for d in (first, second))}
    # the cell (docs/optimise.md): the design point of the second trace's fronts
    for key in ("spiral_angle_deg", "cutter_radius_mm"):
        if f"design_{key}" in second.attrs:
            base[f"cell_{key}"] = float(second.attrs[f"design_{key}"])
    base.update(attrs or {})
    labels = [f"{a} / {b}" for a, b in stats["projections"]]
    return xr.Dataset(data, coords={
        "trace": ("trace", traces, {"units": one, "long_name": "tooth trace"}),
        "run": ("run", np.arange(runs), {"units": one, "long_name": "search of the trace"}),
        "projection": ("projection", labels, {"units": one,
                                              "long_name": "2-D projection: x / y objective"}),
        "bound": ("bound", ["x_low", "y_low", "x_high", "y_high"], {
            "units": one, "long_name": "corner coordinate of a rectangle"}),
        "rectangle": ("rectangle", np.arange(largest), {
            "units": one, "long_name": "rectangle of the EAF difference"})}, attrs=base)
