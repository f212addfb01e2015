"""The workflow's configuration, checked completely before any job runs.

:func:`check_config` is the one check ``workflow/rules/common.smk`` calls
while Snakemake reads the workflow (``snakemake -n`` included), before the
DAG is built. It returns every problem as one line that starts with the
user's key path and value, in the configuration's units (``design.face_width_mm
= 500``, never lsbg's SI name ``face_width = 0.5``). In order (each step
assumes the ones before it passed):

1. every number is finite: JSON Schema's range keywords let NaN through
   (every comparison with NaN is false) and inf through any lower bound;
2. the schema (workflow/schemas/config.schema.yaml): types, ranges, enums,
   list lengths, duplicates, required and unknown keys;

then, with the schema's defaults filled in (:func:`fill_defaults`, as
``snakemake.utils.validate`` does), all of these (each a function of the
configuration that returns its problem lines):

3. file names: sweep values that differ but give the same file name
   (:func:`lsbg.files.number_label` keeps 6 decimals);
4. the settings as lsbg's commands will read them: each engine's simulation
   settings, the contact law, the sensitivity cases, the paper engine, the
   speed sweep and the load sweep;
5. the statistics: steady state <= chart window start < window end <=
   duration, and enough samples for the Anderson-Darling test, the Xbar-R
   subgroups and the sampling-phase spread of the summary;
6. every design point: :class:`lsbg.gear.geometry.GearPair` runs lsbg's own
   checks (:mod:`lsbg.gear.design`: proportions, backlash, bores, cutter radius;
   :mod:`lsbg.gear.geometry`: pointed teeth, contact ratio >= 1 under
   interference), their messages mapped back to the design key in mm;
7. the resource guard: each design point's geometry memory and time,
   estimated from its mesh size (:func:`geometry_cost`), against
   ``limits.memory_gb`` and ``limits.geometry_minutes``; each run's record
   against ``limits.memory_gb`` and the line model's slices against the
   runtime the simulation rules request (:func:`run_cost_problems`); the
   load and the pinion speed against what the teeth of each contact model
   can carry and the full-rate record can resolve
   (:func:`lsbg.study.resources.load_problems`);
8. the contact state at each design point that passed 6 and 7 (odd map steps
   first; :func:`lsbg.tca.checks.contact_state_problems`): the relief within
   the backlash, the misalignment and the V-H map's corners neither losing
   contact nor closing the backlash; kept (:func:`contact_state_cache_dir`):
   its quick TCAs and numba's start cost about 1.2 s once per configuration;
9. the tooth section, the compliance case and each FE compliance's estimated
   cost (:func:`lsbg.tooth.config.tooth_problems`);
10. the rating section and the paper point's ISO 10300 rating
    (:func:`lsbg.rating.config.rating_problems`);
11. the sweeps (:func:`lsbg.study.sweep_checks.sweep_problems`): every point of every
    sweep through the schema and steps 4, 6 and 7 as if its values were set in
    their own sections, at the sweep's own design points; points that give one
    file name; the number of runs against the resource guard.

A YAML syntax error in a ``--configfile`` never reaches this module:
Snakemake 9 reads that file before the Snakefile and stops with
"Config file is not valid JSON or YAML" (without the file or the line;
``--verbose`` adds the YAML parser's message, which names both).
``lsbg check-config FILE`` (:mod:`lsbg.cli.config`) reads the files as
Snakemake does, names the file and line of such an error, and runs
:func:`check_config`.
"""

from __future__ import annotations

import hashlib
import os
import re
import warnings
from pathlib import Path

import numpy as np

from lsbg.config import fill_defaults, key_path, nonfinite_problems, schema_problems
from lsbg.gear.design import CONFIG_KEYS, DesignError, GearPairDesign
from lsbg.files import number_label
from lsbg.study.resources import (engines_run, geometry_cost, load_problems, memory_limit_gb,
                                  run_cost_problems, run_memory_gb, speed_sweep_problems)
from lsbg.study.plan import design_points, map_steps

__all__ = [
    "key_path", "check_config", "nonfinite_problems", "schema_problems", "fill_defaults",
    "contact_state_cache_dir", "AD_MIN_SAMPLES"
]


