"""One trace's optimisation from a configuration: the dataset holds what was computed."""

import numpy as np
import pytest

from lsbg.config import resolve_config
from lsbg.optimise.checks import run_settings
from lsbg.optimise.choice import chosen_modification
from lsbg.optimise.objectives import Evaluator
from lsbg.optimise.run import optimise_pair


def test_a_tiny_run_chooses_a_feasible_design(pairs):
    pair = pairs["circular"]
    config = resolve_config([], [
        "optimise.population=6", "optimise.generations=2", "optimise.phases=12",
        "optimise.edge_load_tolerance=1", "optimise.objectives=[transmission_error, mesh_loss]",
        "optimise.bounds.bias_um=[0, 0]", "optimise.bounds.spiral_angle_correction_um=[0, 0]",
        "optimise.bounds.pressure_angle_correction_um=[0, 0]",
        "optimise.bounds.lengthwise_crowning_um=[30, 45]",
        "optimise.bounds.profile_crowning_um=[10, 20]",
        "optimise.bounds.pinion_tip_relief_um=[10, 15]",
        "optimise.bounds.gear_tip_relief_um=[10, 15]",
        "misalignment_map.range=0.02", "flank_modification.lengthwise_crowning_um=25",
        "flank_modification.profile_crowning_um=5"])
    settings = run_settings(config, pair.design)
    ds = optimise_pair(pair, settings)
    assert ds.sizes["individual"] == 6 and ds.sizes["generation"] == 2
    assert ds.attrs["seed"] == 1 and ds.attrs["evaluations"] <= 12
    assert ds.attrs["rated_torque_N_m"] == pytest.approx(484.8, abs=0.5)
    assert ds.attrs["design_trace"] == "circular"
    # the shared design's figures are its evaluation
    reference = Evaluator(pair, settings["evaluation"]).evaluate(settings["reference"])
    assert float(ds["reference_transmission_error"]) == reference["transmission_error"]
    k = ds.attrs["chosen"]
    assert k >= 0 and ds["feasible"][k] == 1 and ds["front"][k] == 1
    chosen = chosen_modification(ds)
    again = Evaluator(pair, settings["evaluation"]).evaluate(chosen)
    assert again["transmission_error"] == pytest.approx(float(ds["transmission_error"][k]),
                                                        rel=1e-9)
    assert 30e-6 <= chosen.lengthwise_crowning <= 45e-6 and chosen.bias == 0.0
    assert np.all(np.diff(ds["evaluations"].values) >= 0)


def test_least_transmission_error_presses_no_harder_than_the_shared_design(pairs):
    """Its permissible pressure, by default, is the shared design's own in the same model."""
    pair = pairs["logarithmic"]
    config = resolve_config([], [
        "optimise.population=6", "optimise.generations=2", "optimise.phases=12",
        "optimise.edge_load_tolerance=1", "optimise.choice=least_transmission_error",
        "optimise.objectives=[transmission_error, contact_pressure]",
        "optimise.bounds.bias_um=[0, 0]", "optimise.bounds.spiral_angle_correction_um=[0, 0]",
        "optimise.bounds.pressure_angle_correction_um=[0, 0]",
        "optimise.bounds.lengthwise_crowning_um=[30, 45]",
        "optimise.bounds.profile_crowning_um=[0, 20]",
        "optimise.bounds.pinion_tip_relief_um=[0, 15]",
        "optimise.bounds.gear_tip_relief_um=[0, 15]", "misalignment_map.range=0.02"])
    ds = optimise_pair(pair, run_settings(config, pair.design))
    shared = float(ds["reference_contact_pressure"])
    assert ds.attrs["permissible_pressure_MPa"] == shared
    front = ds["front"].values == 1
    within = front & (ds["contact_pressure"].values <= shared)
    k = ds.attrs["chosen"]
    assert within.any()  # designs pressing no harder than the shared one exist here
    assert within[k]  # and the least TE among them is chosen
    assert ds["transmission_error"].values[k] == ds["transmission_error"].values[within].min()


