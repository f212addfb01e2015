"""The optimise section: every bad input named, with its value, before any evaluation."""

import math

import pytest

from lsbg.config import ConfigError, resolve_config
from lsbg.gear.design import GearPairDesign
from lsbg.optimise.checks import (evaluation_seconds, optimise_problems, rated_torque,
                                  run_settings)
from lsbg.rating.config import rate_design

DESIGN = GearPairDesign.from_units(module_mm=4.5, spiral_angle_deg=35, trace="logarithmic")


def config(*overrides):
    return resolve_config([], list(overrides))


def first_problem(*overrides):
    with pytest.raises(ValueError) as error:
        run_settings(config(*overrides), DESIGN)
    return str(error.value)


def test_the_defaults_pass_and_read_as_lsbgs_objects():
    assert optimise_problems(config()) == []
    settings = run_settings(config("flank_modification.lengthwise_crowning_um=25"), DESIGN)
    evaluation = settings["evaluation"]
    assert settings["objectives"] == ("transmission_error", "pattern_movement",
                                      "contact_pressure", "mesh_loss")
    assert settings["population"] * settings["generations"] == 360
    assert evaluation.torques.tolist() == pytest.approx([0.5 * evaluation.rated_torque,
                                                         evaluation.rated_torque,
                                                         1.5 * evaluation.rated_torque])
    assert len(evaluation.corners) == 4 and evaluation.phases == 24
    assert evaluation.lubricant.kinematic_viscosity == pytest.approx(150e-6)
    assert evaluation.lubricant.roughness == pytest.approx(8e-6 / 6)
    assert evaluation.pinion_speed == pytest.approx(math.radians(7703))
    assert settings["reference"].lengthwise_crowning == pytest.approx(25e-6)
    assert settings["permissible_pressure"] is None  # the shared design's, once evaluated
    assert run_settings(config("optimise.permissible_pressure_MPa=1500"),
                        DESIGN)["permissible_pressure"] == 1500


def test_rated_torque_is_where_iso_10300s_contact_safety_is_one():
    torque = rated_torque(DESIGN, config())
    assert torque == pytest.approx(484.8, abs=0.5)
    rating = rate_design(DESIGN, {}, {}, torque, math.radians(7703))[0]
    assert min(rating.contact_safety) == pytest.approx(1.0, rel=1e-6)
    assert rated_torque(DESIGN, config("optimise.rated_torque_N_m=300")) == 300.0


def test_reversed_bounds_are_named():
    assert first_problem("optimise.bounds.lengthwise_crowning_um=[60, 5]").startswith(
        "optimise.bounds.lengthwise_crowning_um = [60, 5]: the lower bound is above the upper")


def test_an_empty_design_space_is_named():
    fixed = [f"optimise.bounds.{key}=[{v}, {v}]" for key, v in (
        ("lengthwise_crowning_um", 25), ("profile_crowning_um", 5), ("bias_um", 0),
        ("spiral_angle_correction_um", 0), ("pressure_angle_correction_um", 0),
        ("pinion_tip_relief_um", 0), ("gear_tip_relief_um", 0))]
    assert "every variable is fixed (equal bounds): nothing to optimise" in first_problem(*fixed)


def test_an_unknown_objective_is_named():
    # the schema names it on the command line ...
    with pytest.raises(ConfigError, match=r"optimise.objectives\[1\]: 'noise' is not one of"):
        config("optimise.objectives=[transmission_error, noise]")
    # ... and lsbg's own check in a configuration that skipped the schema
    settings = config()
    settings["optimise"]["objectives"] = ["transmission_error", "noise"]
    with pytest.raises(ValueError, match=r"^optimise.objectives = \['transmission_error', "
                                         r"'noise'\]: 'noise' is not an objective"):
        run_settings(settings, DESIGN)


def test_a_budget_beyond_the_limit_is_named():
    message = first_problem("optimise.population=400", "optimise.generations=100")
    assert message.startswith("optimise.population = 400, optimise.generations = 100: 40000 "
                              "evaluations of each trace, about ")
    assert message.endswith("more than limits.optimise_minutes = 10")
    seconds = evaluation_seconds(config())
    assert 0.02 < seconds < 0.08
    # the full budget of workflow/config-optimise.yaml fits its own limit, not the default
    full = ("optimise.population=100", "optimise.generations=150")
    assert first_problem(*full).endswith("more than limits.optimise_minutes = 10")
    assert optimise_problems(config(*full, "limits.optimise_minutes=15")) == []
    # on four cores (optimise.workers) a quarter of the time: 40000 designs then fit 15 min
    big = ("optimise.population=400", "optimise.generations=100", "limits.optimise_minutes=15")
    assert "on one core" in first_problem(*big)
    assert optimise_problems(config(*big, "optimise.workers=4")) == []
    assert "on 2 cores (optimise.workers)" in first_problem(*big[:2], "optimise.workers=2")


def test_a_friction_law_outside_its_roughness_and_a_rule_without_its_objectives():
    assert first_problem("optimise.friction_law=benedict_kelley").startswith(
        "rating.flank_roughness_um = 8: Benedict & Kelley's roughness factor needs Ra < 1.27 um")
    assert optimise_problems(config("optimise.friction_law=benedict_kelley",
                                    "optimise.flank_roughness_Ra_um=0.4")) == []
    assert first_problem("optimise.choice=least_transmission_error",
                         "optimise.objectives=[transmission_error, mesh_loss]").startswith(
        "optimise.choice = 'least_transmission_error': needs the objectives transmission_error "
        "and contact_pressure")
