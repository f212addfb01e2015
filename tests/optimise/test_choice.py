"""The choice rules on hand-built fronts, and the chosen design read back."""

import numpy as np
import pytest

from lsbg.optimise.choice import choose, knee_point, least_transmission_error


def test_knee_is_the_least_sum_of_normalised_objectives():
    front = np.array([[0.0, 10.0], [2.0, 3.0], [5.0, 1.5], [10.0, 0.0]])
    # normalised: (0, 1), (0.2, 0.3), (0.5, 0.15), (1, 0): sums 1, 0.5, 0.65, 1
    assert knee_point(front) == 1
    # units do not matter, only each objective's range over the front
    assert knee_point(front * [1e3, 1e-3]) == 1


def test_knee_ignores_an_objective_the_front_does_not_vary_and_takes_the_first_tie():
    front = np.array([[1.0, 5.0, 3.0], [0.0, 5.0, 4.0], [0.5, 5.0, 3.5]])
    # normalised: (1, 0, 0), (0, 0, 1), (0.5, 0, 0.5): every sum 1, the first wins
    assert knee_point(front) == 0
    assert knee_point(front[:1]) == 0


def test_least_transmission_error_within_the_permissible_pressure():
    te, pressure = [10.0, 20.0, 30.0], [2000.0, 1400.0, 1000.0]
    assert least_transmission_error(te, pressure, 1500.0) == 1
    assert least_transmission_error(te, pressure, 3000.0) == 0
    # none within: the least pressure
    assert least_transmission_error(te, pressure, 900.0) == 2


def test_choose_by_name():
    values = np.array([[10.0, 2000.0, 1.0], [20.0, 1400.0, 1.0], [30.0, 1000.0, 1.0]])
    names = ("transmission_error", "contact_pressure", "mesh_loss")
    assert choose(values, names, "least_transmission_error", 1500.0) == 1
    assert choose(values, names, "knee") == knee_point(values)
    with pytest.raises(ValueError, match="optimise.choice = 'nearest'"):
        choose(values, names, "nearest")
    with pytest.raises(ValueError, match="needs the objectives"):
        choose(values[:, :1], names[:1], "least_transmission_error", 1500.0)