def test_a_choice_that_fails_the_finer_edge_check_gives_way_to_the_next():
    from lsbg.optimise.choice import knee_point
    from lsbg.optimise.run import checked_choice
    from lsbg.optimise.search import Front
    from lsbg.optimise.space import DesignSpace

    space = DesignSpace.from_config({})
    values = np.array([[0.0, 10.0], [2.0, 3.0], [5.0, 1.5], [10.0, 0.0]])
    quantities = {"transmission_error": values[:, 0], "mesh_loss": values[:, 1]}
    x = np.linspace(0.1, 0.9, 4)[:, None] * np.ones((4, space.size))
    front = Front(x, quantities, ("transmission_error", "mesh_loss"), np.ones(4, bool),
                  np.ones(4, bool), np.zeros(1), np.zeros(1), np.zeros(1), 1, 4, 1, "nsga2", 0)
    knee = knee_point(values)

    class Finer:
        def edge_contact(self, modification):
            # the knee touches an edge between the quick check's positions
            knee_design = space.modification(x[knee])
            return 0.03 if modification.lengthwise_crowning == knee_design.lengthwise_crowning \
                else 0.0

    chosen, checked = checked_choice(Finer(), front, space, "knee", None)
    remaining = [k for k in range(4) if k != knee]
    assert chosen == remaining[knee_point(values[remaining])]
    assert checked[knee] == 0.03 and checked[chosen] == 0.0
    assert np.isnan(checked).sum() == 2


def _front_of(values, rated):
    from lsbg.optimise.search import Front
    from lsbg.optimise.space import DesignSpace

    space = DesignSpace.from_config({})
    n = len(values)
    quantities = {"transmission_error": values[:, 0], "mesh_loss": values[:, 1],
                  "rated_transmission_error": np.asarray(rated, float)}
    x = np.linspace(0.1, 0.9, n)[:, None] * np.ones((n, space.size))
    return space, x, Front(x, quantities, ("transmission_error", "mesh_loss"), np.ones(n, bool),
                           np.ones(n, bool), np.zeros(1), np.zeros(1), np.zeros(1), 1, n, 1,
                           "nsga2", 0)


def test_the_choice_is_made_among_the_members_below_the_shared_te():
    from lsbg.optimise.choice import knee_point
    from lsbg.optimise.run import checked_choice, choice_candidates

    values = np.array([[0.0, 10.0], [2.0, 3.0], [5.0, 1.5], [10.0, 0.0]])
    space, x, front = _front_of(values, [30.0, 40.0, 33.0, 31.0])
    assert knee_point(values) == 1  # the plain knee: 40 urad at the rated torque
    below = choice_candidates(front, "below_shared", 34.0)
    assert below.tolist() == [0, 2, 3]
    assert choice_candidates(front, "front", 34.0).tolist() == [0, 1, 2, 3]
    # none below: the whole front
    assert choice_candidates(front, "below_shared", 20.0).tolist() == [0, 1, 2, 3]
    with pytest.raises(ValueError, match="optimise.choose_from = 'nearest'"):
        choice_candidates(front, "nearest", 34.0)

    class Clean:
        def edge_contact(self, modification):
            return 0.0

    chosen, _ = checked_choice(Clean(), front, space, "knee", None, below)
    assert chosen == below[knee_point(values[below])] == 2

    class EdgesBelow:  # every candidate touches an edge: the rest of the front is tried
        def edge_contact(self, modification):
            return 0.05 if modification.lengthwise_crowning in [
                space.modification(x[k]).lengthwise_crowning for k in below] else 0.0

    chosen, checked = checked_choice(EdgesBelow(), front, space, "knee", None, below)
    assert chosen == 1
    assert checked[below].tolist() == [0.05] * 3
