"""Each type at its best ease-off, in the reports: the fronts, the released designs, the seeds.

Read from the fronts ``lsbg optimise`` writes (:func:`lsbg.optimise.dataset.front_dataset`):
the two seeds' searches and hypervolumes (the search's convergence); and from the releases ``lsbg release`` writes
(:func:`lsbg.optimise.release.release_dataset`): the shared (practice) design, the best
candidate under FE and the released design side by side with every figure under both
models at converged positions, the release's verdict and the ranks under the
alternative rules.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lsbg.aggregate.runs import TYPE_ORDER, gear_type
from lsbg.gear.design import TRACE_LABELS

__all__ = ["read_fronts", "study_seed", "study_fronts", "seed_table", "COEFFICIENTS",
           "read_releases", "release_words",
           "release_table", "release_text", "release_efficiency_text", "trace_fronts_table",
           "trace_fronts_text", "cell_name", "trace_cells_table", "trace_level_text"]

#: The ease-off coefficients shown [um].
COEFFICIENTS = ("lengthwise_crowning", "profile_crowning", "bias", "spiral_angle_correction",
                "pressure_angle_correction", "pinion_tip_relief", "gear_tip_relief")


def read_fronts(paths):
    """``{(gear type, seed): front}`` of the fronts' files, in type and seed order."""
    import xarray as xr

    from lsbg.files import as_path_list

    fronts = {}
    for path in as_path_list(paths):
        ds = xr.load_dataset(path)
        fronts[(gear_type(ds), int(ds.attrs["seed"]))] = ds
    return dict(sorted(fronts.items(), key=lambda kv: (TYPE_ORDER.index(kv[0][0]), kv[0][1])))


def study_seed(fronts):
    """The study's seed: the least of the fronts' (the next one only checks it)."""
    return min(seed for _, seed in fronts)


def study_fronts(fronts):
    """``{gear type: front}`` of the study's seed (:func:`study_seed`), in type order."""
    seed = study_seed(fronts)
    return {kind: ds for (kind, s), ds in fronts.items() if s == seed}


def seed_table(fronts):
    """Each type's searches: evaluations, time, feasible front, hypervolume, seeds' agreement.

    Returns
    -------
    pandas.DataFrame
        Per type and seed; ``hypervolume vs the study's seed [%]`` the relative
        difference of each seed's final hypervolume from the study's seed's.
    """
    base = {kind: float(ds.attrs["final_hypervolume"])
            for kind, ds in study_fronts(fronts).items()}
    rows = []
    for (kind, s), ds in fronts.items():
        a = ds.attrs
        hv = float(a["final_hypervolume"])
        rows.append({"type": kind, "seed": s, "designs evaluated": int(a["evaluations"]),
                     "time [s]": float(a["run_seconds"]),
                     "feasible on the front": int(a["front_individuals"]),
                     "hypervolume": hv,
                     "hypervolume vs the study's seed [%]":
                         100 * (hv - base[kind]) / base[kind] if base.get(kind) else np.nan})
    return pd.DataFrame(rows)


def read_releases(paths):
    """``{gear type: release}`` of the releases' files (lsbg release), in type order."""
    import xarray as xr

    from lsbg.files import as_path_list

    releases = {}
    for path in as_path_list(paths):
        ds = xr.load_dataset(path)
        releases[gear_type(ds)] = ds
    return {kind: releases[kind] for kind in TYPE_ORDER if kind in releases}


def _best_candidate(ds):
    """The FE-evaluated candidate of least score (-1 for none)."""
    score = ds["score"].values
    return int(np.nanargmin(score)) if np.any(np.isfinite(score)) else -1


def release_words(releases):
    """How each type's ease-off was released, in words (Markdown, no full stop)."""
    first = next(iter(releases.values()))
    criteria = ", ".join(first.attrs["release_criteria"].split()).replace("_", " ")
    kept = [kind for kind, ds in releases.items() if ds.attrs["chosen"] < 0]
    text = (f"the release rule (under the FE loaded TCA at converged positions no worse than "
            f"the shared design in {criteria} within "
            f"{100 * first.attrs['release_tolerance']:g} % and better in one; the least "
            f"weighted sum in engineering units among the released)")
    if kept:
        text += f"; {' and '.join(kept)}: none released, the shared ease-off stays"
    return text


