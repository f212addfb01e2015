"""The complete configuration check (lsbg.study.checks): every invalid value is rejected
before any job, naming the user's key path and value.

Most cases run through :func:`lsbg.study.checks.check_config`, the function
workflow/rules/common.smk calls: a fuzz suite generated from the schema
(every key with a wrong type, out of its range, NaN/inf, empty, duplicated,
rounded to an existing file name, and unknown keys) and the checks beyond the
schema (cross-field rules, sample counts, physics, resource guard). A handful
run ``python -m snakemake -n`` end to end: one clean message, no stack lines,
nothing created.
"""

import copy
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from lsbg.config import merge_config
from lsbg.study import checks as config_check, resources, plan
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair

REPO = Path(__file__).resolve().parents[2]
SCHEMA = yaml.safe_load((REPO / "lsbg" / "schemas" / "config.schema.yaml")
                        .read_text(encoding="utf-8"))

#: The optional sections, small, so that the fuzz suite reaches their keys too.
OPTIONAL_SECTIONS = {
    "speed_sweep": {"traces": ["logarithmic"], "spiral_angle_deg": 35,
                    "pinion_speeds_deg_s": {"start": 3000, "stop": 9000, "count": 3},
                    "engine": "compiled", "mesh_cycles": 100, "min_window_s": 0.05,
                    "settle_time_s": 0.05, "ramp_time_s": 0.05, "samples_per_mesh": 32},
    "sweeps": {"s": {"contact.dynamic_friction": [0, 0.1], "traces": ["logarithmic"],
                     "engine": "compiled", "contact_model": "point", "batch_size": 2}},
    "extensions": ["mesh_mode"],
    "limits": {"memory_gb": 8, "geometry_minutes": 10},
}


def load(*names):
    """workflow/config.yaml with other config files merged over it (as --configfile), the
    study's spiral angle set where design.spiral_angle_deg asks (as the check does)."""
    given = {}
    for name in names:
        given = merge_config(given, yaml.safe_load((REPO / "workflow" / name).read_text(
            encoding="utf-8")))
    config = merge_config(yaml.safe_load((REPO / "workflow" / "config.yaml").read_text(
        encoding="utf-8")), given)
    assert config_check.one_spiral_angle(config, given) == []
    return config


BASE = {**load("config-test.yaml"), **OPTIONAL_SECTIONS}


def base():
    """The test study with every optional section: valid, two design points."""
    return copy.deepcopy(BASE)


def with_value(config, path, value):
    """A copy of ``config`` with ``value`` at the key path ``path`` (parents made)."""
    config = copy.deepcopy(config)
    parent = config
    for part in path[:-1]:
        parent = parent.setdefault(part, {}) if isinstance(part, str) else parent[part]
    parent[path[-1]] = value
    return config


#: lsbg's SI field names (``face_width = 0.5``) and rules (``ContactParameters.``):
#: never in a message to the user.
INTERNAL = re.compile(r"(?:^|: |\()(module|face_width|addendum|dedendum|backlash|cutter_radius|"
                      r"pinion_bore|gear_bore|shaft_angle|spiral_angle|duration|samples|"
                      r"ramp_time|time_step|full_rate|full_rate_after|slices) = "
                      r"|ContactParameters\.")


def assert_rejected(problems, key):
    """Rejected, naming ``key``, each problem one line in the user's names."""
    assert problems, f"{key}: accepted"
    assert any(key in line for line in problems), (key, problems)
    for line in problems:
        assert "\n" not in line and not INTERNAL.search(line), line


# ------------------------------------------------- fuzz suite from the schema
def valid_item(schema):
    """A value the (scalar) ``schema`` accepts."""
    if "enum" in schema:
        return schema["enum"][0]
    low = schema.get("minimum", schema.get("exclusiveMinimum", 0))
    high = schema.get("maximum", schema.get("exclusiveMaximum", low + 2))
    value = (low + high) / 2
    return round(value) if schema.get("type") == "integer" else value


