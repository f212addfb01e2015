"""The ``sweeps`` section checked before any job (:mod:`lsbg.experiments.sweeps`).

Every point of every sweep goes through the same checks as if its values were
set in their own sections (the schema, then lsbg's checks of the settings, the
design points and the load, at the sweep's own design points); the sweep's
keys must be sweepable, its design points the study's, its points distinct as
file names, and all sweeps together within the resource guard's number of runs.
Part of :func:`lsbg.study.checks.check_config`.
"""

from __future__ import annotations

import copy

from lsbg.experiments.sweeps import FIXED_KEYS, SWEEPABLE_SECTIONS, sweeps_from_config

__all__ = ["MAX_SWEEP_RUNS", "sweep_problems", "load_sweep_moved"]


def _key_problems(name, sweep, config):
    problems = []
    for key in sweep.keys:
        section, _, field = key.partition(".")
        where = f"sweeps.{name}.{key}"
        if key in FIXED_KEYS:
            problems.append(f"{where}: cannot be swept ({FIXED_KEYS[key]})")
        elif section not in SWEEPABLE_SECTIONS:
            problems.append(f"{where}: the {section!r} section cannot be swept (sweepable: "
                            f"{', '.join(SWEEPABLE_SECTIONS)})")
        elif section != "design" and field not in config.get(section, {}):
            known = ", ".join(sorted(config.get(section, {})))
            problems.append(f"{where}: unknown key (known in {section}: {known})")
    return problems


def _value_problems(name, sweep, config, check):
    """Every point through ``check(config, sweep)`` as if set in its own section."""
    problems, seen = [], set()
    for k, point in enumerate(sweep.points):
        changed = copy.deepcopy(config)
        for key, value in point.items():
            section, field = key.split(".", 1)
            changed[section][field] = value
        for line in check(changed, sweep):
            if line not in seen:  # the same problem at several points: named once
                seen.add(line)
                problems.append(f"sweeps.{name}: point {k} ({_point_text(point)}): {line}")
    return problems


def _point_problems(name, sweep, spec, config):
    """The sweep's design points must be the study's (their geometry is the study's)."""
    from lsbg.files import number_label
    from lsbg.study.points import design_points

    study = set(design_points(config))
    missing = [(t, a) for t in sweep.traces for a in sweep.spiral_angles
               if (t, number_label(a)) not in study]
    if not missing:
        return []
    key = "spiral_angles_deg" if "spiral_angles_deg" in spec else "traces"
    trace, angle = missing[0]
    return [f"sweeps.{name}.{key} = {spec.get(key, list(sweep.traces))!r}: {number_label(angle)} "
            f"({trace}) is not a design point of the study (sweep.traces x "
            f"sweep.spiral_angles_deg, or the paper's point)"]


def _point_text(point):
    return ", ".join(f"{key} = {value!r}" for key, value in point.items())


def _name_problems(name, sweep):
    patterns = sweep.patterns()
    problems = []
    first = {}
    for k, pattern in enumerate(patterns):
        if pattern in first:
            problems.append(f"sweeps.{name}: points {first[pattern]} ({_point_text(sweep.points[first[pattern]])}) "
                            f"and {k} ({_point_text(sweep.points[k])}) are the same point")
        first.setdefault(pattern, k)
    return problems


#: Most runs a study's sweeps may ask for, together (the resource guard; a sweep
#: of this size is a cluster's: docs/scaling.md) [-].
MAX_SWEEP_RUNS = 5000


def sweep_problems(config, check):
    """Every problem of the ``sweeps`` section, one line each, before any job.

    Parameters
    ----------
    config : dict
        The configuration, defaults filled in.
    check : callable
        ``check(config, sweep) -> list of str``: the configuration check of the
        swept sections (the schema, the settings, the load guard, the design
        points' physics; :mod:`lsbg.study.checks`), applied to the
        configuration with each point's values set.

    Returns
    -------
    list of str
        Starting with ``sweeps.<name>``. Sweeps of more than
        :data:`MAX_SWEEP_RUNS` runs together get that one line (beside the
        sweeps that cannot be read), their points unchecked.
    """
    problems, parsed = [], []
    for name, spec in (config.get("sweeps") or {}).items():
        try:
            (sweep,) = sweeps_from_config({**config, "sweeps": {name: spec}})
        except ValueError as error:
            problems.append(str(error))
            continue
        parsed.append((name, spec, sweep))
    runs = sum(len(s.points) * len(s.traces) * len(s.spiral_angles) for _, _, s in parsed)
    if runs > MAX_SWEEP_RUNS:
        # first: checking each of thousands of points would take minutes
        return problems + [f"sweeps: {runs} runs in all, more than the resource guard's "
                           f"{MAX_SWEEP_RUNS} (split the study, or run it on a cluster with "
                           f"a larger limit)"]
    for name, spec, sweep in parsed:
        found = _key_problems(name, sweep, config) + _point_problems(name, sweep, spec, config)
        if not found:
            found = _name_problems(name, sweep) or _value_problems(name, sweep, config, check)
        if sweep.batch_size < 1:
            found.append(f"sweeps.{name}.batch_size = {sweep.batch_size!r}: must be at least 1")
        problems += found
    return problems


def load_sweep_moved(section):
    """The one-line message naming the ``sweeps`` entry that replaces a ``load_sweep``
    section (the former extension, now an instance of the sweeps).

    Parameters
    ----------
    section : dict
        The ``load_sweep`` section as written.
    """
    section = section if isinstance(section, dict) else {}
    entry = {"simulation.load_torque_N_m": section.get("torques_N_m", []),
             "contact_model": section.get("contact_model", "point")}  # its old default
    entry.update({k: section[k] for k in ("traces", "engine") if k in section})
    text = ", ".join(f"{k}: {v!r}".replace("'", "") for k, v in entry.items())
    return (f"load_sweep: replaced by the sweeps section (docs/usage.md, \"Sweeping any setting\"); "
            f"write instead  sweeps: {{load: {{{text}}}}}  (results in results/sweeps/load.nc)")