def release_table(releases):
    """The shared (practice) design, the best candidate under FE and the released one.

    Parameters
    ----------
    releases : dict
        :func:`read_releases`.

    Returns
    -------
    pandas.DataFrame
        One row per ease-off coefficient [µm] and per figure under each model
        (``model``: uniform bed or FE, both at converged positions; the pattern's
        movement from the unloaded TCA); per type the columns ``shared``, ``best
        candidate`` (the least weighted sum under FE, released or not) and
        ``released`` (the shared design's values where none is).
    """
    from lsbg.optimise.objectives import QUANTITIES
    from lsbg.optimise.verdict import CONVERGED_QUANTITIES, FE_QUANTITIES

    rows = {}

    def put(key, kind, shared, best, released):
        row = rows.setdefault(key, {})
        row[f"{kind} shared"], row[f"{kind} best candidate"] = shared, best
        row[f"{kind} released"] = released

    for kind, ds in releases.items():
        k, best = int(ds.attrs["chosen"]), _best_candidate(ds)

        def of(name, index):
            return float(ds[name].values[index]) if index >= 0 else np.nan

        for name in COEFFICIENTS:
            # (a coefficient left out of the shared design's section is 0)
            shared = float(ds.attrs.get(f"reference_flank_modification_{name}_um", 0.0))
            put(("ease-off", name.replace("_", " "), "µm"), kind, shared, of(name, best),
                of(name, k) if k >= 0 else shared)
        for model, names, words in (("uniform", CONVERGED_QUANTITIES, "uniform bed"),
                                    ("fe", tuple(FE_QUANTITIES), "FE")):
            for name in names:
                unit = (QUANTITIES if model == "uniform" else FE_QUANTITIES)[name][0]
                shared = float(ds[f"reference_{model}_{name}"])
                put((words, name.replace("_", " "), unit), kind, shared,
                    of(f"{model}_{name}", best), of(f"{model}_{name}", k) if k >= 0 else shared)
        shared = float(ds["reference_verdict_pattern_movement"])
        put(("unloaded TCA", "pattern movement", "mm"), kind, shared,
            of("verdict_pattern_movement", best),
            of("verdict_pattern_movement", k) if k >= 0 else shared)
    table = pd.DataFrame([{"model": m, "quantity": q, "unit": u, **values}
                          for (m, q, u), values in rows.items()])
    order = ["model", "quantity", "unit"] + [f"{t} {w}" for t in TYPE_ORDER for w in (
        "shared", "best candidate", "released")]
    return table[[c for c in order if c in table.columns]]


def release_text(releases):
    """Each type's release in one paragraph (Markdown): what was released or kept, the
    converged positions, the ranks under the alternative rules and each seed's answer."""
    parts = []
    for kind, ds in releases.items():
        a, k = ds.attrs, int(ds.attrs["chosen"])
        criteria = a["release_criteria"].split()
        where = (f"Uniform bed at {a['uniform_positions']} positions, FE at "
                 f"{a['fe_aligned_positions']} aligned and {a['fe_corners_positions']} at the "
                 f"corners (each the least whose doubling changes every figure by less than "
                 f"{100 * a['release_convergence']:g} %"
                 + ("" if a["uniform_converged"] and a["fe_aligned_converged"]
                    and a["fe_corners_converged"] else "; not reached within "
                    f"{a['release_largest_positions']} positions") + ")")
        shared = ", ".join(f"{n.replace('_', ' ')} {float(ds[f'reference_fe_{n}']):.4g} "
                           f"{ds[f'reference_fe_{n}'].attrs['units'].replace('urad', 'µrad')}"
                           for n in criteria)
        seeds = a["front_seeds"].split()
        answers = ["shared kept" if a[f"seed{s}_chosen"] < 0 else
                   f"candidate {a[f'seed{s}_chosen']}" for s in seeds]
        seed_words = ", ".join(f"seed {s}: {w}" for s, w in zip(seeds, answers))
        if k < 0:
            best = _best_candidate(ds)
            worse = "" if best < 0 else " (its best candidate under FE: " + ", ".join(
                f"{n.replace('_', ' ')} {float(ds[f'fe_{n}'].values[best]):.4g}"
                for n in criteria) + ")"
            parts.append(f"**{kind}**: none of its {a['fe_candidates_evaluated']} candidates "
                         f"evaluated under FE is no worse than the shared design "
                         f"({shared}){worse}: **the shared ease-off stays**. Each front "
                         f"alone: {seed_words}. {where}.")
            continue
        mine = ", ".join(f"{n.replace('_', ' ')} {float(ds[f'fe_{n}'].values[k]):.4g}"
                         for n in criteria)
        ranks = ", ".join(f"{a[f'rank_under_{r}']} under the {r} rule" for r in
                          ("lexicographic", "knee") if f"rank_under_{r}" in a)
        parts.append(f"**{kind}**: released (seed {int(ds['front_seed'].values[k])}), under FE "
                     f"{mine} against the shared design's {shared}; of "
                     f"{a['released_candidates']} released it ranks {ranks}; each front "
                     f"alone: {seed_words}; its FE figures change by "
                     f"{100 * a['chosen_fe_change']:.2g} % at twice the positions. {where}.")
    return "\n\n".join(parts)