def bad_values(schema):
    """(category, value) pairs that ``schema`` (of one value) rejects."""
    kind = schema.get("type")
    if isinstance(kind, list):  # a type or null: the bad values of the type
        (kind,) = [k for k in kind if k != "null"]
        if kind == "string":
            return [("wrong type", 7), ("wrong type", ["a.csv"])]
        return bad_values({**schema, "type": kind})
    if "oneOf" in schema:  # a choice or a number (rating.dynamic_factor) or a list
        # (trace_study.spiral_angles_deg): the other's bad values that are no choice either,
        # and a word that is no choice
        other = next(s for s in schema["oneOf"] if s.get("type") in ("number", "integer",
                                                                     "array"))
        return [("not one of the choices", "no-such-choice")] + [
            (category, value) for category, value in bad_values(other)
            if category not in ("wrong type",)]
    if "enum" in schema:
        return [("not one of the choices", "no-such-choice"), ("wrong type", 7)]
    if kind in ("number", "integer"):
        out = [("wrong type", "text"), ("wrong type", True)]
        if kind == "integer":
            out.append(("not whole", 2.5))
        else:
            out += [("NaN", math.nan), ("inf", math.inf), ("-inf", -math.inf)]
        if "minimum" in schema:
            out.append(("below the minimum", schema["minimum"] - 1))
        if "exclusiveMinimum" in schema:
            out.append(("at the exclusive minimum", schema["exclusiveMinimum"]))
        if "maximum" in schema:
            out.append(("above the maximum", 2 * schema["maximum"] + 1))
        if "exclusiveMaximum" in schema:
            out.append(("at the exclusive maximum", schema["exclusiveMaximum"]))
        return out
    if kind == "array":
        item = valid_item(schema["items"])
        out = [("wrong type", "text")]
        if schema.get("minItems"):
            out.append(("too short", [item] * (schema["minItems"] - 1)))
        if "maxItems" in schema:
            out.append(("too long", [item] * (schema["maxItems"] + 1)))
        if schema.get("uniqueItems"):
            out.append(("duplicate", [item, item]))
        return out
    if kind == "object":
        return [("wrong type", [1, 2])]
    if kind == "boolean":
        return [("wrong type", "yes"), ("wrong type", 1)]
    if kind == "string" and "pattern" in schema:
        return [("wrong type", 7), ("not matching its pattern", "no such/name")]
    raise AssertionError(f"no invalid values for {schema}")


def fuzz_variants(schema=SCHEMA, path=()):
    """Every invalid variant of the configuration the schema describes:
    ``(name, key path to set, value, key path the message must name)``."""
    variants = []
    if schema.get("additionalProperties") is False:
        where = [*path, "no_such_key"]
        variants.append((f"{config_check.key_path(where)}: unknown key", where, 1,
                         config_check.key_path(where)))
    for key in schema.get("required", []) if path else []:
        variants.append((f"{config_check.key_path(path)}: empty (no {key})", list(path), {},
                         config_check.key_path([*path, key])))
    for key, sub in schema.get("properties", {}).items():
        where = [*path, key]
        name = config_check.key_path(where)
        variants += [(f"{name}: {category}", where, value, name)
                     for category, value in bad_values(sub)]
        if sub.get("type") == "object":
            variants += fuzz_variants(sub, where)
        if sub.get("type") == "array":
            item = [*where, 0]
            variants += [(f"{name}[0]: {category}", where, [value],
                          config_check.key_path(item))
                         for category, value in bad_values(sub["items"])]
    return variants


#: Sweep values that name files: two that differ below the names' 6 decimals.
ROUNDED = [(["sweep", "spiral_angles_deg"], [30, 30.0000001]),
           (["sensitivity", "mesh_damping_ratio"], [2, 2.0000001]),
           (["sensitivity", "line_stiffness_N_per_mm_um"], [0.5, 0.5000000001]),
           (["sensitivity", "slices"], [2, 2.0000002])]
VARIANTS = fuzz_variants() + [
    (f"{config_check.key_path(path)}: same file name", path, values,
     config_check.key_path([*path, 1])) for path, values in ROUNDED]


def test_the_fuzz_suite_covers_every_key_of_the_schema():
    assert len(VARIANTS) >= 80
    keys = set()

    def walk(schema, path):
        for key, sub in schema.get("properties", {}).items():
            keys.add(config_check.key_path([*path, key]))
            walk(sub, [*path, key])

    walk(SCHEMA, [])
    assert keys <= {config_check.key_path(where) for _, where, _, _ in VARIANTS}
    assert config_check.check_config(base(), SCHEMA) == []


@pytest.mark.parametrize("name, where, value, key", VARIANTS, ids=[v[0] for v in VARIANTS])
def test_every_invalid_value_is_rejected_naming_its_key(name, where, value, key):
    assert_rejected(config_check.check_config(with_value(base(), where, value), SCHEMA), key)


