"""The design space: bounds in micrometres, fixed variables, and every bad bound named."""

import numpy as np
import pytest

from lsbg.optimise.space import VARIABLES, DesignSpace, bounds_problems
from lsbg.tca.modification import FlankModification


def test_default_space_frees_the_coefficients_and_fixes_the_lengths():
    space = DesignSpace.from_config({})
    assert space.keys == tuple(k for k in VARIABLES if not k.endswith("_length"))
    assert space.fixed == {"pinion_tip_relief_length": 0.25, "gear_tip_relief_length": 0.25}
    low = space.modification(np.zeros(space.size))
    high = space.modification(np.ones(space.size))
    assert low.lengthwise_crowning == pytest.approx(10e-6)
    assert high.lengthwise_crowning == pytest.approx(50e-6)
    assert low.bias == pytest.approx(-10e-6) and high.gear_tip_relief == pytest.approx(30e-6)
    assert isinstance(low, FlankModification)


def test_scaled_inverts_modification_and_config_speaks_micrometres():
    space = DesignSpace.from_config({"bias_um": [0, 0], "gear_tip_relief_length": [0.1, 0.5]})
    x = np.linspace(0.1, 0.9, space.size)
    np.testing.assert_allclose(space.scaled(space.modification(x)), x, atol=1e-12)
    values = space.config_values(x)
    assert values["bias_um"] == 0 and "bias_um" not in space.keys
    assert 0.1 < values["gear_tip_relief_length"] < 0.5
    assert values["lengthwise_crowning_um"] == pytest.approx(10 + 40 * x[0])


@pytest.mark.parametrize("bounds, message", [
    ({"lengthwise_crowning_um": [60, 5]},
     "optimise.bounds.lengthwise_crowning_um = [60, 5]: the lower bound is above the upper"),
    ({"profile_crowning_um": [-5, 10]},
     "optimise.bounds.profile_crowning_um = [-5, 10]: must be >= 0 um"),
    ({"pinion_tip_relief_length": [0.0, 0.3]},
     "optimise.bounds.pinion_tip_relief_length = [0.0, 0.3]: a relief's length is a fraction"),
    ({"crowning_um": [1, 2]}, "optimise.bounds.crowning_um = [1, 2]: unknown key"),
    ({"bias_um": [1]}, "optimise.bounds.bias_um = [1]: must be [low, high]"),
])
def test_bad_bounds_are_named(bounds, message):
    assert bounds_problems(bounds)[0].startswith(message)
    with pytest.raises(ValueError) as error:
        DesignSpace.from_config(bounds)
    assert str(error.value).startswith(message)


def test_the_reliefs_lengths_are_the_shared_designs_own_unless_bounded():
    # the practice design's "long" relief: a search at 0.25 could not reach it
    shared = FlankModification(pinion_tip_relief=26.6e-6, gear_tip_relief=26.6e-6,
                               pinion_tip_relief_length=0.137, gear_tip_relief_length=0.2)
    space = DesignSpace.from_config({}, shared)
    assert space.fixed == {"pinion_tip_relief_length": 0.137, "gear_tip_relief_length": 0.2}
    assert space.modification(np.full(space.size, 0.5)).pinion_tip_relief_length == 0.137
    free = DesignSpace.from_config({"gear_tip_relief_length": [0.1, 0.3]}, shared)
    assert "gear_tip_relief_length" in free.keys
    assert free.fixed == {"pinion_tip_relief_length": 0.137}


def test_a_space_with_every_variable_fixed_is_refused():
    fixed = {key: [spec[2][0] if spec[2] else 0.25] * 2 for key, spec in VARIABLES.items()}
    with pytest.raises(ValueError, match=r"^optimise.bounds = .*every variable is fixed"):
        DesignSpace.from_config(fixed)