def check_config(config, schema):
    """Every problem of a workflow configuration; fills in the schema's defaults.

    Parameters
    ----------
    config : dict
        The merged configuration, as Snakemake loaded it; changed in place:
        the schema's defaults are filled in once it passes the schema.
    schema : dict
        workflow/schemas/config.schema.yaml, loaded.

    Returns
    -------
    list of str
        One line per problem, each starting with the key path and its value
        in the configuration's units; empty if the configuration is valid.
    """
    if "load_sweep" in config:  # the extension became an instance of the sweeps section
        from lsbg.study.sweep_checks import load_sweep_moved

        return [load_sweep_moved(config["load_sweep"])]
    nonfinite = nonfinite_problems(config)
    flagged = {line.split(" = ", 1)[0] for line in nonfinite}
    problems = nonfinite + [line for line in schema_problems(config, schema)
                            if line.split(":", 1)[0] not in flagged]
    if problems:
        return problems
    fill_defaults(config, schema)
    pairs = {}  # the design points that pass the physics and the resource guard
    problems = (_name_problems(config) + _settings_problems(config) + run_cost_problems(config)
                + _statistics_problems(config) + _design_problems(config, pairs))
    from lsbg.rating.config import rating_problems
    from lsbg.tooth.config import tooth_problems

    problems += load_problems(config, pairs)
    problems += _contact_state_problems(config, pairs) + tooth_problems(
        config, pairs, *memory_limit_gb(config)) + rating_problems(config, pairs)
    if not problems and config.get("sweeps"):
        problems += _sweeps_problems(config, schema, pairs)
    return list(dict.fromkeys(problems))


def _sweeps_problems(config, schema, pairs):
    """The ``sweeps`` section (:func:`lsbg.study.sweep_checks.sweep_problems`): each point through
    the schema and steps 4, 6 and 7, at the sweep's own design points."""
    from lsbg.study.sweep_checks import sweep_problems
    from lsbg.tca.separation import RealFlanks

    def check(changed, sweep):
        problems = (schema_problems(changed, schema) or _settings_problems(changed)
                    + run_cost_problems(changed))
        labels = {number_label(a) for a in sweep.spiral_angles}
        points = {k: v for k, v in pairs.items() if k[0] in sweep.traces and k[1] in labels}
        if any(k.split(".", 1)[0] in ("design", "flank_modification", "misalignment")
               for k in sweep.keys):  # the point's own design and flanks at its points
            points = {}
            where = {**changed, "paper_spiral_angle_deg": sweep.spiral_angles[0],
                     "sweep": {**changed["sweep"], "traces": list(sweep.traces),
                               "spiral_angles_deg": list(sweep.spiral_angles)}}
            problems += _design_problems(where, points)
            try:
                RealFlanks.from_config(changed["flank_modification"], changed["misalignment"])
            except ValueError as error:
                problems.append(str(error))
        return problems + load_problems(changed, points)

    return sweep_problems(config, check)


# ----------------------------------------------------------- values, schema


# ------------------------------------------------------------- file names
def _label_clashes(values, where, label=number_label):
    """Values of a list whose file-name labels equal an earlier one's, one line each."""
    seen, problems = {}, []
    for k, value in enumerate(values):
        name = label(value)
        if name in seen:
            first = seen[name]
            problems.append(f"{where}[{k}] = {value!r}: gives the same file name ({name}) as "
                            f"{where}[{first}] = {values[first]!r} (file names keep "
                            f"6 decimals)")
        else:
            seen[name] = k
    return problems


def _name_problems(config):
    """Sweep values that differ but give the same file name (or case name)."""
    from lsbg.experiments.sensitivity import case_name

    problems = _label_clashes(config["sweep"]["spiral_angles_deg"], "sweep.spiral_angles_deg")
    for key, factors in config["sensitivity"].items():
        problems += _label_clashes(factors, f"sensitivity.{key}",
                                   label=lambda factor, key=key: case_name(key, factor))
    return problems