# ------------------------------------------------------- beyond the schema
BEYOND_SCHEMA = {
    # cross-field rules of the run and the statistics
    "steady state after the run": ({"simulation": {"duration_s": 0.005}},
                                   "statistics.steady_state_after_s = 0.01"),
    "chart window beyond the run": ({"statistics": {"control_chart_window_s": [0.01, 1.5]}},
                                    "statistics.control_chart_window_s"),
    "chart window reversed": ({"statistics": {"control_chart_window_s": [0.04, 0.02]}},
                              "statistics.control_chart_window_s = [0.04, 0.02]"),
    "chart window in the transient": ({"statistics": {"control_chart_window_s": [0.0, 0.05]}},
                                      "statistics.control_chart_window_s"),
    "two samples": ({"simulation": {"samples": 2}}, "simulation.samples = 2"),
    "subgroups that do not fit the window": ({"statistics": {"subgroup_size": 3}},
                                             "statistics.subgroup_size = 3"),
    "ramp longer than the run": ({"simulation": {"ramp_time_s": 2.0}},
                                 "simulation.ramp_time_s = 2.0"),
    "full rate that does not divide the sampling": ({"simulation": {"full_rate_hz": 33333}},
                                                    "simulation.full_rate_hz = 33333"),
    "a record beyond the memory": ({"simulation": {"full_rate_hz": 5e12}},
                                   "simulation.full_rate_hz"),
    # engines, contact, sensitivity, speed sweep
    "paper engine not run": ({"engines": {"sweep": "compiled", "reference": {"point": ["scipy"]},
                                          "paper": "pybullet"}}, "engines.paper = 'pybullet'"),
    "driveline under the pybullet engine": ({"simulation": {"boundary": "driveline"}},
                                            "simulation.boundary = 'driveline': the pybullet"),
    "a driveline case on the pybullet sweep engine": (
        {"engines": {"sweep": "pybullet", "reference": {"point": ["pybullet"], "line": ["scipy"]}}},
        "sensitivity.boundary[0] = 'driveline': gives simulation.boundary = 'driveline'"),
    "a boundary case that is the study's own": (
        {"sensitivity": {"boundary": ["prescribed_pinion"]}},
        "sensitivity.boundary[0] = 'prescribed_pinion': the study's own setting"),
    "a speed case of factor 1": ({"sensitivity": {"pinion_speed": [1]}},
                                 "sensitivity.pinion_speed[0] = 1: the study's own setting"),
    "friction velocity below stiction": ({"contact": {"friction_velocity_mm_s": 0.05}},
                                         "contact.stiction_velocity_mm_s = 0.1"),
    "sensitivity that halves the slices below 2": (
        {"contact": {"slices": 2}, "sensitivity": {"slices": [0.5]}}, "sensitivity.slices[0]"),
    "sensitivity beyond the damping range": ({"sensitivity": {"mesh_damping_ratio": [100]}},
                                             "sensitivity.mesh_damping_ratio[0] = 100"),
    "practice cells of no sensitivity key": (
        {"practice": {"sensitivity": ["crowning", "stiffness"]}},
        "practice.sensitivity[1] = 'stiffness': must be a key of the sensitivity section"),
    # absurd but finite: loads and speeds the teeth cannot carry, a mesh frequency the
    # full-rate record cannot resolve
    "a load no tooth carries": ({"simulation": {"load_torque_N_m": 1e12}},
                                "simulation.load_torque_N_m = 1000000000000.0: the gear's peak "
                                "torque 1e+12 N m is beyond what the teeth can carry"),
    "a speed whose ramp no tooth carries": (
        {"simulation": {"pinion_speed_deg_s": 700000, "ramp_time_s": 0.0005}},
        "simulation.pinion_speed_deg_s = 700000 (with simulation.ramp_time_s = 0.0005"),
    "a mesh frequency beyond the full-rate record": (
        {"simulation": {"pinion_speed_deg_s": 2e6}},
        "its tooth-mesh frequency 5e+04 Hz is beyond the full-rate record's Nyquist"),
    "speeds too close for file names": (
        {"speed_sweep": {"pinion_speeds_deg_s": {"start": 10, "stop": 10.0001, "count": 5}}},
        "speed_sweep.pinion_speeds_deg_s"),
    "speed sweep at no design point": ({"speed_sweep": {"spiral_angle_deg": 33}},
                                       "speed_sweep.spiral_angle_deg = 33"),
    "spiral angle named 0": ({"sweep": {"spiral_angles_deg": [35, 1e-7]}},
                             "sweep.spiral_angles_deg[1] = 1e-07"),
    # physics of every design point, in the user's keys and mm
    "face width beyond half the cone distance": ({"design": {"face_width_mm": 500}},
                                                 "design.face_width_mm = 500"),
    "tiny module": ({"design": {"module_mm": 0.01}}, "design.module_mm = 0.01"),
    "huge module": ({"design": {"module_mm": 1e6}}, "design.module_mm = 1000000.0"),
    "backlash beyond a tenth of the pitch": ({"design": {"backlash_mm": 5}},
                                             "design.backlash_mm = 5"),
    "addendum beyond 1.25 module": ({"design": {"addendum_mm": 7}}, "design.addendum_mm = 7"),
    "dedendum below the addendum": ({"design": {"dedendum_mm": 3}}, "design.dedendum_mm = 3"),
    "cutter radius too small": ({"design": {"cutter_radius_mm": 10}},
                                "design.cutter_radius_mm = 10"),
    # 23 mm spans the face as the paper's arc but not as ISO 23509's circle in the pitch
    # plane (sin beta = 0.998 at the heel): the practice pair's SBG and a sweep's
    "cutter radius the practice design's face-milled SBG cannot span": (
        {"design": {"cutter_radius_mm": 23}}, "design.cutter_radius_mm = 23: is too small"),
    "cutter radius a face-milled sweep point cannot span": (
        {"design": {"cutter_radius_mm": 23}, "practice": {"sbg_trace": "circular"},
         "sweep": {"traces": ["face_milled"]}}, "design.cutter_radius_mm = 23: is too small"),
    # the trace study's cells (lsbg.optimise.cells): an angle the study has no geometry of,
    # a cutter the practice design's face-milled SBG cannot span at an angle of the section
    "a trace-study angle outside the sweep": (
        {"trace_study": {"spiral_angles_deg": [35, 33]}},
        "trace_study.spiral_angles_deg[1] = 33: not the paper's angle"),
    "a trace-study cutter that cannot span the face": (
        {"trace_study": {"cutter_radii_mm": [76.2, 23]}},
        "trace_study.cutter_radii_mm[1] = 23: at 35 deg cannot span the face"),
    "a trace-study cutter outside the usual radii": (
        {"trace_study": {"cutter_radii_mm": [400]}},
        "trace_study.cutter_radii_mm[0] = 400: at 35 deg is outside the usual cutter radii"),
    "a trace study without the searches": (
        {"trace_study": {"cutter_radii_mm": "sweep"}, "optimise": {"enabled": False}},
        "trace_study.cutter_radii_mm = 'sweep': compares the ease-off searches' fronts"),
    "bore through the teeth": ({"design": {"gear_bore_mm": 500}}, "design.gear_bore_mm = 500"),
    "pinion larger than the gear": ({"design": {"pinion_teeth": 40}},
                                    "design.pinion_teeth = 40"),
    "pointed teeth": ({"design": {"normal_pressure_angle_deg": 30, "addendum_mm": 5.6,
                                  "dedendum_mm": 7}}, "design.addendum_mm = 5.6"),
    "trace is not a design key": ({"design": {"trace": "circular"}}, "design.trace"),
    # the depth's taper (lsbg.gear.depth): no dedendum at the toe, a pointed pinion or
    # gear, a taper the flank stages do not build
    "a taper that leaves no dedendum at the toe": (
        {"design": {"depth_taper": "given_dedendum_angles", "dedendum_angles_deg": [18, 2]}},
        "design.dedendum_angles_deg = [18, 2]: leaves the pinion no dedendum at the toe"),
    "a taper that points the pinion": (
        {"design": {"depth_taper": "given_dedendum_angles", "dedendum_angles_deg": [0, -4]}},
        "design.dedendum_angles_deg = [0, -4]: the pinion teeth come out pointed"),
    "a taper that points the gear": (
        {"design": {"depth_taper": "given_dedendum_angles", "dedendum_angles_deg": [-12, 0]}},
        "design.dedendum_angles_deg = [-12, 0]: the gear teeth come out pointed"),
    "dedendum angles without their taper": ({"design": {"dedendum_angles_deg": [2, 6]}},
                                            "design.dedendum_angles_deg = [2, 6]"),
    "a taper the flank stages do not build": ({"design": {"depth_taper": "uniform"}},
                                              "design.depth_taper = 'uniform': lsbg's flanks"),
    # the matched designs: the full runs are of the pairs
    "more full runs than pairs": ({"optimise": {"matched": {"pairs": 4, "full_runs": 5}}},
                                  "optimise.matched.full_runs = 5: at most "
                                  "optimise.matched.pairs = 4"),
    # the resource guard
    "a gear of 100000 teeth": ({"design": {"gear_teeth": 100000}},
                               "design.gear_teeth = 100000"),
    "a memory limit below any point": ({"limits": {"memory_gb": 0.1}}, "limits.memory_gb = 0.1"),
    "slices beyond the run's time": ({"contact": {"slices": 10**6}}, "contact.slices = 1000000"),
    "a PyBullet step far too small": ({"simulation": {"time_step_s": 1e-12}},
                                      "simulation.time_step_s = 1e-12"),
    "a speed sweep beyond the memory": ({"speed_sweep": {"mesh_cycles": 10**9}},
                                        "speed_sweep.mesh_cycles = 1000000000"),
    "a design beyond lsbg's arithmetic": ({"design": {"module_mm": 1e300}},
                                          "design.module_mm = 1e+300"),
    "a sensitivity case of too many slices": ({"sensitivity": {"slices": [2e4]}},
                                              "sensitivity.slices[0] = 20000.0"),
    # the contact state at every design point (lsbg.tca.checks)
    "map steps even": ({"misalignment_map": {"steps": 4}}, "misalignment_map.steps = 4"),
    "sweep map steps even": ({"misalignment_map": {"sweep_steps": 6}},
                             "misalignment_map.sweep_steps = 6"),
    "crowning beyond the backlash": ({"flank_modification": {"lengthwise_crowning_um": 500}},
                                     "flank_modification.lengthwise_crowning_um = 500"),
    "bias beyond the backlash": ({"flank_modification": {"bias_um": -200}},
                                 "flank_modification.bias_um = -200"),
    "a gear pushed into mesh": ({"misalignment": {"gear_axial_G_mm": -0.5}},
                                "misalignment.gear_axial_G_mm = -0.5"),
    "a map whose corners interfere": ({"misalignment_map": {"range": 0.5}},
                                      "misalignment_map.range = 0.5"),
    "a map of G closing the backlash": ({"misalignment_map": {"axes": ["G", "P"]}},
                                        "misalignment_map.range = 0.1 (G = -0.1"),
    "a topography file that is not there": (
        {"flank_modification": {"topography_file": "no-such-relief.csv"}},
        "flank_modification.topography_file = 'no-such-relief.csv': no such file"),
}


