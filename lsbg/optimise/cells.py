"""Trace against trace in every cell: the ``trace_study`` section's spiral angles and cutters.

A cell is a design point of the trace comparison (docs/optimise.md, "Trace against
trace"): a spiral angle of the practice design and a cutter radius of its SBG. The
default study has one, the paper's angle with the design's cutter; the ``trace_study``
section adds the angles of the spiral-angle sweep (``sweep.spiral_angles_deg``) and the
nominal face-mill cutter radii that fit the pair there
(:func:`lsbg.gear.cutter.fitting_radii`).

* :func:`trace_cells`: the cells of a configuration, the paper's first.
* :func:`trace_study_problems`: the section's problems, one line each naming its key and
  value (an angle outside the sweep, a cutter that cannot span the face).
* :func:`trace_level_verdict`: the per-cell verdicts (``lsbg trace-fronts``) combined by
  docs/optimise.md's rule: a trace is better only where it is better in every cell.

The LSBG has no cutter: its fronts at an angle serve every cutter cell of that angle.
Angles are in degrees and radii in millimetres only in the configuration and the labels;
:func:`trace_cells` gives both in SI as well.
"""

from __future__ import annotations

import math

from lsbg.files import number_label

__all__ = ["trace_cells", "trace_study_problems", "trace_level_verdict", "cell_label",
           "paper_cell_label"]


def cell_label(spiral_deg, cutter_mm=None):
    """A cell's file-name part: ``beta35`` (the design's cutter), ``beta35_r76.2``.

    Parameters
    ----------
    spiral_deg : float
        The spiral angle [deg].
    cutter_mm : float or None
        The SBG's cutter radius [mm]; None: the design's.
    """
    label = f"beta{number_label(spiral_deg)}"
    return label if cutter_mm is None else f"{label}_r{number_label(cutter_mm)}"


def paper_cell_label(config):
    """The default study's cell: the paper's spiral angle, the design's cutter."""
    return cell_label(config["paper_spiral_angle_deg"])


def _published(config, trace, spiral_deg):
    from lsbg.gear.design import GearPairDesign

    design = {k: v for k, v in config["design"].items() if v is not None}
    return GearPairDesign.from_config({**design, "trace": trace, "spiral_angle_deg": spiral_deg})


def _section(config):
    section = config.get("trace_study") or {}
    return section.get("spiral_angles_deg", "paper"), section.get("cutter_radii_mm", "design")


def _angles(config):
    angles, _ = _section(config)
    if angles == "paper":
        return [float(config["paper_spiral_angle_deg"])]
    if angles == "sweep":
        return [float(a) for a in config["sweep"]["spiral_angles_deg"]]
    return [float(a) for a in angles]


def _usual_range(config):
    return tuple(config.get("cutter_sweep", {}).get("usual_range_outer_cone_distance",
                                                    (0.5, 1.5)))


def _cutters_at(config, spiral_deg):
    """The cutter radii of an angle's cells [mm], None for the design's."""
    from lsbg.gear.cutter import fitting_radii

    _, cutters = _section(config)
    if cutters == "design":
        return [None]
    sbg = config["practice"]["sbg_trace"]
    if cutters == "sweep":
        design = _published(config, sbg, spiral_deg)
        radii = [round(r * 1e3, 4) for r in fitting_radii(design, sbg, _usual_range(config))]
    else:
        radii = [float(r) for r in cutters]
    own = round(_published(config, sbg, spiral_deg).cutter_radius * 1e3, 4)
    # the design's own cutter is the cell of the design's cutter (one cell, not two)
    return list(dict.fromkeys(None if round(r, 4) == own else r for r in radii))


def trace_cells(config):
    """The cells of the trace comparison, the paper's first (always one: the default
    study's, which the best design point's rules read, runs whatever the section says).

    Parameters
    ----------
    config : dict
        A checked configuration (defaults filled in).

    Returns
    -------
    list of dict
        ``label`` (:func:`cell_label`), ``spiral_deg`` [deg], ``spiral`` (its label),
        ``spiral_angle`` [rad], ``cutter_mm`` [mm] (None: the design's cutter),
        ``cutter_radius`` [m] (None: the design's), ``paper`` (bool: the default
        study's cell, whose files are the default study's), ``lsbg_cell`` (the label of
        the cell whose LSBG fronts this cell reads: the angle's cell of the design's
        cutter, since the LSBG has no cutter).
    """
    paper = paper_cell_label(config)
    cells = [_cell(angle, cutter, paper) for angle in _angles(config)
             for cutter in _cutters_at(config, angle)]
    if paper not in {c["label"] for c in cells}:  # (the default study's cell always runs)
        cells.append(_cell(float(config["paper_spiral_angle_deg"]), None, paper))
    cells.sort(key=lambda c: not c["paper"])
    return list({c["label"]: c for c in cells}.values())


