"""``lsbg matched-pairs``' work: every matched design answered, the statistics, the dataset.

For each pair of :func:`lsbg.matched.run.matched_designs` and each of its two
designs (its ease-off from its search's front, on its trace's geometry and the
aligned pair): the proxy's stds at both boundaries, the full runs' for the
closest ``optimise.matched.full_runs`` pairs (the compiled engine, the line model on
the uniform bed, the ``simulation`` and ``driveline`` sections), and the FE
figures of the aligned pair over the load range (:func:`lsbg.optimise.verdict.fe_group_values`
at the release's aligned FE positions). The ISO 10300 rating takes no ease-off:
it is each trace's design point's, the same for every design of a trace, and
is not repeated here (results/practice/rating/).
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from lsbg.matched.run import ESTIMATES, design_answers, log_ratios, ratio_statistics
from lsbg.matched.stability import BOUNDARIES, STABILITY_QUANTITIES

__all__ = ["RATING_FIGURES", "answer_pairs"]

#: The rating's figures the dataset carries per trace (pinion, gear where per member).
RATING_FIGURES = ("contact_safety", "bending_safety", "contact_stress", "root_stress")


def answer_pairs(settings, geometry_dirs, releases, compliance_files, matched, converged,
                 fronts, log=None, ratings=None):
    """Answer every matched pair and build the dataset.

    Parameters
    ----------
    settings : dict
        The configuration (:func:`lsbg.config.resolve_config`).
    geometry_dirs, releases, compliance_files : sequence
        Each trace's geometry directory, release dataset and compliance file (the
        LSBG's first).
    matched : dict
        :func:`lsbg.matched.run.matched_designs`.
    converged : sequence of xarray.Dataset
        The two traces' converged fronts.
    fronts : sequence of xarray.Dataset
        Every search's front of both traces (``design_trace`` and ``seed`` attributes).
    log : callable, optional
    ratings : sequence of xarray.Dataset, optional
        Each trace's ISO 10300 rating at its design point (``lsbg rate``): its
        :data:`RATING_FIGURES` go into the attributes (the rating takes no ease-off).

    Returns
    -------
    xarray.Dataset
        :func:`lsbg.matched.dataset.matched_pairs_dataset`.
    """
    from lsbg.contact import ContactParameters
    from lsbg.dynamics import SimulationSettings, load_model
    from lsbg.gear.geometry import GearPair
    from lsbg.matched.dataset import matched_pairs_dataset
    from lsbg.optimise.checks import run_settings
    from lsbg.optimise.choice import modification_of
    from lsbg.optimise.verdict import STATE_FIGURES, evaluator_factory, fe_group_values
    from lsbg.solid.directory import read_design
    from lsbg.tca.misalignment import Misalignment
    from lsbg.tca.separation import RealFlanks
    from lsbg.tooth.config import compliance_for_design, tooth_from_config

    log = log or (lambda text: None)
    started = time.perf_counter()
    section = settings["optimise"]["matched"]
    member = matched["member"]
    n = member.shape[0]
    full_pairs = min(int(section["full_runs"]), n)
    # the closest pairs get the full runs
    full = np.zeros(n, bool)
    full[np.argsort(matched["distance"], kind="stable")[:full_pairs]] = True
    by_seed = {(str(f.attrs["design_trace"]), int(f.attrs["seed"])): f for f in fronts}
    traces = [str(d.attrs["design_trace"]) for d in converged]
    params = dataclasses.replace(ContactParameters.from_config(settings["contact"]),
                                 model="line", compliance="uniform")
    simulations = {b: SimulationSettings.from_config({**settings["simulation"], "boundary": b},
                                                     engine="compiled") for b in BOUNDARIES}
    start = float(settings["statistics"]["steady_state_after_s"])
    load, speed = simulations[BOUNDARIES[0]].load_torque, simulations[BOUNDARIES[0]].pinion_speed
    driveline = dict(settings.get("driveline", {}))
    material, mesh, _ = tooth_from_config(settings["tooth"])
    std = np.full((n, 2, len(ESTIMATES), len(BOUNDARIES), len(STABILITY_QUANTITIES)), np.nan)
    fe_names = STATE_FIGURES["aligned"]
    fe = {name: np.full((n, 2), np.nan) for name in fe_names}
    for t, trace in enumerate(traces):
        if not n:
            break
        design = read_design(geometry_dirs[t])
        pair = GearPair(design)
        evaluation = run_settings(settings, design)["evaluation"]
        evaluator_at = evaluator_factory(pair, evaluation)
        compliance, _ = compliance_for_design(pair, material, mesh, compliance_files[t])
        positions = int(releases[t].attrs["fe_aligned_positions"])
        for k in range(n):
            row = converged[t].isel(member=int(member[k, t]))
            front = by_seed[(trace, int(row["seed"]))]
            modification = modification_of(front, int(row["individual"]))
            flanks = RealFlanks(modification, Misalignment())

            def model_at(boundary, flanks=flanks):
                return load_model(geometry_dirs[t], params, flanks,
                                  driveline=driveline if boundary == "driveline" else None)

            def fe_at(modification=modification):
                values = fe_group_values(evaluator_at, compliance, [modification], positions,
                                         "aligned")
                return {name: float(v[0]) for name, v in values.items()}

            answer = design_answers(model_at, simulations, start, bool(full[k]), load, speed,
                                    fe_at)
            std[k, t] = answer["std"]
            for name in fe_names:
                fe[name][k, t] = answer["fe"][name]
            log(f"{trace} pair {k}: proxy {answer['std'][0].ravel().round(4).tolist()}"
                + (" (full runs too)" if full[k] else ""))
    ratios = log_ratios(std)  # (pairs, estimate, boundary, quantity)
    statistics = ratio_statistics(ratios)
    # the contact state and life over the pairs: log SBG / LSBG of each FE figure and of
    # the pattern's movement
    state = {name: values for name, values in fe.items()}
    if "pattern_movement" in converged[0].attrs["objectives"].split():
        state["pattern_movement"] = np.column_stack(
            [d["pattern_movement"].values[member[:, t]] for t, d in enumerate(converged)]) \
            if n else np.zeros((0, 2))
    state_statistics = {name: ratio_statistics(log_ratios(v)[:, None])
                        for name, v in state.items()}
    proxy_error = std[:, :, 0] / std[:, :, 1] - 1
    nothing = np.full((len(BOUNDARIES), len(STABILITY_QUANTITIES)), np.nan)
    with np.errstate(all="ignore"):
        worst = np.nanmax(np.abs(proxy_error), axis=(0, 1)) if full.any() else nothing
        # the proxy's error in the pair's answer: its log ratio less the full runs'
        worst_ratio = np.nanmax(np.abs(ratios[:, 0] - ratios[:, 1]), axis=0) if full.any() \
            else nothing
    fe_positions = " ".join(str(int(r.attrs["fe_aligned_positions"])) for r in releases)
    attrs = {"caliper": float(section["caliper"]), "pairs_sought": int(section["pairs"]),
             "enough_pairs": int(n >= int(section["pairs"])),
             "full_run_pairs": int(full_pairs),
             "full_run_pair_indices": " ".join(map(str, np.flatnonzero(full))),
             "indicative": int(n < int(section["pairs"]) or full_pairs < n),
             "indicative_note": (
                 "the proxy's statistics (estimate proxy) cover every pair; the full runs' "
                 "(estimate full) only the full_run_pair_indices: indicative where fewer "
                 "than all pairs, or fewer pairs than pairs_sought"),
             "rating_note": ("the ISO 10300 rating (lsbg.rating) takes no ease-off: it is "
                             "each trace's design point's (results/practice/rating/; the "
                             "attributes rating_<trace>_*, pinion and gear), the same for "
                             "every design of the trace"),
             "fe_note": (f"FE figures of the aligned pair over the load range at the "
                         f"releases' aligned FE positions ({fe_positions})"),
             "contact_state_note": ("pattern_movement: the largest movement of the bearing "
                                    "pattern's centre over the envelope's corners (unloaded "
                                    "TCA), as the searches' objective"),
             "proxy_error_max": " ".join(f"{b}/{q}={worst[i, j]:.4g}"
                                         for i, b in enumerate(BOUNDARIES)
                                         for j, q in enumerate(STABILITY_QUANTITIES)),
             "proxy_log_ratio_error_max": " ".join(
                 f"{b}/{q}={worst_ratio[i, j]:.4g}" for i, b in enumerate(BOUNDARIES)
                 for j, q in enumerate(STABILITY_QUANTITIES)),
             "steady_state_after_s": start, "run_seconds": time.perf_counter() - started}
    if ratings is not None:
        for t, rating in enumerate(ratings):
            for name in RATING_FIGURES:
                values = np.atleast_1d(rating[name].values)
                attrs[f"rating_{traces[t]}_{name}"] = " ".join(f"{v:.6g}" for v in values)
    return matched_pairs_dataset(matched, converged, std, fe, statistics, attrs,
                                 state_statistics)
