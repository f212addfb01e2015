"""``lsbg matched-pairs``' work (lsbg.matched.stage) on one constructed pair of real designs:
every answer computed, finite, and the proxy within its stated error of the full runs."""

import numpy as np
import pytest
import xarray as xr

from lsbg.matched.stability import BOUNDARIES
from tests.matched.test_run import converged
from tests.matched.test_stability import PROXY_ERROR

TRACES = ("logarithmic", "circular")
#: A short run and a coarse tooth (the tiny study's run; the FE mesh at its coarsest).
SETTINGS = ["simulation.duration_s=0.05", "simulation.samples=25", "simulation.ramp_time_s=0.01",
            "simulation.full_rate_hz=50000", "simulation.full_rate_after_s=0.01",
            "statistics.steady_state_after_s=0.01",
            "statistics.control_chart_window_s=[0.01, 0.05]",
            "tooth.element_size_module=0.52", "tooth.rim_element_factor=10",
            "optimise.matched.full_runs=1"]


def front(trace):
    """A search's front of one individual: a crowned ease-off (um, the variables' units)."""
    from lsbg.optimise.space import VARIABLES

    values = {"lengthwise_crowning_um": 30.0, "profile_crowning_um": 5.0,
              "pinion_tip_relief_length": 0.2, "gear_tip_relief_length": 0.2}
    data = {field: ("individual", [values.get(key, 0.0)],
                    {"units": "1" if scale == 1.0 else "um"})
            for key, (field, scale, *_) in VARIABLES.items()}
    return xr.Dataset(data, attrs={"design_trace": trace, "seed": 1})


@pytest.mark.slow
def test_one_pair_answered(tmp_path):
    from lsbg.config import resolve_config
    from lsbg.files import write_dataset
    from lsbg.gear.design import GearPairDesign
    from lsbg.matched.stage import answer_pairs
    from lsbg.solid.export import write_geometry

    settings = resolve_config((), SETTINGS)
    geometry = []
    for trace in TRACES:
        geometry.append(tmp_path / trace)
        write_geometry(GearPairDesign(trace=trace), geometry[-1], step=False)
    fronts = [front(t) for t in TRACES]
    sets = [converged(t, [3.0], [1500.0], [1]) for t in TRACES]
    matched = {"member": np.array([[0, 0]]), "distance": np.zeros(1),
               "candidates": np.array([1, 1]), "assigned": 1, "dropped": 0}
    releases = [xr.Dataset(attrs={"fe_aligned_positions": 8}) for _ in TRACES]
    ds = answer_pairs(settings, geometry, releases,
                      [tmp_path / f"{t}_compliance.nc" for t in TRACES], matched, sets, fronts)
    std = np.stack([ds[f"std_{q}"].values for q in ds["quantity"].values], axis=-1)
    assert ds["std_gear_speed"].attrs["units"] == "deg/s"
    assert np.all(np.isfinite(std)) and np.all(std > 0)
    for b, boundary in enumerate(BOUNDARIES):
        for q, quantity in enumerate(ds["quantity"].values):
            error = ds["proxy_error"].values[0, :, b, q]
            assert np.all(np.abs(error) <= PROXY_ERROR[str(quantity)]), (boundary, error)
    for name in ("contact_pressure", "root_stress_gear", "transmission_error"):
        assert np.all(ds[f"fe_{name}"].values > 0)
    assert ds.attrs["full_run_pairs"] == 1 and ds.attrs["indicative"] == 1
    assert int(ds["ratio_pairs"].values.min()) == 1
    write_dataset(ds, tmp_path / "matched_pairs.nc")
