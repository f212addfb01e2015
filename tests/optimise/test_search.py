"""NSGA-II on the ease-off: deterministic from its seed, two seeds' fronts alike."""

import numpy as np
import pytest

from lsbg.optimise.objectives import CONSTRAINTS, EvaluationSettings, Evaluator
from lsbg.optimise.search import (HYPERVOLUME_SCALES, hypervolume, merged_front, non_dominated,
                                  optimise)
from lsbg.optimise.space import DesignSpace

from tests.optimise.conftest import RATED, edge_radius

#: A small problem: lengthwise and profile crowning with fixed tip reliefs, two objectives,
#: the aligned pair only.
SMALL = {"bias_um": [0, 0], "spiral_angle_correction_um": [0, 0],
         "pressure_angle_correction_um": [0, 0], "pinion_tip_relief_um": [25, 25],
         "gear_tip_relief_um": [25, 25], "lengthwise_crowning_um": [20, 50],
         "profile_crowning_um": [0, 15]}
OBJECTIVES = ("transmission_error", "contact_pressure")


@pytest.fixture(scope="module")
def small(pairs):
    pair = pairs["logarithmic"]
    evaluator = Evaluator(pair, EvaluationSettings(rated_torque=RATED, phases=16,
                                                   edge_radius=edge_radius(pair.design)))
    return evaluator, DesignSpace.from_config(SMALL)


def test_hypervolume_by_hand():
    scales = np.array([HYPERVOLUME_SCALES[n] for n in OBJECTIVES])
    # normalised (0.5, 0.5) and (0.25, 0.75): 0.25 + 0.1875 - 0.125 under the point (1, 1)
    points = np.array([[0.5, 0.5], [0.25, 0.75], [1.2, 0.1]]) * scales
    assert hypervolume(points, OBJECTIVES) == pytest.approx(0.3125, rel=1e-12)
    assert hypervolume(points[:0], OBJECTIVES) == 0.0
    assert non_dominated([[1, 2], [2, 1], [2, 2], [1, 2]]).tolist() == [True, True, False, True]


def test_two_seeds_reach_the_same_hypervolume(small):
    evaluator, space = small
    fronts = [optimise(evaluator, space, OBJECTIVES, 16, 12, seed) for seed in (1, 2)]
    finals = [front.hypervolume[-1] for front in fronts]
    assert min(finals) > 0.1
    assert finals[0] == pytest.approx(finals[1], rel=0.02)
    for front in fronts:
        assert front.hypervolume.size == 12 and front.evaluations[-1] <= 16 * 12
        assert np.all(front.feasible[front.front])
        # the front's members are not dominated by any feasible individual
        values = front.values[front.feasible]
        assert np.all(non_dominated(values)[front.front[front.feasible]])


def test_merged_front_keeps_what_nothing_dominates():
    front = np.array([[1.0, 4.0], [2.0, 2.0], [4.0, 1.0]])
    candidates = np.array([[1.5, 1.5], [3.0, 3.0], [0.5, 5.0], [0.5, 5.0]])
    old, new = merged_front(front, candidates)
    assert old.tolist() == [True, False, True]  # (1.5, 1.5) dominates (2, 2)
    assert new.tolist() == [True, False, True, True]  # equal vectors dominate neither
    union = np.vstack([front, candidates])
    assert np.array_equal(np.concatenate([old, new]), non_dominated(union))
    assert merged_front(np.zeros((0, 2)), candidates)[1].tolist() == [True, False, True, True]


def test_the_front_is_every_feasible_design_evaluated_that_none_dominates(small):
    evaluator, space = small
    seen = []

    class Recording:
        def evaluate(self, modification):
            seen.append(evaluator.evaluate(modification))
            return seen[-1]

    front = optimise(Recording(), space, OBJECTIVES, 8, 4, 3)
    feasible = [q for q in seen if all(q[name] <= 0 for name in CONSTRAINTS)]
    values = np.array([[q[name] for name in OBJECTIVES] for q in feasible])
    expected = values[non_dominated(values)]
    found = front.values[front.front]
    assert sorted(map(tuple, found)) == sorted(map(tuple, expected))
    assert np.all(np.diff(front.hypervolume) >= 0)  # the archive never loses a design
    assert front.hypervolume[-1] == pytest.approx(hypervolume(expected, OBJECTIVES), rel=1e-12)
    assert front.population_member.sum() == 8 and np.all(front.population_member[:8])


def test_the_same_seed_gives_the_same_front(small):
    evaluator, space = small
    first, again = (optimise(evaluator, space, OBJECTIVES, 6, 2, 5) for _ in range(2))
    np.testing.assert_array_equal(first.x, again.x)
    np.testing.assert_array_equal(first.values, again.values)
    np.testing.assert_array_equal(first.hypervolume, again.hypervolume)


class Untouchable:
    def evaluate(self, modification):
        raise AssertionError("evaluated before the input was checked")


@pytest.mark.parametrize("objectives, algorithm, message", [
    (("transmission_error", "noise"), "nsga2", r"objectives = \['transmission_error', 'noise'\]"),
    (OBJECTIVES, "moead", "algorithm = 'moead'"),
])
def test_bad_input_is_refused_before_any_evaluation(objectives, algorithm, message):
    with pytest.raises(ValueError, match=message):
        optimise(Untouchable(), DesignSpace.from_config(SMALL), objectives, 8, 2, 1, algorithm)


def test_nsga3_runs_on_reference_directions(small):
    evaluator, space = small
    front = optimise(evaluator, space, OBJECTIVES, 8, 2, 1, algorithm="nsga3")
    assert front.algorithm == "nsga3" and front.x.shape[1] == space.size
    assert front.evaluations[-1] <= 16 and front.hypervolume.size == 2


def test_a_seeded_start_evaluates_the_shared_design_first_and_draws_the_rest_alike(small):
    evaluator, space = small
    shared = space.scaled(DesignSpace.from_config({}).modification(np.full(7, 0.5)))

    def first_generation(initial):
        seen = []

        class Recording:
            def evaluate(self, modification):
                seen.append(space.scaled(modification))
                return evaluator.evaluate(modification)

        optimise(Recording(), space, OBJECTIVES, 6, 1, 5, initial=initial)
        return np.array(seen)

    plain, seeded = first_generation(None), first_generation([shared])
    assert np.allclose(seeded[0], shared)  # the shared design is evaluated first
    assert np.array_equal(seeded[1:], plain[1:])  # the other places as without it
    assert not np.allclose(plain[0], shared)


def test_worker_processes_give_the_same_front(small):
    evaluator, space = small
    one = optimise(evaluator, space, OBJECTIVES, 8, 3, 4)
    two = optimise(evaluator, space, OBJECTIVES, 8, 3, 4, workers=2)
    assert np.array_equal(one.x, two.x)
    for name in one.quantities:
        assert np.array_equal(one.quantities[name], two.quantities[name], equal_nan=True), name
    assert np.array_equal(one.front, two.front)
    assert np.array_equal(one.hypervolume, two.hypervolume)
    with pytest.raises(ValueError, match="workers = 0: at least 1"):
        optimise(evaluator, space, OBJECTIVES, 8, 3, 4, workers=0)