def beyond_schema(name):
    """The test study with the overrides of BEYOND_SCHEMA[name], and the key it names."""
    overrides, key = BEYOND_SCHEMA[name]
    config = base()
    for section, values in overrides.items():
        config[section] = {**config.get(section, {}), **values}
    return config, key


@pytest.mark.parametrize("name", BEYOND_SCHEMA)
def test_checks_beyond_the_schema_name_the_key_and_value(name):
    config, key = beyond_schema(name)
    problems = config_check.check_config(config, SCHEMA)
    assert_rejected(problems, key)
    if name.endswith("module"):  # the key at fault, in mm, not lsbg's metres
        assert not re.search(r"\d m\b", " ".join(problems)), problems
    if key.startswith(("flank_modification.", "misalignment")):
        # one line for the key, naming the design points (both, here)
        assert len(problems) == 1 and problems[0].startswith(key), problems
        assert ("(at every design point)" in problems[0] or "steps" in key
                or "topography_file" in key), problems


#: The cases only an analysis at the design points finds (a TCA: the workflow's onstart).
ANALYSED = {"crowning beyond the backlash", "bias beyond the backlash", "a gear pushed into mesh",
            "a map whose corners interfere", "a map of G closing the backlash"}


@pytest.mark.parametrize("name", BEYOND_SCHEMA)
def test_all_but_the_analyses_are_found_while_the_workflow_is_parsed(name):
    config, key = beyond_schema(name)
    problems = config_check.check_config(config, SCHEMA, analyses=False)
    if name in ANALYSED:
        assert problems == [], problems
    else:
        assert_rejected(problems, key)


