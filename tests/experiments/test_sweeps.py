"""Parameter sweeps from the configuration (lsbg.experiments.sweeps): points, names, batches, checks."""

import copy
from pathlib import Path

import pytest
import yaml

from lsbg.study import checks as config_check
from lsbg.study.sweep_checks import MAX_SWEEP_RUNS
from lsbg.experiments.sweeps import sweeps_from_config

REPO = Path(__file__).resolve().parents[2]
SCHEMA = yaml.safe_load((REPO / "lsbg" / "schemas" / "config.schema.yaml").read_text())


def merged(*names):
    config = {}
    for name in names:
        _merge(config, yaml.safe_load((REPO / "workflow" / name).read_text()))
    return config


def _merge(base, extra):
    for key, value in extra.items():
        if isinstance(value, dict) and isinstance(base.get(key), dict):
            _merge(base[key], value)
        else:
            base[key] = value
    return base


@pytest.fixture(scope="module")
def study():
    return merged("config.yaml", "config-test.yaml")


def problems(study, sweeps):
    return config_check.check_config({**copy.deepcopy(study), "sweeps": sweeps}, SCHEMA)


def test_the_shipped_example_is_valid_and_makes_its_points(study):
    config = _merge(copy.deepcopy(study), merged("config-sweep-example.yaml"))
    assert config_check.check_config(config, SCHEMA) == []
    friction, grid = sweeps_from_config(config)
    assert friction.kind == "values" and len(friction.points) == 5
    assert friction.patterns()[1] == "dynamic_friction~0.05"
    assert friction.batches() == [[0, 1, 2, 3, 4]]
    assert grid.kind == "product" and len(grid.points) == 9
    assert grid.points[3] == {"contact.mesh_damping_ratio": 0.05,
                              "contact.line_stiffness_N_per_mm_um": 10}
    assert grid.batches() == [[0, 1, 2, 3, 4], [5, 6, 7, 8]]
    assert (friction.traces, friction.spiral_angles) == (("logarithmic", "circular"), (35.0,))
    assert (friction.contact_model, friction.engine) == ("line", "compiled")


def test_points_are_named_safely_and_apart(study):
    (sweep,) = sweeps_from_config({**study, "sweeps": {"s": {
        "misalignment.offset_E_mm": [-0.05, 0.0, 0.1, 0.1000001]}}})
    names = sweep.patterns()
    assert names == ["offset_E_mm~-0.05", "offset_E_mm~0.0", "offset_E_mm~0.1",
                     "offset_E_mm~0.1000001"]
    (combo,) = sweeps_from_config({**study, "sweeps": {"c": {"combinations": [
        {"contact.slices": 10, "design.face_width_mm": 20},
        {"contact.slices": 30, "design.face_width_mm": 25}]}}})
    assert combo.kind == "combinations" and combo.columns == ["slices", "face_width_mm"]
    assert combo.patterns() == ["slices~10_face_width_mm~20", "slices~30_face_width_mm~25"]


@pytest.mark.parametrize("sweeps, message", [
    ({"s": {"contact.nosuch": [1]}}, "sweeps.s.contact.nosuch: unknown key (known in contact:"),
    ({"s": {"design.spiral_angle_deg": [30, 35]}},
     "sweeps.s.design.spiral_angle_deg: cannot be swept (a coordinate of every design point"),
    ({"s": {"flank_modification.topography_file": ["a.csv"]}},
     "sweeps.s.flank_modification.topography_file: cannot be swept (a file path"),
    ({"s": {"statistics.subgroup_size": [4]}},
     "sweeps.s.statistics.subgroup_size: the 'statistics' section cannot be swept"),
    ({"s": {"contact.dynamic_friction": []}}, "sweeps.s.contact.dynamic_friction: [] should be "
                                              "non-empty"),
    ({"s": {"contact.dynamic_friction": [0, -0.05]}},
     "sweeps.s: point 1 (contact.dynamic_friction = -0.05): contact.dynamic_friction: -0.05 is "
     "less than the minimum of 0"),
    ({"s": {"contact.slices": [10, 10.0]}}, "sweeps.s: points 0 (contact.slices = 10) and 1 "
                                            "(contact.slices = 10.0) are the same point"),
    ({"s": {"design.face_width_mm": [25, 500]}},
     "sweeps.s: point 1 (design.face_width_mm = 500): design.face_width_mm = 500: exceeds half "
     "the outer cone distance"),
    ({"s": {"simulation.load_torque_N_m": [1000, 1e12]}},
     "point 1 (simulation.load_torque_N_m = 1000000000000.0): simulation.load_torque_N_m = "
     "1000000000000.0: the gear's peak torque"),
    ({"s": {"contact.mesh_damping_ratio": [0.1], "contact.slices": [10]}},
     "sweeps.s: contact.mesh_damping_ratio, contact.slices: several keys: put them under "
     "product"),
    ({"s": {"combinations": [{"contact.slices": 10}, {"contact.dynamic_friction": 0.1}]}},
     "sweeps.s: combinations[0]: lacks contact.dynamic_friction"),
    ({"s": {"contact.slices": [10], "spiral_angles_deg": [33]}},
     "sweeps.s.spiral_angles_deg = [33]: 33 (logarithmic) is not a design point of the study"),
    ({"s": {"product": {"contact.slices": list(range(10, 90)),
                        "contact.dynamic_friction": [i / 100 for i in range(40)]}}},
     f"more than the resource guard's {MAX_SWEEP_RUNS}"),
])
def test_bad_sweeps_are_named_before_any_job(study, sweeps, message):
    found = problems(study, sweeps)
    assert any(message in line for line in found), found
