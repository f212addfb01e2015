"""ISO 10300 at every design point of a sweep, with each point's own K_v: ``lsbg rate-sweep``.

The standard needs only the geometry and the load, so the sweep report's
service-life claim rates every design point of the study's summary table
(:func:`rating_by_angle`); :func:`rating_sweep_dataset` writes that table as a
dataset the report reads (:func:`lsbg.tables.rating.read_rating_sweep`).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

__all__ = ["rating_by_angle", "rating_sweep_dataset", "RATING_SWEEP_VARIABLES"]

#: Columns of :func:`rating_by_angle` after ``gear_type`` and ``spiral_angle``:
#: name -> (units, long name).
RATING_SWEEP_VARIABLES = {
    "K_v": ("1", "dynamic factor K_v (the point's line-model run, or 1)"),
    "contact_stress": ("MPa", "contact stress sigma_H (ISO 10300-2, method B1)"),
    "root_stress_pinion": ("MPa", "pinion's tooth root stress sigma_F (ISO 10300-3, method B1)"),
    "root_stress_gear": ("MPa", "gear's tooth root stress sigma_F (ISO 10300-3, method B1)"),
    "contact_safety": ("1", "safety factor S_H, the lesser of both members"),
    "bending_safety_pinion": ("1", "pinion's safety factor S_F"),
    "bending_safety_gear": ("1", "gear's safety factor S_F"),
    "rated_gear_torque_contact": ("N m", "gear torque at which S_H = 1"),
}


def rating_by_angle(config, summary, engine="compiled"):
    """ISO 10300 at every design point of a sweep, with each point's own K_v.

    The standard needs only the geometry and the load: every design point of
    the summary table is rated with the study's ``rating`` and ``tooth``
    sections at its load and speed, K_v from the point's line-model run (the
    summary table's ``dynamic_factor``; 1 where there is none, or the
    section's number).

    Parameters
    ----------
    config : dict
        The study's settings as validated (``results/config.yaml``): its
        ``design``, ``rating``, ``tooth`` and ``simulation`` sections.
    summary : pandas.DataFrame
        The summary table (:func:`lsbg.aggregate.summary.summary_table`): its design
        points (``trace``, ``spiral_angle_deg``) and dynamic factors.
    engine : str
        The engine of the line-model runs whose K_v is taken.

    Returns
    -------
    pandas.DataFrame
        Per gear type, trace and spiral angle [deg]: ``K_v``, ``contact_stress``,
        ``root_stress_pinion``, ``root_stress_gear`` [MPa],
        ``contact_safety``, ``bending_safety_pinion``, ``bending_safety_gear``,
        ``rated_gear_torque_contact`` [N m].
    """
    from lsbg.gear.design import TRACE_LABELS, GearPairDesign
    from lsbg.rating.config import rate_design

    simulation = config.get("simulation", {})
    load = float(simulation.get("load_torque_N_m", 1964.99))
    speed = math.radians(float(simulation.get("pinion_speed_deg_s", 7703)))
    factors = summary[(summary.contact_model == "line") & (summary.engine == engine)
                      & summary.dynamic_factor.notna()]
    rows = []
    points = summary[["trace", "spiral_angle_deg"]].drop_duplicates()
    for trace, angle in sorted(points.itertuples(index=False, name=None)):
        if trace not in TRACE_LABELS:
            continue
        design = GearPairDesign.from_config({**config["design"], "trace": trace,
                                             "spiral_angle_deg": float(angle)})
        kv = factors[(factors.trace == trace) & np.isclose(factors.spiral_angle_deg, angle)]
        kv = float(kv.dynamic_factor.iloc[0]) if len(kv) else None
        rating, _, _ = rate_design(design, config.get("rating", {}), config.get("tooth", {}),
                                   load, speed, kv)
        ratio = design.gear_teeth / design.pinion_teeth
        rows.append({"gear_type": TRACE_LABELS[trace], "trace": trace, "spiral_angle": float(angle),
                     "K_v": rating.factors["K_v"],
                     "contact_stress": rating.contact_stress / 1e6,
                     "root_stress_pinion": rating.root_stress[0] / 1e6,
                     "root_stress_gear": rating.root_stress[1] / 1e6,
                     "contact_safety": min(rating.contact_safety),
                     "bending_safety_pinion": rating.bending_safety[0],
                     "bending_safety_gear": rating.bending_safety[1],
                     "rated_gear_torque_contact": rating.rated_pinion_torque_contact * ratio})
    return pd.DataFrame(rows, columns=["gear_type", "trace", "spiral_angle",
                                       *RATING_SWEEP_VARIABLES])


def rating_sweep_dataset(table, engine, load, history=""):
    """:func:`rating_by_angle`'s table as a dataset, one row per design point.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`rating_by_angle`.
    engine : str
        The engine whose line-model runs gave K_v.
    load : float
        The load on the gear [N m].
    history : str
        The command that computes it.

    Returns
    -------
    xarray.Dataset
        Over dimension ``point``: ``gear_type`` (SBG, LSBG), ``trace``, ``spiral_angle``
        [degree] and :data:`RATING_SWEEP_VARIABLES` with their units;
        CF-1.11 attributes.
    """
    import xarray as xr

    import lsbg
    from lsbg.gear.design import TRACE_NAMES

    variables = {"gear_type": ("point", table["gear_type"].to_numpy(str),
                               {"long_name": "gear type (SBG: circular or face_milled, LSBG: "
                                             "logarithmic tooth trace)"}),
                 "trace": ("point", table["trace"].to_numpy(str),
                           {"long_name": "tooth trace (" + "; ".join(
                               f"{t}: {n}" for t, n in TRACE_NAMES.items()) + ")"}),
                 "spiral_angle": ("point", table["spiral_angle"].to_numpy(float),
                                  {"units": "degree", "long_name": "mean spiral angle"})}
    variables.update({name: ("point", table[name].to_numpy(float),
                             {"units": units, "long_name": text})
                      for name, (units, text) in RATING_SWEEP_VARIABLES.items()})
    attrs = {"Conventions": "CF-1.11",
             "title": "ISO 10300 (method B1) at every design point of the sweep",
             "source": f"lsbg {lsbg.__version__} (lsbg.experiments.rating_sweep)",
             "history": history, "lsbg_version": lsbg.__version__,
             "dynamic_factor_engine": engine, "load_torque_N_m": float(load)}
    return xr.Dataset(variables, attrs=attrs)
