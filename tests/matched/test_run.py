"""The matched designs of two converged fronts (lsbg.matched.run) on constructed datasets."""

import numpy as np
import xarray as xr

from lsbg.matched import run
from lsbg.optimise.fronts import converged_front_dataset

OBJECTIVES = ["transmission_error", "pattern_movement", "contact_pressure"]


def converged(trace, pattern, pressure, kept, seeds=None):
    n = len(pattern)
    values = {"transmission_error": np.full(n, 40.0), "pattern_movement": np.array(pattern),
              "contact_pressure": np.array(pressure)}
    result = {"seed": np.array(seeds or [1] * n), "individual": np.arange(n),
              "search": values, "converged": values, "edge_load": np.zeros(n),
              "kept": np.array(kept, bool), "seeds": sorted(set(seeds or [1])), "positions": 24}
    return converged_front_dataset(result, OBJECTIVES, {"design_trace": trace})


def box():
    return xr.Dataset({"box_low_pattern_movement": 2.0, "box_high_pattern_movement": 4.0,
                       "box_low_contact_pressure": 1000.0, "box_high_contact_pressure": 2000.0})


def test_pairs_of_kept_members_within_the_caliper():
    # LSBG: member 1 not kept, members 2 and 3 the same design (two seeds' shared one)
    lsbg = converged("logarithmic", [2.0, 2.5, 3.0, 3.0, 3.9], [2000, 1500, 1500, 1500, 1000],
                     [1, 0, 1, 1, 1], seeds=[1, 1, 1, 2, 2])
    # SBG: member 0 matches LSBG 0 (0.01 in pattern), member 1 LSBG 2 (0.02 in pressure);
    # member 2 nowhere near
    sbg = converged("face_milled", [2.02, 3.0, 2.0], [2000, 1520, 1000], [1, 1, 1])
    out = run.matched_designs((lsbg, sbg), run.box_of(box()), caliper=0.05)
    assert out["candidates"].tolist() == [3, 3]      # 0, 2, 4 of the LSBG
    assert out["member"].tolist() == [[0, 0], [2, 1]]
    assert np.allclose(out["distance"], [0.01, 0.02])
    assert out["assigned"] == 3 and out["dropped"] == 1
    none = run.matched_designs((converged("logarithmic", [], [], []), sbg),
                               run.box_of(box()), 0.05)
    assert none["member"].shape == (0, 2) and none["candidates"].tolist() == [0, 3]


def test_log_ratios_and_their_statistics_per_column():
    rng = np.random.default_rng(1)
    std = np.ones((12, 2, 2, 2, 2))
    # the SBG's std 20 % above the LSBG's in the first boundary, 20 % below in the second
    std[:, 1, :, 0] = 1.2 + 0.01 * rng.standard_normal((12, 2, 2))
    std[:, 1, :, 1] = 0.8 + 0.01 * rng.standard_normal((12, 2, 2))
    ratios = run.log_ratios(std)
    assert ratios.shape == (12, 2, 2, 2)
    stats = run.ratio_statistics(ratios)
    assert np.all(stats["mean"][:, 0] > 0) and np.all(stats["mean"][:, 1] < 0)
    assert np.all(stats["wilcoxon_p"] < 1e-3) and np.all(stats["pairs"] == 12)
