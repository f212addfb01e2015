"""Tables of the verification report: engines agree, runs converge, the geometry is exact.

* :func:`engine_agreement`: each engine's statistics against the reference
  engine's (:data:`REFERENCE_ENGINES`);
* :func:`read_convergence` and :func:`convergence_table`: the statistics under
  halving the time step or tightening the tolerance (``lsbg convergence``);
* :func:`contact_resonance`: the contact mode's frequency and damping ratio
  from the contact law and the gear's inertia;
* :func:`pressure_angle_table` and :func:`conjugacy_errors`: the pressure
  angles along the face and the deviation of the flanks from conjugacy
  (:mod:`lsbg.gear.geometry`);
* :func:`setting_label`, :func:`convergence_display` and :func:`by_gear_type`:
  the tables as the verification report shows them (narrow; nothing computed).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from lsbg.gear.design import TRACE_LABELS
from lsbg.files import as_path_list
from lsbg.aggregate.runs import records_by_type, run_spiral_angle, steady
from lsbg.stats.samples import format_number

__all__ = [
    "REFERENCE_ENGINES", "engine_agreement", "contact_resonance", "read_convergence",
    "convergence_table", "pressure_angle_table", "conjugacy_errors", "setting_label",
    "CONVERGENCE_DISPLAY_COLUMNS", "convergence_display", "by_gear_type"
]


#: Engines in the order they serve as the reference of :func:`engine_agreement`
#: (the compiled DOP853 loop agrees with scipy's LSODA at rtol 1e-10 within
#: 1e-10, tests/test_dynamics.py).
REFERENCE_ENGINES = ("compiled", "scipy", "pybullet")


def engine_agreement(runs, start=0.2, quantities=("gear_speed", "tangential_force"),
                     reference=None, tolerance=0.03) -> pd.DataFrame:
    """Standard deviations of each engine against the reference engine's.

    Parameters
    ----------
    runs : sequence of xarray.Dataset
        Runs of one or more design points with several engines.
    start : float, default 0.2
        End of the transient [s].
    quantities : sequence of str
        Run variables to compare.
    reference : str, optional
        Engine the others are compared with; default, per design point, the
        first of :data:`REFERENCE_ENGINES` that ran there.
    tolerance : float, default 0.03
        Accepted relative difference of the standard deviations [-]
        (DESIGN.md §3: 3 %).

    Returns
    -------
    pandas.DataFrame
        Per design point, engine and quantity: ``std``, ``reference_std``,
        ``std_ratio`` (engine / reference), ``mean_difference_percent`` and
        ``within_tolerance`` (|ratio − 1| <= tolerance). Empty if no design
        point has a reference run and another one.
    """
    groups = {}
    for ds in runs:
        key = (ds.attrs["design_trace"], run_spiral_angle(ds))
        groups.setdefault(key, {})[ds.attrs["solver_engine"]] = ds
    rows = []
    for (trace, angle), engines in groups.items():
        chosen = reference or next((e for e in REFERENCE_ENGINES if e in engines), None)
        if chosen not in engines or len(engines) < 2:
            continue
        ref = engines[chosen]
        for engine, ds in engines.items():
            if engine == chosen:
                continue
            for quantity in quantities:
                x, y = steady(ds, quantity, start), steady(ref, quantity, start)
                ratio = x.std(ddof=1) / y.std(ddof=1)
                rows.append({"gear_type": TRACE_LABELS.get(trace, trace),
                             "spiral_angle_deg": angle, "engine": engine,
                             "reference": chosen, "quantity": quantity,
                             "std": float(x.std(ddof=1)), "reference_std": float(y.std(ddof=1)),
                             "std_ratio": float(ratio),
                             "mean_difference_percent": float(100 * (x.mean() - y.mean())
                                                              / abs(y.mean())),
                             "within_tolerance": bool(abs(ratio - 1.0) <= tolerance)})
    columns = ["gear_type", "spiral_angle_deg", "engine", "reference", "quantity", "std",
               "reference_std", "std_ratio", "mean_difference_percent", "within_tolerance"]
    return pd.DataFrame(rows, columns=columns)


def _contact_parameters(ds):
    """ContactParameters from a run's ``contact_*`` attributes (the paper's if absent)."""
    from lsbg.contact import ContactParameters

    return ContactParameters.from_dict({} if ds is None else ds.attrs, prefix="contact_")


def contact_resonance(geometry_dir, run=None, positions=12) -> dict:
    """Torsional resonance of the gear on the linearised contact at the static load.

    The pinion follows its prescribed motion, so the gear (inertia J2) rests
    on the mesh spring k = −dT/dφ2 of the IMPACT law at the deflection that
    carries the load: f = √(k/J2) / 2π. The stiffness varies with the mesh
    position (the number of tooth pairs and their lines change), so it is
    evaluated at ``positions`` pinion angles over one pinion pitch.

    Parameters
    ----------
    geometry_dir : str or os.PathLike
        Geometry directory of the design point.
    run : xarray.Dataset, optional
        Run dataset whose contact parameters and load torque to use (the
        paper's otherwise).
    positions : int, default 12
        Mesh positions over one pinion pitch [-].

    Returns
    -------
    dict
        ``frequency_hz`` (mean), ``frequency_min_hz``, ``frequency_max_hz``
        [Hz] and ``stiffness_N_m_per_rad`` (mean) [N m/rad].
    """
    from lsbg.dynamics import SimulationSettings, load_model

    model = load_model(geometry_dir, _contact_parameters(run))
    load = (float(run.attrs["solver_load_torque_N_m"])
            if run is not None and "solver_load_torque_N_m" in run.attrs
            else SimulationSettings().load_torque)
    z1 = model.pair.design.pinion_teeth
    stiffness = []
    for phi1 in np.linspace(0.0, 2 * math.pi / z1, positions, endpoint=False):
        phi2 = model.contact.static_gear_angle(load, pinion_angle=phi1)
        h = 1e-7
        plus = model.contact.forces(phi1, phi2 + h).gear_torque
        minus = model.contact.forces(phi1, phi2 - h).gear_torque
        stiffness.append(abs(plus - minus) / (2 * h))
    stiffness = np.asarray(stiffness)
    freq = np.sqrt(stiffness / model.gear_inertia) / (2 * math.pi)
    return {"frequency_hz": float(freq.mean()), "frequency_min_hz": float(freq.min()),
            "frequency_max_hz": float(freq.max()),
            "stiffness_N_m_per_rad": float(stiffness.mean())}


# -------------------------------------------------------------- verification
def read_convergence(paths) -> pd.DataFrame:
    """Read and stack convergence tables (``lsbg convergence``).

    Raises
    ------
    FileNotFoundError, ValueError
        Naming the file if it is missing or lacks a column of
        :data:`lsbg.experiments.verification.COLUMNS`.
    """
    from lsbg.experiments.verification import COLUMNS

    tables = []
    for path in as_path_list(paths):
        if not path.is_file():
            raise FileNotFoundError(f"{path}: no such convergence table")
        table = pd.read_csv(path)
        missing = [c for c in COLUMNS if c not in table.columns]
        if missing:
            raise ValueError(f"{path}: not a convergence table (missing columns {missing})")
        tables.append(table[list(COLUMNS)])
    if not tables:
        raise ValueError("no convergence tables given")
    return pd.concat(tables, ignore_index=True)


def convergence_table(table) -> pd.DataFrame:
    """Convergence table with the relative difference to the tightest tolerance run.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`read_convergence`.

    Returns
    -------
    pandas.DataFrame
        ``table`` plus, per design point and contact model,
        ``<column>_rel_diff_percent`` for the output samples' and the
        full-rate standard deviations of gear speed and tangential force:
        100 (std − std_ref) / std_ref with std_ref from the run of the
        smallest rtol (the scipy run where scipy and compiled tie), and
        ``reference``, that run's engine and rtol.
    """
    out = table.copy()
    for column in _CONVERGENCE_DIFFERENCES:
        out[f"{column}_rel_diff_percent"] = np.nan
    out["reference"] = ""
    for _, part in out.groupby(["trace", "spiral_angle_deg", "contact_model"]):
        tolerance = part[part["parameter"] == "rtol"]
        if tolerance.empty:
            continue
        tightest = tolerance[np.isclose(tolerance["value"], tolerance["value"].min(), rtol=1e-9, atol=0)]
        ref = tightest.sort_values("engine", key=lambda e: e != "scipy").iloc[0]
        out.loc[part.index, "reference"] = f"{ref['engine']} rtol {ref['value']:g}"
        for column, source in _CONVERGENCE_DIFFERENCES.items():
            out.loc[part.index, f"{column}_rel_diff_percent"] = (
                100 * (part[source] - ref[source]) / ref[source])
    return out


# Relative difference columns of convergence_table -> their source column.
_CONVERGENCE_DIFFERENCES = {
    "gear_speed_std": "gear_speed_std_deg_s",
    "tangential_force_std": "tangential_force_std_N",
    "gear_speed_full_std": "gear_speed_full_std_deg_s",
    "tangential_force_full_std": "tangential_force_full_std_N",
}


def pressure_angle_table(geometry_dirs) -> pd.DataFrame:
    """Normal pressure angles measured on the flanks at the mean point.

    Returns
    -------
    pandas.DataFrame
        Per gear type, member and side: ``measured_deg``, ``design_deg``
        (the design's αn) and ``deviation_deg``.
    """
    rows = []
    for label, record in records_by_type(geometry_dirs).items():
        for member in ("pinion", "gear"):
            for side in ("drive", "coast"):
                measured = record[f"normal_pressure_angle_mean_{member}_{side}_deg"]
                design = record["normal_pressure_angle_deg"]
                rows.append({"gear_type": label, "member": member, "side": side,
                             "measured_deg": measured, "design_deg": design,
                             "deviation_deg": measured - design})
    return pd.DataFrame(rows)


def conjugacy_errors(design, side="drive", phases=25, n=17) -> pd.DataFrame:
    """Distance between the pinion and gear flanks on the contact lines.

    At each mesh position (turn Ψ of the generating curve) both members are
    turned so that tooth 0's contact line lies at Ψ; the flank points of both
    members at the contact-line points (same cone distance and polar angle)
    must coincide with the line and their normals must be opposite: exact
    line contact (DESIGN.md §2).

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    side : {'drive', 'coast'}
    phases : int, default 25
        Mesh positions across the field of contact (and a little beyond) [-].
    n : int, default 17
        Points per contact line; the end points (possibly on the base cone,
        where the polar angle is a singular parameter) are left out [-].

    Returns
    -------
    pandas.DataFrame
        Per mesh position with a contact line: ``phase_deg``,
        ``pinion_distance_m`` and ``gear_distance_m`` (largest distance of a
        member's flank point from the contact line point) [m] and
        ``normal_mismatch`` (largest |n1 + n2|) [-].
    """
    from lsbg.gear.geometry import GearPair
    from lsbg.gear.vectors import rotate

    pair = GearPair(design)
    lo, hi = pair.planes[side].field[:2]
    rows = []
    for phase in np.linspace(lo - 0.3, hi + 0.3, phases):
        rho, points, _ = pair.contact_line(side, phase, n=n)
        if rho.size < 3:
            continue
        rho, points = rho[1:-1], points[1:-1]
        flanks = []
        for member in (1, 2):
            u = pair.rotation_axis[member]
            rotation = (phase / pair.axis_normal_component(member, side)
                        - pair.flank_offset[(member, side)])
            polar = np.arccos(points @ pair.axis[member] / np.linalg.norm(points, axis=1))
            body, normals = pair.flank(member, side, rho, polar)
            flanks.append((rotate(body, u, rotation), rotate(normals, u, rotation)))
        (p1, n1), (p2, n2) = flanks
        rows.append({"phase_deg": math.degrees(phase),
                     "pinion_distance_m": float(np.max(np.linalg.norm(p1 - points, axis=1))),
                     "gear_distance_m": float(np.max(np.linalg.norm(p2 - points, axis=1))),
                     "normal_mismatch": float(np.max(np.linalg.norm(n1 + n2, axis=1)))})
    return pd.DataFrame(rows, columns=["phase_deg", "pinion_distance_m", "gear_distance_m",
                                       "normal_mismatch"])


# ------------------------------------------------------------- as shown
def setting_label(engine, parameter, value, is_default=False) -> str:
    """An engine setting of the convergence study as words.

    Parameters
    ----------
    engine : str
    parameter : str
        ``time_step_s`` or ``rtol`` (others are shown as ``parameter = value``).
    value : float
    is_default : bool
        Whether it is the engine's default (the study's runs); adds "(default)".

    Returns
    -------
    str
        e.g. "pybullet dt = 1 µs (default)", "compiled rtol = 10⁻⁸".
    """
    value = float(value)
    if parameter == "time_step_s":
        text = f"dt = {value * 1e6:.4g} µs"
    else:
        text = (f"{'rtol' if parameter == 'rtol' else parameter.replace('_', ' ')} = "
                f"{format_number(value, 3)}")
    return f"{engine} {text}" + (" (default)" if is_default else "")


#: Columns of :func:`convergence_display` after ``gear_type`` and ``setting``:
#: each standard deviation followed by its relative difference to the reference run.
CONVERGENCE_DISPLAY_COLUMNS = (
    "gear_speed_std_deg_s", "gear_speed_std_rel_diff_percent",
    "gear_speed_full_std_deg_s", "gear_speed_full_std_rel_diff_percent",
    "tangential_force_std_N", "tangential_force_std_rel_diff_percent",
    "tangential_force_full_std_N", "tangential_force_full_std_rel_diff_percent",
    "wall_time_s",
)


def convergence_display(table) -> pd.DataFrame:
    """A convergence table (:func:`convergence_table`) narrowed for a page.

    One row per run, in the table's order: ``gear_type`` (LSBG, SBG),
    ``setting`` (:func:`setting_label`: engine, parameter and value in one
    cell), the four standard deviations each followed by its relative
    difference to the reference run, and the wall time
    (:data:`CONVERGENCE_DISPLAY_COLUMNS`). The columns that are the same in
    every row of one report table (trace with gear type, spiral angle,
    contact model, reference) and the means and step counts are left out;
    the complete table is the one to attach.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`convergence_table`, typically one contact model's rows.

    Returns
    -------
    pandas.DataFrame
        A new table; the numbers are the input's.
    """
    shown = pd.DataFrame({
        "gear_type": [TRACE_LABELS.get(t, t) for t in table["trace"]],
        "setting": [setting_label(e, p, v, d) for e, p, v, d in
                    zip(table["engine"], table["parameter"], table["value"],
                        table["is_default"])],
    }, index=table.index)
    for column in CONVERGENCE_DISPLAY_COLUMNS:
        shown[column] = table[column].to_numpy()
    return shown.reset_index(drop=True)


def by_gear_type(table, rows, types=("SBG", "LSBG")) -> pd.DataFrame:
    """A table with one row per gear type turned to one row per quantity.

    Parameters
    ----------
    table : pandas.DataFrame
        One row per gear type (column ``gear_type``).
    rows : sequence of (str, str, str)
        ``(column, label, unit)`` per row of the result, in order.
    types : sequence of str
        Gear types as columns, in this order; those absent from ``table`` are
        left out.

    Returns
    -------
    pandas.DataFrame
        Columns ``check`` (the label), ``unit`` and one per gear type.
    """
    by_type = table.set_index("gear_type")
    present = [t for t in types if t in by_type.index]
    out = pd.DataFrame({"check": [label for _, label, _ in rows],
                        "unit": [unit for _, _, unit in rows]})
    for gear in present:
        out[gear] = [float(by_type.at[gear, column]) for column, _, _ in rows]
    return out