def release_efficiency_text(releases):
    """The mesh efficiencies of the shared and the released designs (Markdown), at
    converged positions on the uniform bed."""
    parts = []
    for kind, ds in releases.items():
        k, shared = int(ds.attrs["chosen"]), 100 - float(ds["reference_uniform_mesh_loss"])
        parts.append(f"{kind} {shared:.2f} % (it keeps the shared ease-off)" if k < 0 else
                     f"{kind} {shared:.2f} % with the shared ease-off, "
                     f"{100 - float(ds['uniform_mesh_loss'].values[k]):.2f} % with its own")
    return ("**Mesh efficiency** (sliding friction of the loaded TCA's line loads on the "
            "uniform bed, at converged positions): " + "; ".join(parts) + ".") if parts else ""


def trace_fronts_table(ds):
    """The trace-against-trace statistics (:func:`lsbg.optimise.fronts.trace_fronts_dataset`),
    one row each, a column per trace (the pair's statistics in the first's column, the
    second's saying so).

    Returns
    -------
    pandas.DataFrame
        ``statistic`` and one column per gear type; the hypervolumes per seed as text.
    """
    kinds = [TRACE_LABELS.get(str(t), str(t)) for t in ds["trace"].values]
    pair_cell = f"(of the pair: under {kinds[0]})"

    def per_trace(name, fmt="{:.3g}"):
        # a dash where a trace has no front member to say it of
        return [fmt.format(float(v)) if np.isfinite(v) else "–" for v in ds[name].values]

    seeds = [", ".join(f"{h:.3g} (seed {int(s)})" for h, s in zip(ds["hypervolume"].values[k],
                                                                  ds["seed"].values[k]) if s >= 0)
             for k in range(len(kinds))]
    rows = [("hypervolume of each seed's converged front [-]", *seeds),
            ("hypervolume, median [-]", *per_trace("hypervolume_median")),
            ("hypervolume, spread (largest less least) [-]", *per_trace("hypervolume_spread")),
            ("members of the pooled converged front", *per_trace("pooled_front_members", "{:.0f}")),
            ("share of its pooled front the other trace dominates", *per_trace(
                "dominated_share", "{:.0%}")),
            ("additive epsilon-indicator against the other's front [-]",
             *per_trace("epsilon_additive")),
            ("Vargha-Delaney A12 of the hypervolumes (first against second)",
             f"{float(ds['a12']):.3g}", pair_cell),
            ("Mann-Whitney U, exact two-sided p", f"U = {float(ds['mann_whitney_u']):.3g}, "
             f"p = {float(ds['mann_whitney_p']):.3g}", pair_cell),
            ("EAF difference, mean over the 2-D projections, permutation p",
             f"{float(ds['eaf_difference_mean_statistic']):.3g}, "
             f"p = {float(ds['eaf_difference_mean_p']):.3g}", pair_cell),
            ("verdict (docs/optimise.md)", ds.attrs["verdict_text"]
             + (" (indicative)" if ds.attrs["indicative"] else ""), pair_cell)]
    rows += [(f"EAF difference, {p.replace('_', ' ')}: mean |difference|, p",
              f"{s:.3g}, p = {q:.2g}", pair_cell)
             for p, s, q in zip(ds["projection"].values, ds["eaf_difference_statistic"].values,
                                ds["eaf_difference_p"].values)]
    return pd.DataFrame(rows, columns=["statistic", *kinds])