# ----------------------------------------------------------------- settings
def _settings_problems(config):
    """The engines, simulation, contact, sensitivity, speed and load sweeps as lsbg
    reads them (:mod:`lsbg.dynamics`, :mod:`lsbg.contact`, :mod:`lsbg.experiments.speed`)."""
    from lsbg.contact import ContactParameters
    from lsbg.dynamics import SimulationSettings
    from lsbg.experiments.sensitivity import scaled_contact

    problems = []
    engines = config["engines"]
    sweep_engine, reference = engines["sweep"], engines["reference"]
    if engines["paper"] not in {sweep_engine, *reference.get("point", [])}:
        problems.append(f"engines.paper = {engines['paper']!r}: must be engines.sweep or one of "
                        f"engines.reference.point {reference.get('point', [])!r} (the paper "
                        f"report reproduces the paper with the point model)")
    engines_failing = {}  # message -> engines
    for engine in sorted(engines_run(config)):
        try:
            SimulationSettings.from_config(config["simulation"], engine=engine)
        except ValueError as error:
            engines_failing.setdefault(_settings_message(error, config), []).append(engine)
    problems += [f"{message} (engine {', '.join(names)})"
                 for message, names in engines_failing.items()]
    try:
        ContactParameters.from_config(config["contact"])
    except ValueError as error:
        problems.append(_settings_message(error, config))
    except ArithmeticError as error:  # numbers beyond what the unit conversions survive
        problems.append(f"{_section_values(config, 'contact')}: lsbg cannot compute this "
                        f"contact law ({type(error).__name__}: {error})")
    for key, factors in config["sensitivity"].items():
        for k, factor in enumerate(factors):
            scaled = {**config["contact"], "model": "line",
                      **scaled_contact(config["contact"], key, factor)}
            try:
                ContactParameters.from_config(scaled)
            except ValueError as error:
                problems.append(f"sensitivity.{key}[{k}] = {factor!r}: gives "
                                f"{_settings_message(error, {**config, 'contact': scaled})}")
    if config.get("speed_sweep"):
        problems += speed_sweep_problems(config)
    return problems


#: lsbg's message of a ``simulation`` or ``contact`` setting: the user's key
#: and value, then lsbg's field name, SI value and rule
#: (``contact.slices = 1: ContactParameters.slices must be ..., got slices=1``,
#: ``simulation.ramp_time_s = 2.0: ramp_time = 2.0: exceeds ...``).
_SETTINGS_ERROR = re.compile(r"^((?:simulation|contact)\.\w+ = .*?): "
                             r"(?:ContactParameters\.\w+ (.*?), got .*|\w+ = .*?: (.*))$",
                             re.DOTALL)


def _settings_message(error, config):
    """lsbg's message of a setting without its SI field names and units: the rule
    in the user's keys (``v_s=0.0001 [m/s]`` -> ``contact.stiction_velocity_mm_s = 0.1``)."""
    from lsbg.contact import CONTACT_CONFIG_KEYS

    match = _SETTINGS_ERROR.match(str(error))
    if not match:
        return str(error)
    rule = match.group(3)
    if rule is None:  # a contact rule: its unit is the SI field's, the user's value is not
        rule = re.sub(r" \[[^\]]*\]$", "", match.group(2))
        rule = re.sub(r"\b(\w+)=\S+", lambda m: (
            f"contact.{CONTACT_CONFIG_KEYS[m.group(1)]} = "
            f"{config['contact'].get(CONTACT_CONFIG_KEYS[m.group(1)])!r}"
            if m.group(1) in CONTACT_CONFIG_KEYS else m.group(0)), rule)
    return f"{match.group(1)}: {rule}"


# --------------------------------------------------------------- statistics
#: Fewest samples of lsbg.stats.anderson_darling (the summary's normality test).
AD_MIN_SAMPLES = 3


