"""The study's design points and the names of the files made at them.

:func:`design_points` lists every design point a configuration asks for
(``(trace, spiral label)``, with the keys that ask for it); :data:`FILES`
holds the file-name pattern of every stage, which :class:`lsbg.study.plan.Study`
fills in for the rules. A point's label is its spiral angle as file names
have it (:func:`lsbg.files.number_label`).
"""

from __future__ import annotations

import math

from lsbg.files import number_label

__all__ = ["PAPER_TRACES", "CONTACT_MODELS", "REPORT_NAMES", "FILES", "design_points",
           "map_steps", "speed_labels", "speed_sweep_of"]

#: File name patterns of every stage (Snakemake wildcards in braces).
FILES = {
    "study_config": "results/config.yaml",
    "kernels": "results/kernels.json",
    "geometry": "results/geometry/{trace}_beta{spiral}",
    "mesh": "results/mesh/{trace}_beta{spiral}.nc",
    "run": "results/runs/{trace}_beta{spiral}_{model}_{engine}.nc",
    "sensitivity_run": "results/sensitivity/{trace}_beta{spiral}_{case}.nc",
    "convergence": "results/verification/convergence_{trace}_{model}.csv",
    "sweep": "results/sweep.nc",
    "summary": "results/summary.csv",
    "speed_run": "results/speed/{trace}_beta{spiral}_{boundary}_w{speed}.nc",
    "speed_curve": "results/speed_curve_{boundary}.nc",
    "tca": "results/tca/{trace}_beta{spiral}.nc",
    "vh_map": "results/vh/{trace}_beta{spiral}.nc",
    "compliance": "results/tooth/{trace}_beta{spiral}_compliance.nc",
    "fe_ltca": "results/tooth/{trace}_beta{spiral}_ltca.nc",
    "fe_envelope": "results/tooth/{trace}_beta{spiral}_envelope.nc",
    "fe_case": "results/tooth/{trace}_beta{spiral}_{case}_ltca.nc",
    "vh_case": "results/vh/{trace}_beta{spiral}_{case}.nc",
    "rating": "results/rating/{trace}_beta{spiral}.nc",
    "sweep_run": "results/sweeps/{name}/{trace}_beta{spiral}_{point}.nc",
    "sweep_dataset": "results/sweeps/{name}.nc",
    "sweep_table": "results/sweeps/{name}.csv",
    "report": "reports/{name}.html",
    # the pair as a designer would make it (lsbg practice, rules/practice.smk)
    "practice_design": "results/practice/design.yaml",
    "practice_geometry": "results/practice/geometry/{trace}_beta{spiral}",
    "practice_compliance": "results/practice/tooth/{trace}_beta{spiral}_compliance.nc",
    "practice_fe_ltca": "results/practice/tooth/{trace}_beta{spiral}_ltca.nc",
    "practice_fe_envelope": "results/practice/tooth/{trace}_beta{spiral}_envelope.nc",
    "practice_tca": "results/practice/tca/{trace}_beta{spiral}.nc",
    "practice_vh_map": "results/practice/vh/{trace}_beta{spiral}.nc",
    "practice_run": "results/practice/runs/{trace}_beta{spiral}_line_{engine}.nc",
    "practice_rating": "results/practice/rating/{trace}_beta{spiral}.nc",
    # its model-form cells: the sensitivity cases of practice.sensitivity on its design
    "practice_sensitivity_run": "results/practice/sensitivity/{trace}_beta{spiral}_{case}.nc",
    "practice_vh_case": "results/practice/vh/{trace}_beta{spiral}_{case}.nc",
    "practice_fe_case": "results/practice/tooth/{trace}_beta{spiral}_{case}_ltca.nc",
    # each type at its best ease-off (lsbg optimise on the practice design, rules/optimise.smk):
    # the front of each seed, the released ease-off as an overlay, and the practice design
    # point's claims' files again with it
    "optimise_front": "results/optimise/{trace}_beta{spiral}_seed{seed}_front.nc",
    # the fronts' candidates under the verdict's models and the released ease-off (lsbg release)
    "optimise_release": "results/optimise/{trace}_beta{spiral}_release.nc",
    "best_overlay": "results/optimise/{trace}_beta{spiral}_best.yaml",
    # each front re-evaluated at the release's converged positions (lsbg converge-front),
    # and the traces' fronts compared (lsbg trace-fronts)
    "optimise_converged_front": "results/optimise/{trace}_beta{spiral}_converged_front.nc",
    "trace_fronts": "results/optimise/trace_fronts.nc",
    # the trace study's other cells (trace_study; lsbg.optimise.cells, rules/trace_study.smk):
    # the practice design at each other spiral angle, and per cell (a spiral angle and the
    # SBG's cutter) the same chain as the paper cell's; the LSBG's at an angle's cell of the
    # design's cutter only
    "cell_practice_design": "results/trace_study/beta{spiral}_design.yaml",
    "cell_geometry": "results/trace_study/{cell}/geometry/{trace}",
    "cell_compliance": "results/trace_study/{cell}/{trace}_compliance.nc",
    "cell_front": "results/trace_study/{cell}/{trace}_seed{seed}_front.nc",
    "cell_release": "results/trace_study/{cell}/{trace}_release.nc",
    "cell_best_overlay": "results/trace_study/{cell}/{trace}_best.yaml",
    "cell_converged_front": "results/trace_study/{cell}/{trace}_converged_front.nc",
    "cell_trace_fronts": "results/optimise/trace_fronts_{cell}.nc",
    "best_fe_ltca": "results/best/tooth/{trace}_beta{spiral}_ltca.nc",
    "best_fe_envelope": "results/best/tooth/{trace}_beta{spiral}_envelope.nc",
    "best_tca": "results/best/tca/{trace}_beta{spiral}.nc",
    "best_vh_map": "results/best/vh/{trace}_beta{spiral}.nc",
    "best_run": "results/best/runs/{trace}_beta{spiral}_line_{engine}.nc",
    "best_rating": "results/best/rating/{trace}_beta{spiral}.nc",
    "best_sensitivity_run": "results/best/sensitivity/{trace}_beta{spiral}_{case}.nc",
    "best_vh_case": "results/best/vh/{trace}_beta{spiral}_{case}.nc",
    "best_fe_case": "results/best/tooth/{trace}_beta{spiral}_{case}_ltca.nc",
    # stresses, TE and pattern against torque (lsbg load-curve), design_set: paper or practice
    "load_curve": "results/load_curves/{design_set}_{trace}_beta{spiral}.nc",
    # the SBG's cutter radius as a design variable (lsbg cutter-point, rules/cutter.smk):
    # lsbg, or {trace}_r{radius in mm}
    "cutter_point": "results/cutter/{point}.nc",
}