def trace_fronts_text(ds):
    """The trace-level answer in words, with its limits (the seeds, the labelings)."""
    kinds = [TRACE_LABELS.get(str(t), str(t)) for t in ds["trace"].values]
    seeds = [int((ds["seed"].values[k] >= 0).sum()) for k in range(len(kinds))]
    members = [int(v) for v in ds["pooled_front_members"].values]
    hv = ds["hypervolume_median"].values
    eps = ds["epsilon_additive"].values
    if not all(members):
        empty = " and ".join(k for k, m in zip(kinds, members) if not m)
        return (f"**Trace against trace:** no verdict: no search of the {empty} kept a feasible "
                f"front member at the converged positions ({seeds[0]} against {seeds[1]} seeds; "
                f"a budget this small finds none).")
    return (f"**Trace against trace** ({seeds[0]} against {seeds[1]} seeds, each front at "
            f"{ds.attrs['positions'].split()[0]} positions): median hypervolume {hv[0]:.3g} "
            f"({kinds[0]}) against {hv[1]:.3g} ({kinds[1]}), A12 {float(ds['a12']):.2f}; the "
            f"additive epsilon-indicator {eps[0]:.3g} ({kinds[0]} to cover {kinds[1]}) against "
            f"{eps[1]:.3g}. By the rule of docs/optimise.md: {ds.attrs['verdict_text']}."
            + (f" Indicative only: {ds.attrs['least_attainable_p_note']}."
               if ds.attrs["indicative"] else ""))


def cell_name(ds):
    """A cell of the trace study in words: its spiral angle [deg] and the SBG's cutter
    radius [mm] (the attributes ``cell_*`` of a trace-fronts dataset), else "?"."""
    angle = ds.attrs.get("cell_spiral_angle_deg")
    cutter = ds.attrs.get("cell_cutter_radius_mm")
    if angle is None:
        return "?"
    return f"{float(angle):g} deg" + ("" if cutter is None else f", r_c0 {float(cutter):g} mm")


def trace_cells_table(datasets):
    """The trace study's cells (lsbg trace-fronts, one dataset per cell), a row each.

    Parameters
    ----------
    datasets : list of xarray.Dataset
        The cells' trace-fronts datasets, the paper's first.

    Returns
    -------
    pandas.DataFrame
        ``cell`` (spiral angle [deg], the SBG's cutter radius [mm]), the median
        hypervolume of each trace [-], A12 [-], the additive epsilon-indicator both ways
        [-] and the cell's verdict.
    """
    rows = []
    for ds in datasets:
        hv = ds["hypervolume_median"].values
        eps = ds["epsilon_additive"].values
        rows.append({"cell": cell_name(ds), "hypervolume median, LSBG": float(hv[0]),
                     "hypervolume median, SBG": float(hv[1]), "A12": float(ds["a12"]),
                     "epsilon LSBG to SBG": float(eps[0]), "epsilon SBG to LSBG": float(eps[1]),
                     "verdict": ds.attrs["verdict_text"]
                     + (" (indicative)" if ds.attrs["indicative"] else "")})
    return pd.DataFrame(rows)


def trace_level_text(datasets):
    """The trace-level answer over the cells (:func:`lsbg.optimise.cells.trace_level_verdict`)
    in words."""
    from lsbg.optimise.cells import trace_level_verdict

    answer = trace_level_verdict({f"{k}: {cell_name(ds)}": ds for k, ds in enumerate(datasets)})
    indicative = any(ds.attrs["indicative"] for ds in datasets)
    return (f"**The trace over every cell** ({answer['cells']} cells: spiral angles and the "
            f"SBG's cutters; a side only where every cell gives it, docs/optimise.md): "
            f"{answer['text']}." + (" Indicative only: fewer than 5 seeds per trace."
                                    if indicative else ""))