def test_contact_state_is_checked_at_each_point_with_its_steps(monkeypatch):
    """lsbg.tca.checks runs once per design point that passed the physics, with the map
    section and the steps of that point; identical lines are one line naming the points."""
    import lsbg.tca.checks

    calls = []

    def fake(pair, modification, misalignment, map_config):
        calls.append((pair.design.trace, round(math.degrees(pair.design.spiral_angle), 6),
                      map_config["steps"]))
        if pair.design.trace == "circular":
            return ["misalignment_map.range = 0.1 (E = 0.1, P = 0.1): the members interfere"]
        return []

    monkeypatch.setattr(lsbg.tca.checks, "contact_state_problems", fake)
    config = base()
    config["sweep"]["spiral_angles_deg"] = [30, 35]
    del config["speed_sweep"]
    problems = config_check.check_config(config, SCHEMA)
    assert sorted(calls) == [("circular", 30.0, 3), ("circular", 35.0, 3),
                             ("logarithmic", 30.0, 3), ("logarithmic", 35.0, 3)]
    assert problems == ["misalignment_map.range = 0.1 (E = 0.1, P = 0.1): the members interfere "
                        "(at circular 30 deg, circular 35 deg)"]
    config = base()
    config["sweep"]["spiral_angles_deg"] = [30, 35]
    config["misalignment_map"] = {**config["misalignment_map"], "steps": 7, "sweep_steps": 5}
    calls.clear()
    config_check.check_config(config, SCHEMA)
    assert {(spiral, steps) for _, spiral, steps in calls} == {(30.0, 5), (35.0, 7)}
    # a design point that fails the physics is not asked
    config = base()
    config["design"]["face_width_mm"] = 500
    calls.clear()
    assert_rejected(config_check.check_config(config, SCHEMA), "design.face_width_mm = 500")
    assert calls == []


