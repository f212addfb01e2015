"""Each type at its best ease-off, in the reports: the fronts, the chosen designs, the seeds.

Read from the fronts ``lsbg optimise`` writes (:func:`lsbg.optimise.dataset.front_dataset`):
the chosen ease-off of each type beside the shared one with their objectives and
mesh efficiencies, and the two seeds' hypervolumes (the search's convergence).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lsbg.aggregate.runs import TYPE_ORDER, gear_type

__all__ = ["read_fronts", "study_seed", "study_fronts", "choice_text", "chosen_table",
           "seed_table", "efficiency_text", "COEFFICIENTS"]

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


def choice_text(fronts):
    """How the study's seed chose each type's design, in words (Markdown, no full stop).

    Parameters
    ----------
    fronts : dict
        :func:`read_fronts`.

    Returns
    -------
    str
        The rule and the members it chose from, e.g. "the knee rule among its
        front's designs whose loaded TE at the rated torque is below the shared
        ease-off's", naming a type whose front had none there (then chosen
        from the whole front) and a type for which none was chosen (its shared
        ease-off stands).
    """
    chosen = study_fronts(fronts)
    first = next(iter(chosen.values()))
    text = f"the {first.attrs['choice_rule']} rule"
    if first.attrs.get("choose_from", "front") != "below_shared":
        return text + " over its whole front"
    text += (" among its front's designs whose loaded TE at the rated torque is below the "
             "shared ease-off's")
    unchosen = [kind for kind, ds in chosen.items() if int(ds.attrs.get("chosen", 0)) < 0]
    missed = [kind for kind, ds in chosen.items() if kind not in unchosen
              and not ds.attrs.get("chosen_below_shared_transmission_error", 0)]
    notes = []
    if missed:
        notes.append(f"{' and '.join(missed)}: no such design passed, so chosen from the "
                     f"whole front")
    if unchosen:
        notes.append(f"{' and '.join(unchosen)}: no design of the front passed, so the shared "
                     f"ease-off stands")
    return text + (f" ({'; '.join(notes)})" if notes else "")


def chosen_table(fronts):
    """The shared ease-off and each type's chosen one, with their objectives.

    Parameters
    ----------
    fronts : dict
        :func:`read_fronts`.

    Returns
    -------
    pandas.DataFrame
        One row per ease-off coefficient [µm] and objective (and the loaded
        TE at the rated torque [µrad] and the mesh efficiency [%]); columns
        ``shared`` and, per type, its chosen design and the shared design's
        value at its own trace (a type with none chosen keeps the shared
        ease-off: its chosen values are the shared ones).
    """
    rows = {}
    for kind, ds in study_fronts(fronts).items():
        chosen = int(ds.attrs["chosen"])
        for name in COEFFICIENTS:
            row = rows.setdefault((name.replace("_", " "), "µm"), {})
            row["shared"] = float(ds.attrs.get(f"reference_flank_modification_{name}_um", 0.0))
            # none chosen (chosen < 0): the type keeps the shared ease-off
            row[f"{kind} chosen"] = (float(ds[name].values[chosen]) if chosen >= 0
                                     else row["shared"])
        # the loaded TE at the rated torque beside the objectives: what the check reads
        shown = dict.fromkeys((*ds.attrs["objectives"].split(), "rated_transmission_error",
                               "efficiency"))
        for name in (n for n in shown if n in ds):
            units = ds[name].attrs.get("units", "")
            row = rows.setdefault((ds[name].attrs.get("long_name", name), units), {})
            row[f"{kind} shared"] = float(ds[f"reference_{name}"])
            row[f"{kind} chosen"] = (float(ds[name].values[chosen]) if chosen >= 0
                                     else row[f"{kind} shared"])
    table = pd.DataFrame([{"quantity": q, "unit": u, **values}
                          for (q, u), values in rows.items()])
    order = ["quantity", "unit", "shared"] + [f"{t} {w}" for t in TYPE_ORDER
                                              for w in ("shared", "chosen")]
    return table[[c for c in order if c in table.columns]]


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


def efficiency_text(fronts):
    """The mesh efficiencies in one sentence: shared and chosen, per type (Markdown)."""
    parts = []
    for kind, ds in study_fronts(fronts).items():
        if "efficiency" not in ds:
            continue
        chosen = int(ds.attrs["chosen"])
        shared = float(ds["reference_efficiency"])
        if chosen < 0:  # no feasible design below the shared one: the shared ease-off stands
            parts.append(f"{kind} {shared:.2f} % (it keeps the shared ease-off)")
            continue
        best = float(ds["efficiency"].values[chosen])
        parts.append(f"{kind} {shared:.2f} % with the shared ease-off, {best:.2f} % with its "
                     f"own")
    if not parts:
        return ""
    from lsbg.optimise.friction import FRICTION_LAWS

    law = next(iter(fronts.values())).attrs.get("friction_law", "")
    return (f"**Mesh efficiency** (a comparison the paper did not make; sliding friction of "
            f"the loaded TCA's line loads, {FRICTION_LAWS.get(law, law)}): "
            + "; ".join(parts) + ".")
