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
6. every design point: :class:`lsbg.geometry.GearPair` runs lsbg's own
   checks (:mod:`lsbg.design`: proportions, backlash, bores, cutter radius;
   :mod:`lsbg.geometry`: pointed teeth, contact ratio >= 1 under
   interference), their messages mapped back to the design key in mm;
7. the resource guard: each design point's geometry memory and time,
   estimated from its mesh size (:func:`geometry_cost`), against
   ``limits.memory_gb`` and ``limits.geometry_minutes``; each run's record
   against ``limits.memory_gb`` and the line model's slices against the
   runtime the simulation rules request (:func:`_run_cost_problems`).

A YAML syntax error in a ``--configfile`` never reaches this module:
Snakemake 9 reads that file before the Snakefile and stops with
"Config file is not valid JSON or YAML" (without the file or the line;
``--verbose`` adds the YAML parser's message, which names both).
"""

from __future__ import annotations

import copy
import math
import os
import re
import warnings

import numpy as np

from lsbg.design import CONFIG_KEYS, DesignError, GearPairDesign
from lsbg.files import number_label
from lsbg.workflow import (CONTACT_MODELS, design_points, simulation_runtime, speed_keywords,
                           speed_labels)

__all__ = ["check_config", "nonfinite_problems", "schema_problems", "fill_defaults",
           "geometry_cost", "run_memory_gb", "machine_memory_gb", "memory_limit_gb", "key_path"]


def key_path(parts):
    """``["sweep", "spiral_angles_deg", 2]`` -> ``"sweep.spiral_angles_deg[2]"``."""
    text = ""
    for part in parts:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text or "(top level)"


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
    nonfinite = nonfinite_problems(config)
    flagged = {line.split(" = ", 1)[0] for line in nonfinite}
    problems = nonfinite + [line for line in schema_problems(config, schema)
                            if line.split(":", 1)[0] not in flagged]
    if problems:
        return problems
    fill_defaults(config, schema)
    problems = (_name_problems(config) + _settings_problems(config) + _run_cost_problems(config)
                + _statistics_problems(config) + _design_problems(config))
    return list(dict.fromkeys(problems))


# ----------------------------------------------------------- values, schema
def nonfinite_problems(config, where=()):
    """NaN and infinite numbers anywhere in ``config``, one line each.

    Parameters
    ----------
    config : dict or list or scalar
    where : tuple
        Key path of ``config`` itself.

    Returns
    -------
    list of str
    """
    if isinstance(config, dict):
        return [p for key, value in config.items()
                for p in nonfinite_problems(value, (*where, key))]
    if isinstance(config, list):
        return [p for k, value in enumerate(config)
                for p in nonfinite_problems(value, (*where, k))]
    if isinstance(config, float) and not math.isfinite(config):
        return [f"{key_path(where)} = {config!r}: must be a finite number"]
    return []


#: A number YAML 1.1 reads as text: an exponent without a decimal point (1e-6).
_NUMBER_TEXT = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)[eE][-+]?\d+$")


def schema_problems(config, schema):
    """Every violation of the schema, one line each, starting with the key path.

    Parameters
    ----------
    config : dict
    schema : dict
        workflow/schemas/config.schema.yaml, loaded.

    Returns
    -------
    list of str
    """
    import jsonschema

    problems = []
    for error in jsonschema.Draft202012Validator(schema).iter_errors(config):
        where = list(error.absolute_path)
        if error.validator == "additionalProperties":
            known = sorted(error.schema.get("properties", {}))
            problems += [f"{key_path(where + [key])}: unknown key (known: {', '.join(known)})"
                         for key in sorted(set(error.instance) - set(known))]
        elif error.validator == "required":
            problems += [f"{key_path(where + [key])}: missing (a required key)"
                         for key in error.validator_value if key not in error.instance]
        else:
            hint = ""
            if (error.validator == "type" and isinstance(error.instance, str)
                    and _NUMBER_TEXT.match(error.instance)):
                hint = (f" (YAML reads {error.instance} as text: write the mantissa with a "
                        f"decimal point, e.g. 1.0e-6)")
            problems.append(f"{key_path(where)}: {error.message}{hint}")
    return sorted(problems)


def fill_defaults(config, schema):
    """Fill in the schema's ``default`` of every missing key, in place.

    The same as ``snakemake.utils.validate(config, schema, set_default=True)``
    for this schema (objects nested in ``properties`` only): a section left
    out takes its default (e.g. ``{}``), whose own keys then take theirs.

    Parameters
    ----------
    config : dict
        Valid under ``schema``.
    schema : dict
    """
    for key, subschema in schema.get("properties", {}).items():
        if key not in config and "default" in subschema:
            # a copy: the schema's default objects must not be filled in themselves
            config[key] = copy.deepcopy(subschema["default"])
        if isinstance(config.get(key), dict):
            fill_defaults(config[key], subschema)


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
    from lsbg.sensitivity import case_name

    problems = _label_clashes(config["sweep"]["spiral_angles_deg"], "sweep.spiral_angles_deg")
    for key, factors in config["sensitivity"].items():
        problems += _label_clashes(factors, f"sensitivity.{key}",
                                   label=lambda factor, key=key: case_name(key, factor))
    if config.get("load_sweep"):
        problems += _label_clashes(config["load_sweep"]["torques_N_m"], "load_sweep.torques_N_m")
    return problems


# ----------------------------------------------------------------- settings
def _settings_problems(config):
    """The engines, simulation, contact, sensitivity, speed and load sweeps as lsbg
    reads them (:mod:`lsbg.dynamics`, :mod:`lsbg.contact`, :mod:`lsbg.speed`)."""
    from lsbg.contact import ContactParameters
    from lsbg.dynamics import SimulationSettings
    from lsbg.sensitivity import scaled_contact

    problems = []
    engines = config["engines"]
    sweep_engine, reference = engines["sweep"], engines["reference"]
    if engines["paper"] not in {sweep_engine, *reference.get("point", [])}:
        problems.append(f"engines.paper = {engines['paper']!r}: must be engines.sweep or one of "
                        f"engines.reference.point {reference.get('point', [])!r} (the paper "
                        f"report reproduces the paper with the point model)")
    engines_failing = {}  # message -> engines
    for engine in sorted(_engines_run(config)):
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
        problems += _speed_sweep_problems(config)
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


def _speed_sweep_problems(config):
    """The speed sweep's settings, checked as ``lsbg speed-run`` will use them."""
    from lsbg.dynamics import SimulationSettings
    from lsbg.speed import speed_settings

    speed = config["speed_sweep"]
    grid = speed["pinion_speeds_deg_s"]
    problems = []
    angle = speed.get("spiral_angle_deg", config["paper_spiral_angle_deg"])
    if number_label(angle) != number_label(config["paper_spiral_angle_deg"]):
        swept = {number_label(a) for a in config["sweep"]["spiral_angles_deg"]}
        missing = [t for t in speed["traces"]
                   if t not in config["sweep"]["traces"] or number_label(angle) not in swept]
        if missing:
            problems.append(f"speed_sweep.spiral_angle_deg = {angle!r}: no design point of "
                            f"{', '.join(missing)} there (use paper_spiral_angle_deg or an "
                            f"angle of sweep.spiral_angles_deg)")
    try:
        speeds, labels = speed_labels(grid)
    except ValueError as error:
        return [f"speed_sweep.pinion_speeds_deg_s = {grid!r}: {error}"]
    if len(set(labels)) < len(labels):
        problems.append(f"speed_sweep.pinion_speeds_deg_s = {grid!r}: speeds too close to "
                        f"tell apart in file names")
    try:
        base = SimulationSettings.from_config(config["simulation"], engine=speed["engine"])
    except ValueError:
        return problems  # the simulation settings themselves: named by _settings_problems
    teeth = config["design"].get("pinion_teeth", GearPairDesign.pinion_teeth)
    limit, source = memory_limit_gb(config)
    for value in (speeds[0], speeds[-1]):
        at = (f"speed_sweep.pinion_speeds_deg_s = {grid!r}: the run at "
              f"{math.degrees(value):.6g} deg/s")
        try:
            run = speed_settings(base, value, teeth, **speed_keywords(speed))
        except ValueError as error:
            # a setting lsbg.speed derives for the run ("full_rate = ...: why")
            why = str(error).split(": ", 1)[-1]
            problems.append(f"{at} (speed_sweep.engine = {speed['engine']!r}): {why}")
            continue
        instants, need = run_memory_gb(run.samples, run.duration, run.full_rate)
        if need > limit:
            problems.append(f"{at} records {instants:.3g} instants over {run.duration:.3g} s "
                            f"(speed_sweep.mesh_cycles = {speed['mesh_cycles']!r}, "
                            f"min_window_s = {speed['min_window_s']!r}, samples_per_mesh = "
                            f"{speed['samples_per_mesh']!r}), about {need:.3g} GB, more than "
                            f"{source} = {limit:.3g} GB")
    return problems


# --------------------------------------------------------------- statistics
#: Fewest samples of lsbg.stats.anderson_darling (the summary's normality test).
AD_MIN_SAMPLES = 3
#: Memory of a run: a base and the bytes per recorded instant [GB, B]. Measured
#: 160 B per instant and 0.26 GB (``lsbg simulate --engine compiled``, 0.05 s,
#: full rate 2 and 8 MHz: 80 000 and 320 000 instants, 275 and 313 MB peak);
#: three times that per instant covers the other engines' working copies.
RUN_MEMORY_BASE_GB = 0.26
RUN_BYTES_PER_INSTANT = 500
#: Wall time of the line model per slice and simulated second, compiled
#: engine [s]: 1.6, 1.4 and 5.4 s for 20, 200 and 2000 slices over 0.05 s
#: simulated (``lsbg simulate --engine compiled --contact-model line``).
LINE_SECONDS_PER_SLICE = 0.039
#: Wall time of one PyBullet step [s] (README: 7.67 us, tests/benchmarks/bench_dynamics.py).
PYBULLET_SECONDS_PER_STEP = 7.67e-6


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
    from lsbg import spectra
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
        return problems  # a record too large for the grid below: named by _run_cost_problems
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
    # lsbg.dynamics.model and lsbg.runs.full_rate_series select them.
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


def run_memory_gb(samples, duration, full_rate):
    """Instants a run records [-] and the memory it needs [GB].

    Parameters
    ----------
    samples : int
        Output intervals [-].
    duration : float
        Simulated time [s].
    full_rate : float
        Rate of the full-rate record [1/s].
    """
    instants = samples + 1 + duration * full_rate
    return instants, RUN_MEMORY_BASE_GB + instants * RUN_BYTES_PER_INSTANT / 1e9


def _run_cost_problems(config):
    """The resource guard of the runs: each run's record against the memory limit,
    and the line model's slices against the runtime the simulation rules request.

    A run records ``samples + 1`` output instants and ``full_rate_hz`` per
    second (:data:`RUN_BYTES_PER_INSTANT`). A line-model step costs in
    proportion to the slices (:data:`LINE_SECONDS_PER_SLICE`, the compiled
    engine, the fastest: the estimate is a lower bound); the rules request
    :func:`lsbg.workflow.simulation_runtime` minutes per run.
    """
    from lsbg.sensitivity import scaled_contact

    simulation = config["simulation"]
    duration, samples, rate = (simulation["duration_s"], simulation["samples"],
                               simulation["full_rate_hz"])
    problems = []
    instants, need = run_memory_gb(samples, duration, rate)
    limit, source = memory_limit_gb(config)
    if need > limit:
        problems.append(f"simulation.samples = {samples!r}, simulation.full_rate_hz = {rate!r}: "
                        f"each run records {instants:.3g} instants over simulation.duration_s "
                        f"= {duration!r}, about {need:.3g} GB, more than {source} = "
                        f"{limit:.3g} GB")
    budget = simulation_runtime(config)
    slices = [("contact.slices", config["contact"]["slices"], config["contact"]["slices"])]
    slices += [(f"sensitivity.slices[{k}]", factor,
                scaled_contact(config["contact"], "slices", factor)["slices"])
               for k, factor in enumerate(config["sensitivity"].get("slices", []))]
    for key, value, count in slices:
        minutes = LINE_SECONDS_PER_SLICE * count * duration / 60
        if minutes > budget:
            problems.append(f"{key} = {value!r}: a line-model run of {count} slices over "
                            f"simulation.duration_s = {duration!r} takes at least "
                            f"{minutes:.3g} min, more than the {budget} min its rule requests")
    step = simulation["time_step_s"]
    minutes = PYBULLET_SECONDS_PER_STEP * duration / step / 60
    if "pybullet" in _engines_run(config) and minutes > budget:
        problems.append(f"simulation.time_step_s = {step!r}: a PyBullet run of "
                        f"{duration / step:.3g} steps over simulation.duration_s = "
                        f"{duration!r} takes about {minutes:.3g} min, more than the {budget} "
                        f"min its rule requests")
    return problems


def _engines_run(config):
    """Every engine some run of the study uses."""
    engines = config["engines"]
    run = {engines["sweep"], *(e for model in CONTACT_MODELS
                               for e in engines["reference"].get(model, []))}
    if config.get("load_sweep"):
        run.add(config["load_sweep"].get("engine", engines["sweep"]))
    if config.get("speed_sweep"):
        run.add(config["speed_sweep"]["engine"])
    return run


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

    lsbg.design names the dataclass field (``face_width = 0.5``) and writes
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


def _design_problems(config):
    """lsbg's physics checks and the resource guard at every design point: one line
    per key at fault, naming the design points where it fails."""
    from lsbg.geometry import GearPair

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
    problems = []
    for head, (why, where) in failing.items():
        at = ("every design point" if len(where) == len(points) else
              ", ".join(where[:4]) + (f" and {len(where) - 4} more" if len(where) > 4 else ""))
        problems.append(f"{head}: {why} (at {at})")
    return problems


# ----------------------------------------------------------- resource guard
#: Geometry cost model (:func:`geometry_cost`), fitted to ``lsbg geometry``
#: of the paper's design with 37 to 40 000 gear teeth (43 thousand to 7.9
#: million mesh vertices): peak memory = base + per vertex, wall time =
#: base + per vertex * (vertices / 1e6)**(exponent - 1).
GEOMETRY_MEMORY_BASE_GB = 0.29
GEOMETRY_BYTES_PER_VERTEX = 500.0
GEOMETRY_SECONDS_BASE = 3.0
GEOMETRY_SECONDS_PER_VERTEX = 20e-6
GEOMETRY_TIME_EXPONENT = 1.2


def geometry_cost(pair):
    """Estimated peak memory and wall time of ``lsbg geometry`` for a design point.

    The geometry stage builds both solid meshes (:func:`lsbg.solids.gear_mesh`)
    and works on arrays of their vertices and triangles (mass properties,
    STL, the rendered picture); its cost grows with the vertex count and is
    otherwise nearly constant (the exact flanks, ``flanks.nc``). The vertex
    count is estimated without building a mesh, from the same resolution
    (:data:`lsbg.solids.DEFAULT_RESOLUTION`): per member, the lofted sections
    times the teeth times the outline points per tooth, plus on each end
    face a ring of at least z points per ``end_face_step`` of polar angle
    between bore and root and the cap area over ``end_face_step**2``
    (within 15 % of the actual count over 9 to 3000 teeth).

    Calibration: ``lsbg -v geometry --gear-teeth Z`` (the paper's design
    otherwise) on 2 shared cores, 23.5 GB, load average 2-4 (a second series
    at load 3.6-5.7 in its own column); vertices measured from the STL
    triangle counts / 2; the model's figures from the estimated count:

    ======  ========  =========  ========  ===========  =====  ========  =====
    z2      vertices  estimated  wall [s]  (high load)  model  RSS [GB]  model
    ======  ========  =========  ========  ===========  =====  ========  =====
    37      43 k      38 k       3.1                    3.4    0.29      0.31
    1 000   201 k     230 k      4.8                    6.4    0.35      0.41
    3 000   598 k     660 k      10.7                   15     0.53      0.62
    5 000             1.08 M               55           25     0.67      0.83
    10 000  1.98 M    2.16 M     36                     53     1.19      1.37
    20 000  3.96 M    4.30 M     109       151          118    2.14      2.44
    40 000  7.92 M    8.58 M     246       388          267    4.13      4.58
    ======  ========  =========  ========  ===========  =====  ========  =====

    Memory: 0.29 GB + 500 B per vertex; the measured
    slope is 480-495 B per vertex and the same in both series, so with the
    estimate's 8-15 % excess the model stays 7-17 % above the measurement.
    Time: 3 s + 20 us per vertex times (vertices / 1e6)**0.2: the cost per
    vertex rises from 11 to 31 us over the table (meshing and the picture
    outgrow the caches), which the exponent 1.2 follows; the wall time also
    grows with the machine's load (up to 1.6 times above). For
    ``design.gear_teeth: 100000`` (21 M vertices estimated) the model gives
    11 GB and 13 min; the default ``limits.geometry_minutes`` of 10 min
    admits up to about 79 000 teeth on the paper's pinion.

    Parameters
    ----------
    pair : lsbg.geometry.GearPair

    Returns
    -------
    dict
        ``vertices`` ({member: estimated vertex count} [-]), ``memory_gb``
        [GB], ``minutes`` [min].
    """
    from lsbg import solids
    from lsbg.geometry import MEMBERS

    design, resolution = pair.design, solids.DEFAULT_RESOLUTION
    step = resolution.end_face_step
    vertices = {}
    for member in MEMBERS:
        teeth = design.teeth[member - 1]
        sections = solids.section_cone_distances(pair, member, resolution).size
        # the outline counts at the mean point (cheap: one flank of 201 points)
        flank, top, root_arc = solids._outline_counts(pair, member, resolution)
        per_tooth = 2 * (flank + resolution.extension) + top + root_arc
        bore = (design.pinion_bore if member == 1 else design.gear_bore) / 2
        theta_bore = math.asin(min(1.0, bore / design.inner_cone_distance))
        root = design.root_angle(member)
        rings = max(0, math.ceil((root - theta_bore) / step))
        cap = 2 * math.pi * (math.cos(theta_bore) - math.cos(root)) / step**2
        vertices[member] = sections * teeth * per_tooth + 2 * (teeth * rings + cap)
    total = sum(vertices.values())
    seconds = (GEOMETRY_SECONDS_BASE + GEOMETRY_SECONDS_PER_VERTEX * total
               * (total / 1e6) ** (GEOMETRY_TIME_EXPONENT - 1))
    return {"vertices": vertices,
            "memory_gb": GEOMETRY_MEMORY_BASE_GB + GEOMETRY_BYTES_PER_VERTEX * total / 1e9,
            "minutes": seconds / 60}


def machine_memory_gb():
    """Physical memory of this machine [GB], or None where the OS does not tell."""
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 1e9
    except (AttributeError, ValueError, OSError):
        return None


def memory_limit_gb(config):
    """The memory a job may use [GB] and the words that name where it comes from."""
    limit = config["limits"].get("memory_gb")
    if limit is not None:
        return limit, "limits.memory_gb"
    machine = machine_memory_gb()
    if machine is None:
        return math.inf, "limits.memory_gb (unset)"
    return machine, "limits.memory_gb (default: this machine's memory)"