def test_the_parse_time_check_runs_no_analysis_and_keeps_nothing(monkeypatch, tmp_path):
    """Without ``analyses`` (the workflow's parse, ``snakemake -n``) no TCA, FE section,
    rating or practice design runs; :func:`analysis_problems` (the workflow's onstart)
    names what they find; neither writes into lsbg's cache folder."""
    import lsbg.practice.checks
    import lsbg.rating.iso10300
    import lsbg.tca.checks
    import lsbg.tooth.config

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    config = with_value(base(), ("misalignment", "gear_axial_G_mm"), -0.5)
    config["sweep"]["contact_models"] = ["point", "line"]
    analysed = copy.deepcopy(config)
    for module, name in ((lsbg.tca.checks, "point_problems"),
                         (lsbg.tooth.config, "fillet_problem"),
                         (lsbg.rating.iso10300, "rate"),
                         (lsbg.practice.checks, "practice_problems")):
        monkeypatch.setattr(module, name, lambda *args, _n=name: pytest.fail(f"{_n} ran"))
    assert config_check.check_config(config, SCHEMA, analyses=False) == []
    monkeypatch.undo()
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert config_check.check_config(analysed, SCHEMA, analyses=False) == []
    assert_rejected(config_check.analysis_problems(analysed),
                    "misalignment.gear_axial_G_mm = -0.5")
    assert config_check.practice_analysis_problems(analysed) == []
    assert list(tmp_path.rglob("*.json")) == []


@pytest.mark.parametrize("names", [(), ("config-test.yaml",), ("config-speed.yaml",),
                                   ("config-optimise.yaml",), ("config-cells.yaml",),
                                   ("config-trace.yaml",)])
def test_shipped_configs_pass_with_the_schema_defaults_filled_in(names):
    config = load(*names)
    assert config_check.check_config(config, SCHEMA) == []
    # the full ease-off search (15 000 designs a trace) sets its own time limit
    full_search = names in (("config-optimise.yaml",), ("config-trace.yaml",))
    assert config["limits"] == {"geometry_minutes": 10, "tooth_minutes": 10,
                                "optimise_minutes": 15 if full_search else 10}
    assert config["contact"]["model"] == "point" and "slices" in config["contact"]


def test_defaults_are_those_snakemake_fills_in():
    from snakemake.utils import validate

    ours, theirs = base(), base()
    del ours["limits"], theirs["limits"], ours["simulation"], theirs["simulation"]
    config_check.fill_defaults(ours, SCHEMA)
    validate(theirs, str(REPO / "lsbg" / "schemas" / "config.schema.yaml"))
    assert ours == theirs


def test_a_number_yaml_reads_as_text_gets_a_hint():
    config = with_value(base(), ["simulation", "time_step_s"], "1e-6")
    problems = config_check.check_config(config, SCHEMA)
    assert_rejected(problems, "simulation.time_step_s")
    assert "1.0e-6" in problems[0]


