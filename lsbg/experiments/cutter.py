"""The SBG's cutter radius as a design variable (the ``cutter_sweep`` section).

At the paper's design point the study cuts the SBG (trace ``cutter_sweep.trace``) with
every nominal face-mill cutter that fits the pair (:func:`lsbg.gear.cutter.fitting_radii`),
with the design's own cutter, and with the one whose tooth trace curves as the LSBG's at
the mean point (:func:`lsbg.gear.cutter.matched_cutter_radius`), and records per SBG and
for the LSBG beside them (:func:`point_dataset`):

* the loaded TE of the line model on the uniform bed at the rated torque (``lsbg ltca``'s,
  at ``tca.loaded_positions``), as the spiral-angle sweep's design points record it;
* the bearing pattern's movement per 0.1 mm of displacement, claim 2's measure
  (of a V-H map at ``misalignment_map.sweep_steps``, the sweep's own resolution; the
  reports take its total, :func:`lsbg.tables.contact_state.pattern_movement`);
* the FE stresses of the FE loaded TCA (largest contact pressure, pinion and gear root
  stress over the mesh cycle, the ``tooth`` section's mesh) at the points ``cutter_sweep.fe``
  names: ``reference`` the design's cutter and the curvature-matched one (the
  decomposition's), ``all`` every point.

:func:`lsbg.tables.cutter.decomposition` splits each difference LSBG - SBG(design's
cutter) into the curvature's share, SBG(matched) - SBG(design's cutter), and the constant
spiral angle's, LSBG - SBG(matched).
"""

from __future__ import annotations

import math

__all__ = ["STRESS_FIGURES", "cutter_points", "cutter_sweep_problems", "point_dataset",
           "fe_stresses"]

#: The FE loaded TCA's figures of a point [MPa].
STRESS_FIGURES = ("max_contact_pressure", "root_stress_pinion", "root_stress_gear")


def _design(config):
    from lsbg.gear.design import GearPairDesign

    design = {k: v for k, v in config["design"].items() if v is not None}
    return GearPairDesign.from_config({**design, "trace": "logarithmic",
                                       "spiral_angle_deg": config["paper_spiral_angle_deg"]})


def cutter_points(config):
    """The sweep's points: the LSBG, then each SBG by ascending cutter radius.

    Parameters
    ----------
    config : dict
        A checked configuration (defaults filled in).

    Returns
    -------
    list of dict
        ``label`` (the file-name part: ``lsbg``, ``r76.2``), ``trace``, ``radius_mm``
        (the LSBG's: its curvature radius R_m / sin beta_m), ``roles`` (a tuple of
        ``lsbg``, ``design``, ``nominal``, ``matched``), ``fe`` (bool).
    """
    from lsbg.files import number_label
    from lsbg.gear.cutter import fitting_radii, lsbg_curvature_radius, matched_cutter_radius

    section = config["cutter_sweep"]
    design, trace = _design(config), section["trace"]
    usual = tuple(section["usual_range_outer_cone_distance"])
    nominal = (fitting_radii(design, trace, usual) if section["radii_mm"] is None
               else [r * 1e-3 for r in section["radii_mm"]])
    radii = {}
    for r in nominal:
        radii.setdefault(round(r * 1e3, 4), set()).add("nominal")
    radii.setdefault(round(design.cutter_radius * 1e3, 4), set()).add("design")
    radii.setdefault(round(matched_cutter_radius(design, trace) * 1e3, 4), set()).add("matched")
    fe_roles = {"reference": {"design", "matched"}, "all": {"design", "matched", "nominal"},
                "none": set()}[section["fe"]]
    points = [{"label": "lsbg", "trace": "logarithmic",
               "radius_mm": round(lsbg_curvature_radius(design) * 1e3, 4), "roles": ("lsbg",),
               "fe": section["fe"] != "none"}]
    for r in sorted(radii):
        roles = tuple(sorted(radii[r]))
        points.append({"label": "r" + number_label(r), "trace": trace, "radius_mm": r,
                       "roles": roles, "fe": bool(fe_roles & set(roles))})
    return points