def _statistics_problems(config):
    """The statistics windows against the run, and enough samples for the summary.

    ``lsbg summary`` keeps the samples after ``steady_state_after_s`` (the
    Anderson-Darling test needs 3), cuts the chart window (start excluded,
    stop included) into subgroups of ``subgroup_size`` (its sample count
    must be a whole multiple of it), and splits the full-rate record after
    the steady-state start into the sampling phases (3 samples each). These
    are counted here on the run's own record instants
    (:meth:`lsbg.dynamics.SimulationSettings.record_grid`) with the
    summary's selection rules.
    """
    from lsbg.stats import spectra
    from lsbg.dynamics import SimulationSettings

    simulation, statistics = config["simulation"], config["statistics"]
    duration, samples = simulation["duration_s"], simulation["samples"]
    steady = statistics["steady_state_after_s"]
    start, stop = statistics["control_chart_window_s"]
    size = statistics["subgroup_size"]
    problems = []
    if steady >= duration:
        problems.append(f"statistics.steady_state_after_s = {steady!r}: must be below "
                        f"simulation.duration_s = {duration!r}")
    if not steady <= start < stop <= duration * (1 + 1e-9):
        problems.append(f"statistics.control_chart_window_s = {[start, stop]!r}: needs "
                        f"statistics.steady_state_after_s = {steady!r} <= start < stop <= "
                        f"simulation.duration_s = {duration!r}")
    if problems or (run_memory_gb(samples, duration, simulation["full_rate_hz"])[1]
                    > memory_limit_gb(config)[0]):
        return problems  # a record too large for the grid below: named by run_cost_problems
    # The output instants (SimulationSettings.sample_times), valid settings or not.
    time = np.linspace(0.0, duration, int(samples) + 1)
    where = f"simulation.samples = {samples!r} over simulation.duration_s = {duration!r}"
    # The summary's selections (lsbg.stats.steady_state, subgroups_from_window:
    # a time within 1e-9 of a sample spacing of an edge counts as on it),
    # counted here without importing lsbg.stats (statsmodels: seconds per parse).
    tol = 1e-9 * float(np.median(np.diff(time)))
    kept = int(np.sum(time - steady > tol))
    if kept < AD_MIN_SAMPLES:
        problems.append(f"{where}: {kept} samples after statistics.steady_state_after_s = "
                        f"{steady!r}; the statistics (Anderson-Darling) need at least "
                        f"{AD_MIN_SAMPLES}")
    window = int(np.sum((time - start > tol) & (time - stop <= tol)))
    if window == 0 or window % size:
        problems.append(f"{where}: {window} samples in statistics.control_chart_window_s = "
                        f"{[start, stop]!r} (start excluded), which statistics.subgroup_size = "
                        f"{size!r} does not divide into whole subgroups")
    try:
        settings = SimulationSettings.from_config(simulation, engine=config["engines"]["sweep"])
    except ValueError:
        return problems  # the settings themselves: named by _settings_problems
    # The full-rate record and the part of it the summary reads, as
    # lsbg.dynamics.model and lsbg.aggregate.runs.full_rate_series select them.
    times = settings.record_grid()[1]
    full = times[times >= settings.full_rate_start - 0.5 * settings.full_rate_interval]
    spacing = full[1] - full[0] if full.size > 1 else 1.0
    try:
        spectra.sampling_phase_spread(full[full >= steady - 1e-6 * spacing],
                                      settings.full_rate, samples / duration)
    except ValueError as error:
        problems.append(f"{where}: simulation.full_rate_hz = {simulation['full_rate_hz']!r} "
                        f"after statistics.steady_state_after_s = {steady!r}: {error}")
    return problems


# ------------------------------------------------------------ design points
#: lsbg's SI name of each design key (``face_width`` -> ``face_width_mm``).
_DESIGN_KEYS = {re.sub(r"_(mm|deg|kg_m3)$", "", key): key for key in CONFIG_KEYS}


#: A DesignError's message: ``name = value: why``.
_DESIGN_ERROR = re.compile(r"^(\w+) = (.*?): (.*)$", re.DOTALL)


#: A length in metres inside a DesignError's message.
_METRES = re.compile(r"(?<![\w.])([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?) m\b")


#: The design keys each of lsbg's design rules compares a key with (its
#: message names only the key at fault; the others may be the user's mistake,
#: e.g. ``module_mm: 0.01`` leaves the face width too wide).
_DESIGN_DEPENDS = {
    "pinion_teeth": ("gear_teeth",),
    "face_width": ("module_mm", "pinion_teeth", "gear_teeth", "shaft_angle_deg"),
    "addendum": ("module_mm", "normal_pressure_angle_deg", "base_cone_rule"),
    "dedendum": ("addendum_mm", "module_mm"),
    "backlash": ("module_mm", "face_width_mm"),
    "pinion_bore": ("module_mm", "pinion_teeth", "gear_teeth", "face_width_mm", "dedendum_mm"),
    "gear_bore": ("module_mm", "pinion_teeth", "gear_teeth", "face_width_mm", "dedendum_mm"),
    "cutter_radius": ("face_width_mm", "module_mm"),
    "base_cone_rule": ("addendum_mm", "module_mm"),
}


