"""Tables of the tooth itself: the uniform bed of springs against the tooth's own compliance.

Built from the loaded TCAs of a design point (:func:`lsbg.tca.loaded.loaded_tca`,
the uniform bed) and the loaded TCAs with the FE compliance
(:func:`lsbg.tooth.analysis.fe_ltca`). Units are the datasets' (µrad, N/µm,
N/(mm·µm), MPa).

* :func:`compliance_table`: per gear type, the mesh stiffness, the loaded
  transmission error, the largest contact pressure and root stresses, uniform
  beside FE;
* :func:`fe_mesh_table`: the finite-element models behind them (elements,
  degrees of freedom, mesh size, material).
"""

from __future__ import annotations

import pandas as pd

from lsbg.aggregate.runs import TYPE_ORDER

__all__ = ["COMPLIANCE_FIGURES", "compliance_table", "fe_mesh_table"]

#: Loaded-TCA attribute -> (label, unit) of :func:`compliance_table`; the last
#: three exist only with the FE compliance.
COMPLIANCE_FIGURES = {
    "mesh_stiffness_mean_N_per_um": ("mesh stiffness, mean", "N/um"),
    "mesh_stiffness_per_face_width_N_per_mm_um": ("  per unit face width (c_γ)", "N/(mm um)"),
    "mesh_stiffness_variation_percent": ("  its variation over the mean", "%"),
    "transmission_error_peak_to_peak_urad": ("loaded transmission error, peak to peak", "urad"),
    "transmission_error_harmonic_1_urad": ("  its 1st mesh harmonic", "urad"),
    "max_contact_pressure_MPa": ("largest Hertz pressure over the cycle", "MPa"),
    "max_root_stress_pinion_MPa": ("largest root stress, pinion", "MPa"),
    "max_root_stress_gear_MPa": ("largest root stress, gear", "MPa"),
}


def compliance_table(uniform, fe) -> pd.DataFrame:
    """The uniform bed beside the tooth's own compliance, per gear type.

    Parameters
    ----------
    uniform, fe : dict
        ``{gear type: loaded-TCA dataset}``, the uniform bed's and the FE
        compliance's (gear types in either may be missing).

    Returns
    -------
    pandas.DataFrame
        Rows of :data:`COMPLIANCE_FIGURES`; columns ``figure``, ``unit`` and,
        per gear type, ``<type> uniform``, ``<type> FE`` and ``<type> FE /
        uniform`` (NaN where the uniform bed has no such figure).
    """
    rows = []
    types = [t for t in TYPE_ORDER if t in uniform or t in fe]
    for attr, (label, unit) in COMPLIANCE_FIGURES.items():
        row = {"figure": label, "unit": unit}
        for t in types:
            u = float(uniform[t].attrs.get(attr, float("nan"))) if t in uniform else float("nan")
            f = float(fe[t].attrs.get(attr, float("nan"))) if t in fe else float("nan")
            row[f"{t} uniform"], row[f"{t} FE"] = u, f
            row[f"{t} FE / uniform"] = f / u if u else float("nan")
        rows.append(row)
    return pd.DataFrame(rows)


def fe_mesh_table(compliances) -> pd.DataFrame:
    """The finite-element models of the compliances.

    Parameters
    ----------
    compliances : dict
        ``{gear type: dataset}``: a compliance
        (:func:`lsbg.tooth.compliance.tooth_compliance`) or a loaded TCA with
        it (:func:`lsbg.tooth.analysis.fe_ltca`, which carries its ``fe_*``
        and ``material_*`` attributes).

    Returns
    -------
    pandas.DataFrame
        Per gear type and member: nodes, elements, degrees of freedom, the
        element size on the teeth [mean normal modules], E [GPa], nu, and the
        solve's wall time [s].
    """
    rows = []
    for t in [t for t in TYPE_ORDER if t in compliances]:
        a = compliances[t].attrs
        for member in ("pinion", "gear"):
            rows.append({"gear type": t, "member": member,
                         "nodes": int(a[f"fe_nodes_{member}"]),
                         "elements": int(a[f"fe_elements_{member}"]),
                         "degrees of freedom": int(a[f"fe_dofs_{member}"]),
                         "element size [m_mn]": float(a["fe_tooth_size"]),
                         "E [GPa]": float(a["material_young_modulus"]) * 1e-9,
                         "ν": float(a["material_poisson_ratio"]),
                         "wall time [s]": float(a[f"fe_seconds_{member}"])})
    return pd.DataFrame(rows)