def cutter_sweep_problems(config):
    """The ``cutter_sweep`` section's problems, one line each naming its key and value.

    A listed radius must fit the pair
    (:func:`lsbg.gear.cutter.cutter_fit_problem`, at the paper's spiral angle); the usual
    range must be increasing; the curvature-matched cutter must exist.
    """
    from lsbg.gear.cutter import cutter_fit_problem, matched_cutter_radius
    from lsbg.gear.design import DesignError

    section = config.get("cutter_sweep") or {}
    if not section.get("enabled"):
        return []
    trace = section["trace"]
    low, high = section["usual_range_outer_cone_distance"]
    if not 0 < low < high:
        return [f"cutter_sweep.usual_range_outer_cone_distance = {[low, high]!r}: must be "
                f"two increasing positive multiples of the outer cone distance"]
    try:
        design = _design(config)
    except DesignError:
        return []  # (the design's own check names it)
    problems = []
    if section["radii_mm"] is not None:
        for k, radius in enumerate(section["radii_mm"]):
            why = cutter_fit_problem(design, trace, radius * 1e-3, (low, high))
            if why:
                problems.append(f"cutter_sweep.radii_mm[{k}] = {radius!r}: {why}")
    try:
        matched_cutter_radius(design, trace)
    except DesignError as error:
        problems.append(f"cutter_sweep.trace = {trace!r}: {error}")
    return problems


def fe_stresses(ds):
    """{figure: MPa} of an FE loaded TCA (its largest over the mesh cycle)."""
    return {"max_contact_pressure": float(ds["max_contact_pressure"].max()),
            "root_stress_pinion": float(ds["root_stress_pinion"].max()),
            "root_stress_gear": float(ds["root_stress_gear"].max())}


def point_dataset(pair, load_torque, params, flanks, sections, fe=None):
    """One point's V-H map with its other figures as attributes ``cutter_*``.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    load_torque : float
        Torque on the gear [N m].
    params : lsbg.contact.ContactParameters
        The line model's settings (uniform bed).
    flanks : lsbg.tca.separation.RealFlanks
    sections : dict
        The configuration's ``tca``, ``misalignment_map`` and ``tooth`` sections.
    fe : xarray.Dataset or "compute" or None
        The point's FE loaded TCA, ``"compute"`` (the ``tooth`` section's mesh), or None
        (stresses NaN).

    Returns
    -------
    xarray.Dataset
        :func:`lsbg.tca.vh_map.misalignment_map` at ``misalignment_map.sweep_steps`` with
        attributes ``cutter_loaded_te_peak_to_peak`` [urad] (``tca.loaded_positions``),
        ``cutter_max_contact_pressure``, ``cutter_root_stress_pinion``,
        ``cutter_root_stress_gear`` [MPa], ``cutter_trace_curvature_radius`` [mm] and
        ``cutter_spiral_angle_toe``, ``cutter_spiral_angle_heel`` [deg] (the gear's pitch
        cone).
    """
    from lsbg.contact import MeshContact
    from lsbg.gear.cutter import trace_curvature_radius
    from lsbg.tca.loaded import pair_loaded_tca
    from lsbg.tca.vh_map import axis_values, misalignment_map

    d = pair.design
    vh = sections["misalignment_map"]
    uniform = params.replace(model="line", compliance="uniform")
    loaded = pair_loaded_tca(pair, load_torque, uniform, flanks,
                             sections["tca"]["loaded_positions"])
    values = axis_values(vh["range"], vh["sweep_steps"])
    load = load_torque if vh["load_torque_N_m"] is None else vh["load_torque_N_m"]
    ds = misalignment_map(pair, flanks.modification, vh["axes"], (values, values), load,
                          uniform, base=flanks.misalignment, positions=vh["positions"])
    ends = pair.spiral_angle(2, d.pitch_angle(2), [d.inner_cone_distance,
                                                   d.outer_cone_distance])
    if isinstance(fe, str):
        import tempfile

        from lsbg.tooth.analysis import fe_ltca
        from lsbg.tooth.config import compliance_for_design, tooth_from_config

        material, mesh, positions = tooth_from_config(sections["tooth"])
        with tempfile.TemporaryDirectory(prefix="lsbg-cutter-") as scratch:
            compliance, _ = compliance_for_design(pair, material, mesh, f"{scratch}/c.nc")
        fe = fe_ltca(MeshContact(pair, uniform, separation=flanks.separation(pair)),
                     compliance, load_torque, positions)
    stresses = fe_stresses(fe) if fe is not None else dict.fromkeys(STRESS_FIGURES, math.nan)
    figures = {"loaded_te_peak_to_peak": float(
                   loaded.attrs["transmission_error_peak_to_peak_urad"]),
               **stresses, "trace_curvature_radius": trace_curvature_radius(pair) * 1e3,
               "spiral_angle_toe": math.degrees(ends[0]),
               "spiral_angle_heel": math.degrees(ends[1])}
    ds.attrs.update({f"cutter_{k}": float(v) for k, v in figures.items()})
    return ds