def test_design_points_name_the_keys_that_ask_for_them():
    config = base()
    config["sweep"]["spiral_angles_deg"] = [30, 35.0]
    points = plan.design_points(config)
    assert list(points) == [("circular", "30"), ("circular", "35"), ("logarithmic", "30"),
                            ("logarithmic", "35")]
    assert points[("logarithmic", "35")] == [
        "paper_spiral_angle_deg", "speed_sweep.spiral_angle_deg", "sweep.spiral_angles_deg[1]"]


def test_geometry_cost_grows_with_the_teeth():
    small, large = (resources.geometry_cost(GearPair(GearPairDesign(gear_teeth=z)))
                    for z in (37, 3000))
    # the measured figures (geometry_cost's docstring): 0.29 GB, 3 s; 0.53 GB, 11 s
    assert 0.25 < small["memory_gb"] < 0.4 and small["minutes"] < 0.1
    assert 0.45 < large["memory_gb"] < 0.75 and 0.1 < large["minutes"] < 0.4
    assert large["vertices"][2] > 10 * small["vertices"][2]


# --------------------------------------------------------------- end to end
END_TO_END = {
    "YAML syntax error": ("design:\n  face_width_mm: [25\nsweep: {}\n", None),
    "physics": ("design:\n  face_width_mm: 500\n", "design.face_width_mm = 500"),
    "resource guard": ("design:\n  gear_teeth: 100000\n", "design.gear_teeth = 100000"),
    "same file name": ("sweep:\n  traces: [logarithmic]\n  spiral_angles_deg: [35, 35.0000001]\n",
                       "sweep.spiral_angles_deg[1] = 35.0000001"),
    "too few samples": ("simulation:\n  samples: 2\n", "simulation.samples = 2"),
    "even map steps": ("misalignment_map:\n  steps: 8\n", "misalignment_map.steps = 8"),
    "spiral angle twice": ("design:\n  spiral_angle_deg: 30\npaper_spiral_angle_deg: 35\n",
                           "design.spiral_angle_deg = 30: the study's design point"),
}


def dry_run(tmp_path, *args):
    proc = subprocess.run([sys.executable, "-m", "snakemake", "-n", "--snakefile",
                           REPO / "Snakefile", "--configfile", tmp_path / "bad.yaml", *args],
                          cwd=tmp_path, capture_output=True, text=True, timeout=600)
    return proc.returncode, proc.stdout + proc.stderr


@pytest.mark.parametrize("name", END_TO_END)
def test_snakemake_stops_before_any_job_with_one_clean_message(tmp_path, name):
    text, key = END_TO_END[name]
    (tmp_path / "bad.yaml").write_text(text, encoding="utf-8")
    returncode, output = dry_run(tmp_path)
    assert returncode != 0
    assert "Traceback" not in output and "common.smk" not in output, output
    # nothing was planned, run or written
    assert "Building DAG" not in output and "Job stats" not in output, output
    assert not (tmp_path / "results").exists() and not (tmp_path / "logs").exists()
    if key is None:
        # Snakemake reads a --configfile before the Snakefile: its message, without
        # the file and line, which --verbose adds (documented in the schema)
        assert "Config file is not valid JSON or YAML" in output, output
        returncode, verbose = dry_run(tmp_path, "--verbose")
        assert returncode != 0 and re.search(r'bad\.yaml", line 2', verbose), verbose
    else:
        assert "invalid configuration" in output and f"config key {key}" in output, output