def _cell(angle, cutter, paper):
    """One of :func:`trace_cells`' cells: ``angle`` [deg], ``cutter`` [mm] or None, ``paper``
    the default study's cell's label."""
    label = cell_label(angle, cutter)
    return {"label": label, "spiral_deg": angle, "spiral": number_label(angle),
            "spiral_angle": math.radians(angle), "cutter_mm": cutter,
            "cutter_radius": None if cutter is None else cutter * 1e-3,
            "paper": label == paper, "lsbg_cell": cell_label(angle)}


def trace_study_problems(config):
    """The ``trace_study`` section's problems, one line each naming its key and value.

    Cells beyond the paper's need the searches (``optimise.enabled``, ``practice.enabled``);
    an explicit angle must be the paper's or one of ``sweep.spiral_angles_deg`` (the
    study's geometry is checked there); an explicit cutter radius must fit the pair at
    every angle of the section (:func:`lsbg.gear.cutter.cutter_fit_problem`, within
    ``cutter_sweep.usual_range_outer_cone_distance``).

    Parameters
    ----------
    config : dict
        The configuration, the schema's defaults filled in.

    Returns
    -------
    list of str
    """
    from lsbg.gear.cutter import cutter_fit_problem
    from lsbg.gear.design import DesignError

    angles, cutters = _section(config)
    if (angles, cutters) != ("paper", "design") and not (
            config.get("optimise", {}).get("enabled", True)
            and config.get("practice", {}).get("enabled", True)):
        key, value = (("spiral_angles_deg", angles) if angles != "paper"
                      else ("cutter_radii_mm", cutters))
        return [f"trace_study.{key} = {value!r}: compares the ease-off searches' fronts, so "
                f"it needs optimise.enabled and practice.enabled"]
    problems = []
    known = [float(a) for a in config["sweep"]["spiral_angles_deg"]]
    if isinstance(angles, list):
        allowed = set(known) | {float(config["paper_spiral_angle_deg"])}
        for k, angle in enumerate(angles):
            if float(angle) not in allowed:
                problems.append(f"trace_study.spiral_angles_deg[{k}] = {angle!r}: not the "
                                f"paper's angle nor one of sweep.spiral_angles_deg "
                                f"({', '.join(f'{a:g}' for a in known)})")
        if len(set(map(float, angles))) < len(angles):
            problems.append(f"trace_study.spiral_angles_deg = {angles!r}: each angle once")
    if problems or not isinstance(cutters, list):
        return problems
    if len(set(map(float, cutters))) < len(cutters):
        return [f"trace_study.cutter_radii_mm = {cutters!r}: each radius once"]
    sbg = config["practice"]["sbg_trace"]
    for angle in _angles(config):
        try:
            design = _published(config, sbg, angle)
        except DesignError:
            return problems  # (the design's own check names it)
        for k, radius in enumerate(cutters):
            why = cutter_fit_problem(design, sbg, float(radius) * 1e-3, _usual_range(config))
            if why:
                problems.append(f"trace_study.cutter_radii_mm[{k}] = {radius!r}: at "
                                f"{angle:g} deg {why}")
    return problems


def trace_level_verdict(cells):
    """The trace-level answer: the cells' verdicts combined by docs/optimise.md's rule.

    A trace is better only where it is better in every cell; otherwise the answer is
    not decided, with the number of cells each way.

    Parameters
    ----------
    cells : mapping
        ``{cell label: verdict}``, each verdict the code of
        :func:`lsbg.optimise.fronts.verdict` (1 the LSBG better, -1 the SBG, 0 a tie,
        NaN none) or a dataset of ``lsbg trace-fronts`` (its ``verdict``).

    Returns
    -------
    dict
        ``verdict`` (1 the LSBG better in every cell, -1 the SBG, 0 not decided),
        ``decided`` (bool), ``counts`` (``lsbg``, ``sbg``, ``tie``, ``none``: cells
        [-]), ``cells`` [-] and ``text``.

    Raises
    ------
    ValueError
        Without a cell, or with a code that is not a verdict.
    """
    if not cells:
        raise ValueError("trace_level_verdict: no cell")
    counts = {"lsbg": 0, "sbg": 0, "tie": 0, "none": 0}
    for label, value in cells.items():
        code = float(value["verdict"]) if hasattr(value, "data_vars") else float(value)
        if math.isnan(code):
            counts["none"] += 1
        elif code in (1, -1, 0):
            counts[{1: "lsbg", -1: "sbg", 0: "tie"}[int(code)]] += 1
        else:
            raise ValueError(f"trace_level_verdict: cell {label}: {code!r} is not a verdict "
                             f"(1, -1, 0 or NaN)")
    n = len(cells)
    side = 1 if counts["lsbg"] == n else -1 if counts["sbg"] == n else 0
    where = "the cell" if n == 1 else f"all {n} cells"
    if side:
        text = f"the {'LSBG' if side == 1 else 'SBG'}'s fronts are better in {where}"
    else:
        text = (f"not decided: the LSBG better in {counts['lsbg']}, the SBG in "
                f"{counts['sbg']}, a tie in {counts['tie']}, no verdict in "
                f"{counts['none']} of {n} cells")
    return {"verdict": side, "decided": bool(side), "counts": counts, "cells": n, "text": text}