def _design_value(config, key):
    """``design.KEY = value`` as the user wrote it (or its default, so marked)."""
    design = config["design"]
    if key in design:
        return f"design.{key} = {design[key]!r}"
    return f"design.{key} = {GearPairDesign().to_config()[key]!r} (default)"


def _section_values(config, section):
    """Every key the user set in a section, with its value (``design (design.x = 1, ...)``)."""
    values = ", ".join(f"{section}.{key} = {value!r}" for key, value in config[section].items())
    return f"{section} ({values})"


def _value_at(config, path):
    """The value at a key path such as ``sweep.spiral_angles_deg[2]``."""
    value = config
    for name, index in re.findall(r"([^.\[\]]+)|\[(\d+)\]", path):
        value = value[int(index)] if index else value[name]
    return value


def _user_message(error, config, point_keys):
    """A DesignError's message under the user's key and units: (key part, why).

    lsbg.gear.design names the dataclass field (``face_width = 0.5``) and writes
    lengths in metres; the user wrote ``design.face_width_mm: 500``.
    """
    match = _DESIGN_ERROR.match(str(error))
    if not match:
        return "design", str(error)
    name, why = match.group(1), match.group(3)
    why = _METRES.sub(lambda m: f"{float(m.group(1)) * 1e3:.6g} mm", why)
    if name == "spiral_angle":
        return f"{point_keys[0]} = {_value_at(config, point_keys[0])!r}", why
    key = _DESIGN_KEYS.get(name)
    if name in _DESIGN_DEPENDS:
        others = ", ".join(_design_value(config, other) for other in _DESIGN_DEPENDS[name])
        why = f"{why} (with {others})"
    return (_design_value(config, key) if key else f"design ({name} = {match.group(2)})"), why


def _design_problems(config, pairs=None):
    """lsbg's physics checks and the resource guard at every design point: one line
    per key at fault, naming the design points where it fails. ``pairs`` is filled in
    with ``(trace, spiral label) -> lsbg.gear.geometry.GearPair`` of each point that passes."""
    from lsbg.gear.geometry import GearPair

    points = design_points(config)
    failing = {}  # key part -> [why, points]
    limit, source = memory_limit_gb(config)
    minutes = config["limits"]["geometry_minutes"]
    for (trace, spiral), keys in points.items():
        where = f"{trace} {spiral} deg"
        try:
            # numpy's warnings of a hopeless design would print around the message
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                pair = GearPair(GearPairDesign.from_config(
                    {**config["design"], "trace": trace, "spiral_angle_deg": float(spiral)}))
                cost = geometry_cost(pair)
        except DesignError as error:
            head, why = _user_message(error, config, keys)
            failing.setdefault(head, [why, []])[1].append(where)
            continue
        except (ValueError, ArithmeticError) as error:
            # numbers beyond what the formulas survive (e.g. module_mm: 1e300)
            failing.setdefault(_section_values(config, "design"), [
                f"lsbg cannot compute this design ({type(error).__name__}: {error})", []
            ])[1].append(where)
            continue
        beyond = ([f"{cost['memory_gb']:.3g} GB of memory, more than {source} = {limit:.3g} GB"]
                  if cost["memory_gb"] > limit else [])
        if cost["minutes"] > minutes:
            beyond.append(f"{cost['minutes']:.3g} min, more than limits.geometry_minutes = "
                          f"{minutes!r}")
        if beyond:
            # the member whose mesh is the larger: its teeth make the point large
            member = max((1, 2), key=lambda m: cost["vertices"][m])
            head = _design_value(config, ("pinion_teeth", "gear_teeth")[member - 1])
            why = (f"the geometry ({sum(cost['vertices'].values()):.3g} mesh vertices) would "
                   f"need about {' and '.join(beyond)}")
            failing.setdefault(head, [why, []])[1].append(where)
        elif pairs is not None:
            pairs[(trace, spiral)] = pair
    return [f"{head}: {why} (at {_points_named(where, points)})"
            for head, (why, where) in failing.items()]