#: Both traces run at the paper's design point (the paper compares them): the paper's SBG.
PAPER_TRACES = ("logarithmic", "circular")

CONTACT_MODELS = ("point", "line")
REPORT_NAMES = ("paper", "sweep", "verification")


def design_points(config):
    """Every design point of a study and the keys of the configuration that ask for it.

    Parameters
    ----------
    config : dict
        Validated by the schema, its defaults filled in.

    Returns
    -------
    dict
        ``(trace, spiral label)`` -> key paths of the spiral angles that give the
        point, e.g. ``("circular", "35") -> ["paper_spiral_angle_deg",
        "sweep.spiral_angles_deg[1]"]``; sorted by trace, then angle. The label
        is the angle [deg] as file names and the jobs have it
        (:func:`lsbg.files.number_label`).
    """
    asked = [(trace, number_label(angle), f"sweep.spiral_angles_deg[{k}]")
             for trace in config["sweep"]["traces"]
             for k, angle in enumerate(config["sweep"]["spiral_angles_deg"])]
    asked += [(trace, number_label(config["paper_spiral_angle_deg"]), "paper_spiral_angle_deg")
              for trace in PAPER_TRACES]
    speed = config.get("speed_sweep")
    if speed:
        key = "speed_sweep.spiral_angle_deg" if "spiral_angle_deg" in speed \
            else "paper_spiral_angle_deg"
        angle = speed.get("spiral_angle_deg", config["paper_spiral_angle_deg"])
        asked += [(trace, number_label(angle), key)
                  for trace in speed.get("traces", PAPER_TRACES)]
    points = {}
    for trace, spiral, key in sorted(asked, key=lambda a: (a[0], float(a[1]), a[2])):
        keys = points.setdefault((trace, spiral), [])
        if key not in keys:
            keys.append(key)
    return points


def speed_labels(grid):
    """The speed sweep's pinion speeds [rad/s] and their file-name labels [deg/s, to 1e-3].

    Parameters
    ----------
    grid : dict
        ``speed_sweep.pinion_speeds_deg_s``: ``start``, ``stop`` [deg/s], ``count``.
    """
    from lsbg.experiments.speed import speed_grid

    speeds = speed_grid(math.radians(grid["start"]), math.radians(grid["stop"]), grid["count"])
    return speeds, [number_label(round(math.degrees(v), 3)) for v in speeds]


def map_steps(config, spiral):
    """Values per axis of the V-H map at a design point's spiral angle (its file-name
    label): ``misalignment_map.steps`` at the paper's, else ``sweep_steps``."""
    section = config["misalignment_map"]
    paper = number_label(config["paper_spiral_angle_deg"])
    return section["steps"] if number_label(spiral) == paper else section["sweep_steps"]


def speed_sweep_of(config):
    """The configuration's ``speed_sweep`` section if the study runs it, else None (no
    section, or ``enabled: false``).

    Parameters
    ----------
    config : dict
        The workflow configuration.
    """
    section = config.get("speed_sweep") or None
    return section if section and section.get("enabled", True) else None
