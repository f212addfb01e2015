"""Tables and the plain statement of the contact state (crowned flanks, V-H maps).

From the unloaded TCAs (:func:`lsbg.tca.analysis.tooth_contact_analysis`) and
the V-H maps (:func:`lsbg.tca.vh_map.misalignment_map`) of the two gear
types: what the bearing pattern and the transmission error look like on the
crowned, aligned pair, how far they move per 0.1 mm of each displacement,
and which type moves less.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from lsbg.aggregate.runs import gear_type

__all__ = ["tca_table", "sensitivity_table", "pattern_movement",
           "movement_statement", "sensitivity_by_angle", "steadier_by_angle"]

#: Quantities of a V-H map summarised per 0.1 of each displacement, with their
#: words and units.
SENSITIVITIES = {
    "pattern_shift_lengthwise": ("pattern moves towards the heel", "mm"),
    "pattern_shift_profile": ("pattern moves towards the tip", "mm"),
    "transmission_error_unloaded_pp": ("unloaded TE peak to peak changes", "µrad"),
    "transmission_error_loaded_pp": ("loaded TE peak to peak changes", "µrad"),
}


def tca_table(tcas):
    """The crowned, aligned pair's contact per gear type.

    Parameters
    ----------
    tcas : dict
        {label: TCA dataset}.

    Returns
    -------
    pandas.DataFrame
        One row per label: unloaded TE peak to peak [µrad] and [arcsec], its
        closed-form design value [µrad], the pattern's length [mm] and share
        of the face width [%], its centre (cone distance, height) [mm], the
        mean contact ellipse's semi-axes [mm], the share of positions whose
        ellipse reaches an edge [%] and the least backlash [µrad].
    """
    rows = []
    for label, ds in tcas.items():
        a = ds.attrs
        rows.append({
            "gear_type": label,
            "transmission_error_pp_urad": a["transmission_error_peak_to_peak_urad"],
            "transmission_error_pp_arcsec": a["transmission_error_peak_to_peak_arcsec"],
            "designed_transmission_error_pp_urad": a["designed_transmission_error_peak_to_peak_urad"],
            "pattern_length_mm": a["pattern_length_mm"],
            "pattern_length_percent": 100 * a["pattern_length_per_face_width"],
            "pattern_centre_cone_distance_mm": a["pattern_centre_cone_distance_mm"],
            "pattern_centre_height_mm": a["pattern_centre_height_mm"],
            "ellipse_semi_major_mm": float(ds["ellipse_semi_major"].mean()),
            "ellipse_semi_minor_mm": float(ds["ellipse_semi_minor"].mean()),
            "edge_contact_percent": 100 * a["edge_contact_share"],
            "backlash_min_urad": a["backlash_min_urad"],
        })
    return pd.DataFrame(rows)


def _axes(ds):
    return ds.attrs["axes"].split()


def sensitivity_table(maps):
    """Change per 0.1 mm (0.1 deg) of each displacement, per gear type.

    Parameters
    ----------
    maps : dict
        {label: V-H map dataset}.

    Returns
    -------
    pandas.DataFrame
        Columns ``quantity``, ``unit``, ``displacement`` and one column per
        label; a row per quantity of :data:`SENSITIVITIES` and axis.
    """
    rows = []
    first = next(iter(maps.values()))
    for name, (words, unit) in SENSITIVITIES.items():
        for axis in _axes(first):
            row = {"quantity": words, "unit": f"{unit} per 0.1 {'deg' if axis == 'Sigma' else 'mm'}",
                   "displacement": axis}
            for label, ds in maps.items():
                row[label] = ds.attrs[f"{name}_per_0_1_{axis}"]
            rows.append(row)
    return pd.DataFrame(rows)


def pattern_movement(ds):
    """How far the bearing pattern's centre moves per 0.1 of each displacement [mm].

    The length of the (toe-heel, root-tip) movement per 0.1 mm (0.1 deg)
    along each axis of the map, and their root sum square.

    Returns
    -------
    dict
        {axis: movement [mm]} and ``"total"``.
    """
    out = {}
    for axis in _axes(ds):
        out[axis] = math.hypot(ds.attrs[f"pattern_shift_lengthwise_per_0_1_{axis}"],
                               ds.attrs[f"pattern_shift_profile_per_0_1_{axis}"])
    out["total"] = math.sqrt(sum(v * v for v in out.values()))
    return out


def movement_statement(maps, where=""):
    """One plain sentence: which type's pattern and TE move less under displacement.

    Parameters
    ----------
    maps : dict
        {label: V-H map dataset} of two gear types with the same crowning.
    where : str
        The design point and model it holds for, e.g. "at 35°".

    Returns
    -------
    str
        Markdown.
    """
    labels = list(maps)
    move = {label: pattern_movement(ds) for label, ds in maps.items()}
    steadier = min(labels, key=lambda t: move[t]["total"])
    other = [t for t in labels if t != steadier]
    axes = _axes(maps[labels[0]])
    parts = [f"{axis}: " + ", ".join(f"{t} {move[t][axis]:.2g} mm" for t in labels)
             for axis in axes]
    te = {t: math.hypot(*(ds.attrs[f"transmission_error_loaded_pp_per_0_1_{a}"] for a in axes))
          for t, ds in maps.items()}
    calmer_te = min(labels, key=te.get)
    others = ", ".join(f"{move[t]['total']:.2g} mm ({t})" for t in other)
    text = (f"Under displacement {where}, the **{steadier}**'s bearing pattern moves less: "
            f"{move[steadier]['total']:.2g} mm per 0.1 mm of displacement against {others} "
            f"(per axis: {'; '.join(parts)}).")
    if other:
        ratio = move[other[0]]["total"] / max(move[steadier]["total"], 1e-12)
        text += f" That is {ratio:.2g} times less movement."
    rest = ", ".join(f"{te[t]:.3g} µrad ({t})" for t in labels if t != calmer_te)
    text += (f" The loaded transmission error's peak to peak changes by {te[calmer_te]:.3g} µrad "
             f"per 0.1 mm for the **{calmer_te}** against {rest}.")
    return text


def sensitivity_by_angle(maps):
    """The V-H sensitivities of many design points, long form.

    Parameters
    ----------
    maps : iterable of xarray.Dataset
        V-H maps of any design points.

    Returns
    -------
    pandas.DataFrame
        Columns ``gear_type``, ``trace``, ``spiral_angle`` [deg], ``axis``, ``quantity``
        (a key of :data:`SENSITIVITIES`), ``value`` (per 0.1 mm or deg), and
        rows of ``quantity`` "pattern_movement" (:func:`pattern_movement`).
    """
    rows = []
    for ds in maps:
        base = {"gear_type": gear_type(ds), "trace": str(ds.attrs["design_trace"]),
                "spiral_angle": float(ds.attrs["design_spiral_angle_deg"])}
        for axis in _axes(ds):
            for name in SENSITIVITIES:
                rows.append({**base, "axis": axis, "quantity": name,
                             "value": ds.attrs[f"{name}_per_0_1_{axis}"]})
        for axis, value in pattern_movement(ds).items():
            rows.append({**base, "axis": axis, "quantity": "pattern_movement", "value": value})
    table = pd.DataFrame(rows)
    return table.sort_values(["quantity", "axis", "gear_type", "spiral_angle"],
                             ignore_index=True) if not table.empty else table


def steadier_by_angle(table, quantity="pattern_movement", axis="total"):
    """Per spiral angle, which type moves less, from :func:`sensitivity_by_angle`.

    Returns
    -------
    pandas.DataFrame
        Columns ``spiral_angle``, one per gear type, ``steadier``.
    """
    part = table[(table.quantity == quantity) & (table.axis == axis)]
    wide = part.pivot(index="spiral_angle", columns="gear_type", values="value")
    wide["steadier"] = np.where(wide.get("SBG", np.nan).abs() < wide.get("LSBG", np.nan).abs(),
                                "SBG", "LSBG")
    return wide.reset_index()