def _points_named(where, points):
    """The design points ``where`` (names) as a message says them."""
    more = f" and {len(where) - 4} more" if len(where) > 4 else ""
    return "every design point" if len(where) == len(points) else ", ".join(where[:4]) + more


# ------------------------------------------------------------ contact state
def _contact_state_problems(config, pairs):
    """The flank modification, the misalignment and the V-H map's corners at each
    point of ``pairs`` (:func:`lsbg.tca.checks.contact_state_problems`): one line per
    key at fault, naming the design points where it fails."""
    section = config["misalignment_map"]
    odd = [f"misalignment_map.{key} = {section[key]!r}: must be odd (the map's values run "
           f"evenly from -range to +range through the aligned pair, 0 included)"
           for key in ("steps", "sweep_steps") if section[key] % 2 == 0]
    if odd or not pairs:
        return odd
    failing = {}  # key path -> [first line, design points]
    for (trace, spiral), pair in pairs.items():
        map_config = {"axes": list(section["axes"]), "range": section["range"],
                      "steps": map_steps(config, spiral)}
        lines = _point_contact_state(pair, config, trace, spiral, map_config)
        if any(line.startswith("misalignment.") for line in lines):
            # the map is taken about the misalignment: that one is the key at fault
            lines = [line for line in lines if not line.startswith("misalignment_map.")]
        for line in lines:
            line = _user_value(line, config)
            key = line.split(" = ", 1)[0].split(":", 1)[0]
            where = failing.setdefault(key, [line, []])[1]
            if f"{trace} {spiral} deg" not in where:  # (one point: several map corners)
                where.append(f"{trace} {spiral} deg")
    points = design_points(config)
    return [f"{line} (at {_points_named(where, points)})" for line, where in failing.values()]


def _user_value(line, config):
    """The line with its flank_modification key's value as the user wrote it (lsbg
    writes it as read: ``500.0`` for ``500``)."""
    match = re.match(r"^flank_modification\.(\w+) = (.*?): (.*)$", line, re.DOTALL)
    if not (match and match.group(1) in config["flank_modification"]):
        return line
    return (f"flank_modification.{match.group(1)} = "
            f"{config['flank_modification'][match.group(1)]!r}: {match.group(3)}")


def contact_state_cache_dir():
    """Where the contact-state check keeps its answers: ``config-checks`` in lsbg's
    machine-wide cache (:func:`lsbg.numba_cache.numba_cache_root`, beside numba's
    compiled kernels); None (kept by the process only) if ``LSBG_CHECK_CACHE=off``."""
    if os.environ.get("LSBG_CHECK_CACHE", "").lower() in ("0", "off", "no", "false"):
        return None
    from lsbg.numba_cache import numba_cache_root

    return numba_cache_root() / "config-checks"


def _point_contact_state(pair, config, trace, spiral, map_config):
    """lsbg's contact-state problems at one design point, kept for the next start
    (:func:`lsbg.study.stages.cached_answer`: asked again when an input, the topography
    file's content or the sources of the contact_state stage change)."""
    from importlib import metadata

    from lsbg.study.stages import cached_answer

    modification, misalignment = config["flank_modification"], config["misalignment"]
    name = modification.get("topography_file")
    try:
        topography = hashlib.sha256(Path(name).read_bytes()).hexdigest() if name else None
    except OSError:
        topography = "missing"
    inputs = {"design": {**config["design"], "trace": trace, "spiral_angle_deg": float(spiral)},
              "flank_modification": modification, "misalignment": misalignment,
              "misalignment_map": map_config, "topography": topography,
              "versions": [np.__version__, metadata.version("numba")]}

    def compute():
        from lsbg.tca.checks import contact_state_problems

        with warnings.catch_warnings(), np.errstate(all="ignore"):  # (as _design_problems)
            warnings.simplefilter("ignore")
            return contact_state_problems(pair, modification, misalignment, map_config)

    return cached_answer(contact_state_cache_dir(), "contact_state", inputs, compute)