def test_an_analysis_problem_stops_the_run_before_any_job(tmp_path):
    """What only a TCA finds is checked by the workflow's onstart, before the first job:
    one clean message naming the key; no job started, no log, no settings file left."""
    (tmp_path / "bad.yaml").write_text("misalignment:\n  gear_axial_G_mm: -0.5\n")
    proc = subprocess.run([sys.executable, "-m", "snakemake", "-j1", "--snakefile",
                           REPO / "Snakefile", "--configfile", REPO / "workflow" /
                           "config-test.yaml", tmp_path / "bad.yaml"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=600)
    output = proc.stdout + proc.stderr
    assert proc.returncode != 0
    assert "config key misalignment.gear_axial_G_mm = -0.5: the members interfere" in output
    assert "Traceback" not in output and "common.smk" not in output, output
    assert not re.search(r"^(local)?rule \w+:", output, re.M), output
    assert not (tmp_path / "logs").exists()
    assert [p for p in (tmp_path / "results").rglob("*") if p.is_file()] == []


def test_one_key_sets_the_studys_spiral_angle(tmp_path):
    """design.spiral_angle_deg in a study's file is its paper point and, unless the file
    lists the sweep's angles (it among them), its sweep; set apart from either, or a paper
    angle outside the sweep: refused, saying what to set."""
    given = {"design": {"spiral_angle_deg": 30}}
    config = merge_config(load(), given)
    assert config_check.check_config(config, SCHEMA, given=given) == []
    assert list(plan.design_points(config)) == [("circular", "30"), ("logarithmic", "30")]
    assert "spiral_angle_deg" not in config["design"] and config["paper_spiral_angle_deg"] == 30
    # with the sweep's angles too (30 among them): the paper's point of that sweep
    swept = merge_config(given, {"sweep": {"spiral_angles_deg": [30, 40]}})
    config = merge_config(load(), swept)
    assert config_check.check_config(config, SCHEMA, given=swept) == []
    assert (config["paper_spiral_angle_deg"], config["sweep"]["spiral_angles_deg"]) == (30, [30, 40])
    for also, problem in (({"paper_spiral_angle_deg": 35}, "design.spiral_angle_deg = 30: the "
                           "study's design point, and paper_spiral_angle_deg = 35 another; "
                           "remove paper_spiral_angle_deg"),
                          ({"sweep": {"spiral_angles_deg": [35]}}, "design.spiral_angle_deg = "
                           "30: not one of sweep.spiral_angles_deg = [35]; add 30 there, or "
                           "remove sweep.spiral_angles_deg for a study of that one angle")):
        twice = merge_config(given, also)
        assert config_check.check_config(merge_config(load(), twice), SCHEMA,
                                         given=twice) == [problem]
    # the former two keys of a study at 30 deg: the paper's angle alone is one more point
    config = merge_config(load(), {"sweep": {"spiral_angles_deg": [35]},
                                   "paper_spiral_angle_deg": 30})
    assert config_check.check_config(config, SCHEMA) == [
        "paper_spiral_angle_deg = 30: not one of sweep.spiral_angles_deg = [35]; for a study of "
        "that one angle set design.spiral_angle_deg: 30 instead of both keys, or add 30 to "
        "sweep.spiral_angles_deg"]
    # the workflow reads the study's own files: the test study at 30 deg plans 30 deg only
    (tmp_path / "at30.yaml").write_text("design:\n  spiral_angle_deg: 30\n")
    proc = subprocess.run([sys.executable, "-m", "snakemake", "-n", "--snakefile",
                           REPO / "Snakefile", "--configfile", REPO / "workflow" /
                           "config-test.yaml", tmp_path / "at30.yaml"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "_beta30" in proc.stdout and "_beta35" not in proc.stdout, proc.stdout


def test_a_configuration_file_with_a_key_twice_is_refused(tmp_path):
    from lsbg.files import duplicate_key_problems

    good, bad = tmp_path / "good.yaml", tmp_path / "bad.yaml"
    good.write_text("contact:\n  slices: 10\n")
    bad.write_text("contact:\n  slices: 10\n  model: line\n  slices: 30\n")
    assert duplicate_key_problems([good, tmp_path / "missing.yaml"]) == []
    (problem,) = duplicate_key_problems([good, bad])
    assert problem.endswith("bad.yaml: line 4: key 'contact.slices' again (first at line 2): "
                            "YAML would keep only the last")


def test_the_load_sweep_section_names_the_sweeps_entry_that_replaces_it():
    """The former extension is an instance of the sweeps: its section is refused with the
    entry to write instead, and that entry is valid as written."""
    config = {**load("config.yaml"), "load_sweep": {"torques_N_m": [1000, 3000],
                                                   "engine": "pybullet"}}
    (problem,) = config_check.check_config(copy.deepcopy(config), SCHEMA)
    assert problem.startswith("load_sweep: replaced by the sweeps section")
    suggested = problem.split("write instead", 1)[1].split("(results in")[0].strip()
    del config["load_sweep"]
    config.update(yaml.safe_load(suggested))
    assert config["sweeps"] == {"load": {"simulation.load_torque_N_m": [1000, 3000],
                                         "contact_model": "point", "engine": "pybullet"}}
    assert config_check.check_config(config, SCHEMA) == []
