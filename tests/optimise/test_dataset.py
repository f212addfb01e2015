"""The front's dataset: CF attributes, the history, the chosen design back."""

import numpy as np
import pytest
import xarray as xr

from lsbg.files import LABEL_WIDTH, write_dataset
from lsbg.optimise.choice import chosen_modification
from lsbg.optimise.dataset import front_dataset
from lsbg.optimise.objectives import QUANTITIES
from lsbg.optimise.search import Front
from lsbg.optimise.space import DesignSpace


@pytest.fixture()
def front():
    rng = np.random.default_rng(0)
    n = 5
    quantities = {name: rng.uniform(0.5, 2.0, n) for name in QUANTITIES}
    feasible = np.array([True, True, False, True, False])
    for name in ("edge_contact", "edge_load", "pattern_margin", "relief_backlash",
                 "contact_lost"):
        quantities[name] = np.where(feasible, -1.0, 1.0)
    return Front(rng.uniform(size=(n, 7)), quantities, ("transmission_error", "mesh_loss"),
                 feasible, feasible & (np.arange(n) != 3), np.array([0.0, 0.1, 0.2]),
                 np.array([0, 2, 4]), np.array([5, 10, 15]), 7, 5, 3, "nsga2", 1.5)


def test_dataset_is_cf_annotated_and_reads_back(front, tmp_path):
    space = DesignSpace.from_config({})
    reference = {name: 1.0 for name in QUANTITIES}
    ds = front_dataset(front, space, 1, reference, {"design_trace": "circular"})
    for name, variable in ds.variables.items():
        if name in ("individual", "generation"):
            continue
        assert "units" in variable.attrs and "long_name" in variable.attrs, name
        assert len(variable.attrs["long_name"]) <= LABEL_WIDTH
    assert ds.attrs["Conventions"] == "CF-1.11" and ds.attrs["chosen"] == 1
    assert ds.attrs["seed"] == 7 and ds.attrs["population"] == 5 and ds.attrs["generations"] == 3
    assert ds.attrs["evaluations"] == 15
    # the last population's feasible designs, beside every feasible design kept
    assert ds.attrs["population_feasible_individuals"] == 4
    assert ds.attrs["feasible_individuals"] == 3
    assert ds.attrs["objectives"] == "transmission_error mesh_loss"
    assert ds["transmission_error"].attrs["role"] == "objective"
    assert ds["edge_contact"].attrs["role"] == "constraint"
    assert ds["lengthwise_crowning"].attrs["units"] == "um"
    assert ds["gear_tip_relief_length"].attrs["units"] == "1"
    np.testing.assert_array_equal(ds["chosen"].values, [0, 1, 0, 0, 0])
    np.testing.assert_array_equal(ds["hypervolume"].values, front.hypervolume)
    path = tmp_path / "front.nc"
    write_dataset(ds, path)
    with xr.open_dataset(path) as stored:
        chosen = chosen_modification(stored.load())
    expected = space.modification(front.x[1])
    for field in ("lengthwise_crowning", "profile_crowning", "bias", "gear_tip_relief",
                  "pinion_tip_relief_length"):
        assert getattr(chosen, field) == pytest.approx(getattr(expected, field), rel=1e-12,
                                                       abs=1e-18)


def test_a_front_without_a_feasible_design_chooses_none(front):
    ds = front_dataset(front, DesignSpace.from_config({}), -1,
                       {name: 1.0 for name in QUANTITIES})
    with pytest.raises(ValueError, match="no feasible design"):
        chosen_modification(ds)
